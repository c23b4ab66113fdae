#include "tsgraphs/pipeline/prefilter.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace tsgraphs::pipeline {
namespace {

struct VoxelSum {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double intensity = 0.0;
  std::uint32_t label = 0;
  std::uint32_t count = 0;
};

// 21 bits per axis: +-1e6 voxels, far beyond any LiDAR range at useful voxel sizes.
std::uint64_t voxel_key(const Eigen::Vector3f& p, double inv_size) {
  constexpr std::int64_t kOffset = 1 << 20;
  constexpr std::uint64_t kMask = (1u << 21) - 1;
  auto axis = [&](float v) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v * inv_size)) + kOffset) & kMask;
  };
  return axis(p.x()) | (axis(p.y()) << 21) | (axis(p.z()) << 42);
}

}  // namespace

PointCloud prefilter(const PointCloud& scan, const PrefilterConfig& config, std::size_t* num_non_finite) {
  const bool with_intensity = scan.has_intensity(), with_labels = scan.has_labels();
  const double min2 = config.min_range * config.min_range, max2 = config.max_range * config.max_range;
  std::size_t non_finite = 0;

  PointCloud out;
  if (config.voxel_size <= 0.0) {
    out.reserve(scan.size(), with_intensity, with_labels);
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const Eigen::Vector3f& p = scan.points[i];
      if (!p.allFinite()) { ++non_finite; continue; }
      const double r2 = p.squaredNorm();
      if (r2 < min2 || r2 > max2) continue;
      out.points.push_back(p);
      if (with_intensity) out.intensity.push_back(scan.intensity[i]);
      if (with_labels) out.labels.push_back(scan.labels[i]);
    }
  } else {
    const double inv = 1.0 / config.voxel_size;
    std::unordered_map<std::uint64_t, std::uint32_t> index;  // voxel -> slot in `voxels`
    index.reserve(scan.size() / 2);
    std::vector<VoxelSum> voxels;
    voxels.reserve(scan.size() / 2);
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const Eigen::Vector3f& p = scan.points[i];
      if (!p.allFinite()) { ++non_finite; continue; }
      const double r2 = p.squaredNorm();
      if (r2 < min2 || r2 > max2) continue;
      const auto [it, fresh] = index.emplace(voxel_key(p, inv), static_cast<std::uint32_t>(voxels.size()));
      if (fresh) {
        voxels.emplace_back();
        if (with_labels) voxels.back().label = scan.labels[i];
      }
      VoxelSum& v = voxels[it->second];
      v.sum += p.cast<double>();
      if (with_intensity) v.intensity += scan.intensity[i];
      ++v.count;
    }
    out.reserve(voxels.size(), with_intensity, with_labels);
    for (const VoxelSum& v : voxels) {
      out.points.push_back((v.sum / v.count).cast<float>());
      if (with_intensity) out.intensity.push_back(static_cast<float>(v.intensity / v.count));
      if (with_labels) out.labels.push_back(v.label);
    }
  }
  if (num_non_finite) *num_non_finite = non_finite;
  return out;
}

}  // namespace tsgraphs::pipeline
