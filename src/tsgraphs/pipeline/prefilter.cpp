#include "tsgraphs/pipeline/prefilter.hpp"

#include <algorithm>

#include "tsgraphs/core/voxel_grid.hpp"

namespace tsgraphs::pipeline {

PointCloud prefilter(const PointCloud& scan, const PrefilterConfig& config, std::size_t* num_non_finite) {
  return voxel_downsample(scan, config.voxel_size, config.min_range, config.max_range, num_non_finite);
}

bool has_finite_point(const PointCloud& scan) {
  return std::any_of(scan.points.begin(), scan.points.end(), [](const Eigen::Vector3f& p) { return p.allFinite(); });
}

}  // namespace tsgraphs::pipeline
