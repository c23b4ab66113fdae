#include "tsgraphs/core/voxel_grid.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace tsgraphs {
namespace {

struct VoxelSum {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double intensity = 0.0;
  std::uint32_t label = 0;
  std::uint32_t count = 0;
};

// Open-addressing voxel -> slot table, reused between calls: a node-based map costs one
// allocation per voxel, which dominated the prefilter on 64k-point scans.
class VoxelTable {
 public:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  void reset(std::size_t num_points) {
    std::size_t capacity = 16;
    while (capacity < 2 * num_points) capacity *= 2;
    keys_.assign(capacity, kEmpty);
    slots_.resize(capacity);
    mask_ = capacity - 1;
  }
  /// The slot of `key`, or `fresh` (inserted) when it is new; `inserted` says which.
  std::uint32_t find_or_insert(std::uint64_t key, std::uint32_t fresh, bool* inserted) {
    std::size_t i = (key * 0x9E3779B97F4A7C15ULL) >> 20 & mask_;
    while (true) {
      if (keys_[i] == key) {
        *inserted = false;
        return slots_[i];
      }
      if (keys_[i] == kEmpty) {
        keys_[i] = key;
        slots_[i] = fresh;
        *inserted = true;
        return fresh;
      }
      i = (i + 1) & mask_;
    }
  }

 private:
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> slots_;
  std::size_t mask_ = 0;
};

}  // namespace

PointCloud voxel_downsample(const PointCloud& scan, double voxel_size, double min_range, double max_range,
                            std::size_t* num_non_finite) {
  const bool with_intensity = scan.has_intensity(), with_labels = scan.has_labels();
  const double min2 = min_range * min_range, max2 = max_range * max_range;
  std::size_t non_finite = 0;
  // A point is kept when finite (the others are counted) and within the range band.
  const auto in_band = [&](const Eigen::Vector3f& p) {
    if (!p.allFinite()) {
      ++non_finite;
      return false;
    }
    const double r2 = p.squaredNorm();
    return r2 >= min2 && r2 <= max2;
  };

  PointCloud out;
  if (voxel_size <= 0.0) {
    out.reserve(scan.size(), with_intensity, with_labels);
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const Eigen::Vector3f& p = scan.points[i];
      if (!in_band(p)) continue;
      out.points.push_back(p);
      if (with_intensity) out.intensity.push_back(scan.intensity[i]);
      if (with_labels) out.labels.push_back(scan.labels[i]);
    }
  } else {
    const double inv = 1.0 / voxel_size;
    thread_local VoxelTable index;  // voxel -> slot in `voxels`
    index.reset(scan.size());
    std::vector<VoxelSum> voxels;
    voxels.reserve(scan.size() / 2);
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const Eigen::Vector3f& p = scan.points[i];
      if (!in_band(p)) continue;
      bool fresh = false;
      const std::uint32_t slot =
          index.find_or_insert(voxel_key(p, inv), static_cast<std::uint32_t>(voxels.size()), &fresh);
      if (fresh) {
        voxels.emplace_back();
        if (with_labels) voxels.back().label = scan.labels[i];
      }
      VoxelSum& v = voxels[slot];
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

}  // namespace tsgraphs
