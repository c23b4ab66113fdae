#include "tsgraphs/odometry/voxel_hash_map.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace tsgraphs::odometry {
namespace {
constexpr int kAxisBits = 21;
constexpr std::int64_t kAxisOffset = std::int64_t{1} << (kAxisBits - 1);
constexpr std::uint64_t kAxisMask = (std::uint64_t{1} << kAxisBits) - 1;
}  // namespace

std::uint64_t VoxelHashMap::pack(const VoxelIndex& v) {
  auto axis = [](int c) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(c) + kAxisOffset) & kAxisMask; };
  return axis(v.x()) | axis(v.y()) << kAxisBits | axis(v.z()) << (2 * kAxisBits);
}

VoxelIndex VoxelHashMap::unpack(std::uint64_t key) {
  auto axis = [&](int shift) {
    return static_cast<int>(static_cast<std::int64_t>((key >> shift) & kAxisMask) - kAxisOffset);
  };
  return VoxelIndex(axis(0), axis(kAxisBits), axis(2 * kAxisBits));
}

VoxelHashMap::VoxelHashMap(double voxel_size, std::size_t max_points_per_voxel)
    : voxel_size_(voxel_size), inv_voxel_size_(1.0 / voxel_size), max_points_per_voxel_(max_points_per_voxel) {
  if (!(voxel_size > 0.0) || !std::isfinite(voxel_size)) {
    throw std::invalid_argument("VoxelHashMap: voxel_size must be positive and finite");
  }
  if (max_points_per_voxel < 1) throw std::invalid_argument("VoxelHashMap: max_points_per_voxel must be >= 1");
}

VoxelIndex VoxelHashMap::voxel_of(const Eigen::Vector3d& p) const {
  return VoxelIndex(static_cast<int>(std::floor(p.x() * inv_voxel_size_)),
                    static_cast<int>(std::floor(p.y() * inv_voxel_size_)),
                    static_cast<int>(std::floor(p.z() * inv_voxel_size_)));
}

Eigen::Vector3d VoxelHashMap::voxel_centre(const VoxelIndex& v) const {
  return (v.cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_size_;
}

const std::vector<Eigen::Vector3d>& VoxelHashMap::voxel_points(const VoxelIndex& v) const {
  static const std::vector<Eigen::Vector3d> kNone;
  const auto it = voxels_.find(pack(v));
  return it == voxels_.end() ? kNone : it->second;
}

void VoxelHashMap::add_points(const std::vector<Eigen::Vector3d>& points) {
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    std::vector<Eigen::Vector3d>& voxel = voxels_[pack(voxel_of(p))];
    if (voxel.size() < max_points_per_voxel_) {
      if (voxel.empty()) voxel.reserve(max_points_per_voxel_);
      voxel.push_back(p);
    }
  }
}

void VoxelHashMap::remove_far(const Eigen::Vector3d& origin, double max_distance) {
  const double max_sq = max_distance * max_distance;
  for (auto it = voxels_.begin(); it != voxels_.end();) {
    if ((voxel_centre(unpack(it->first)) - origin).squaredNorm() > max_sq) {
      it = voxels_.erase(it);
    } else {
      ++it;
    }
  }
}

Neighbour VoxelHashMap::nearest(const Eigen::Vector3d& query) const {
  Neighbour best;
  double best_sq = std::numeric_limits<double>::infinity();
  const VoxelIndex centre = voxel_of(query);
  // Gaps from the query to its voxel's lower and upper faces, per axis: a neighbour voxel
  // farther than the best point so far cannot hold a closer one and is not looked up (the
  // lookups, cache misses each, are most of the time).
  const Eigen::Vector3d lower = query - centre.cast<double>() * voxel_size_;
  const Eigen::Vector3d upper = Eigen::Vector3d::Constant(voxel_size_) - lower;
  auto gap = [&](int axis, int d) { return d < 0 ? lower[axis] : (d > 0 ? upper[axis] : 0.0); };
  auto visit = [&](int dx, int dy, int dz) {
    const double gx = gap(0, dx), gy = gap(1, dy), gz = gap(2, dz);
    if (gx * gx + gy * gy + gz * gz > best_sq) return;
    const auto it = voxels_.find(pack(VoxelIndex(centre.x() + dx, centre.y() + dy, centre.z() + dz)));
    if (it == voxels_.end()) return;
    for (const Eigen::Vector3d& p : it->second) {
      const double d_sq = (p - query).squaredNorm();
      if (d_sq < best_sq) {  // strict: the first of equals (in visiting order) wins
        best_sq = d_sq;
        best.point = p;
        best.found = true;
      }
    }
  };
  visit(0, 0, 0);  // the query's own voxel first: it most often holds the answer
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        if (dx != 0 || dy != 0 || dz != 0) visit(dx, dy, dz);
      }
    }
  }
  if (best.found) best.distance = std::sqrt(best_sq);
  return best;
}

std::size_t VoxelHashMap::num_points() const {
  std::size_t n = 0;
  for (const auto& [index, pts] : voxels_) n += pts.size();
  return n;
}

std::vector<Eigen::Vector3d> VoxelHashMap::points() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(num_points());
  for (const auto& [index, pts] : voxels_) out.insert(out.end(), pts.begin(), pts.end());
  return out;
}

}  // namespace tsgraphs::odometry
