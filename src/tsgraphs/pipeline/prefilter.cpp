#include "tsgraphs/pipeline/prefilter.hpp"

#include "tsgraphs/core/voxel_grid.hpp"

namespace tsgraphs::pipeline {

PointCloud prefilter(const PointCloud& scan, const PrefilterConfig& config, std::size_t* num_non_finite) {
  return voxel_downsample(scan, config.voxel_size, config.min_range, config.max_range, num_non_finite);
}

}  // namespace tsgraphs::pipeline
