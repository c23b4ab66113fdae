#include "tsgraphs/odometry/voxel_hash_map.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tsgraphs::odometry {
std::uint64_t VoxelHashMap::pack(const VoxelIndex& v) { return voxel_key(v.x(), v.y(), v.z()); }

VoxelIndex VoxelHashMap::unpack(std::uint64_t key) { return voxel_of_key(key); }

VoxelHashMap::VoxelHashMap(double voxel_size, std::size_t max_points_per_voxel, const SurfaceConfig& surface)
    : voxel_size_(voxel_size),
      inv_voxel_size_(1.0 / voxel_size),
      max_points_per_voxel_(max_points_per_voxel),
      surface_(surface) {
  if (!(voxel_size > 0.0) || !std::isfinite(voxel_size)) {
    throw std::invalid_argument("VoxelHashMap: voxel_size must be positive and finite");
  }
  if (max_points_per_voxel < 1)
    throw std::invalid_argument("VoxelHashMap: max_points_per_voxel must be >= 1");
  if (surface.min_points < 3) throw std::invalid_argument("VoxelHashMap: surface min_points must be >= 3");
  if (!(surface.min_spread_factor > 0.0) || !(surface.max_thickness_ratio > 0.0))
    throw std::invalid_argument(
        "VoxelHashMap: surface min_spread_factor and max_thickness_ratio must be > 0");
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
  return it == voxels_.end() ? kNone : it->second.points;
}

Surface VoxelHashMap::surface_of(const VoxelIndex& v, Eigen::Vector3d* normal) const {
  const auto it = voxels_.find(pack(v));
  if (it == voxels_.end()) return Surface::unknown;
  if (normal) *normal = it->second.normal;
  return it->second.surface;
}

void VoxelHashMap::fit_surface(Voxel* voxel) const {
  const std::vector<Eigen::Vector3d>& pts = voxel->points;
  voxel->surface = Surface::unknown;
  if (pts.size() < static_cast<std::size_t>(surface_.min_points)) return;
  // Centred on the first point: world coordinates far from the origin would cost the
  // covariance its precision.
  const Eigen::Vector3d origin = pts.front();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : pts) {
    const Eigen::Vector3d d = p - origin;
    sum += d;
    outer.noalias() += d * d.transpose();
  }
  const double n = static_cast<double>(pts.size());
  const Eigen::Vector3d mean = sum / n;
  const Eigen::Matrix3d cov = outer / n - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  const Eigen::Vector3d sd = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending
  if (sd[1] < surface_.min_spread_factor * voxel_size_) return;            // a line or a blob
  if (sd[0] <= surface_.max_thickness_ratio * sd[1]) {
    voxel->surface = Surface::planar;
    voxel->normal = eig.eigenvectors().col(0).normalized();
  } else {
    voxel->surface = Surface::scattered;
  }
}

void VoxelHashMap::add_points(const std::vector<Eigen::Vector3d>& points) {
  std::vector<std::uint64_t> changed;  // keys, not pointers: inserting may move the voxels
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    const std::uint64_t key = pack(voxel_of(p));
    Voxel& voxel = voxels_[key];
    if (voxel.points.size() < max_points_per_voxel_) {
      if (voxel.points.empty()) voxel.points.reserve(max_points_per_voxel_);
      voxel.points.push_back(p);
      if (!voxel.changed) {
        voxel.changed = true;
        changed.push_back(key);
      }
    }
  }
  for (const std::uint64_t key : changed) {
    Voxel& voxel = voxels_.find(key).value();
    fit_surface(&voxel);
    voxel.changed = false;
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
  const Voxel* best_voxel = nullptr;
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
    for (const Eigen::Vector3d& p : it->second.points) {
      const double d_sq = (p - query).squaredNorm();
      if (d_sq < best_sq) {  // strict: the first of equals (in visiting order) wins
        best_sq = d_sq;
        best.point = p;
        best.found = true;
        best_voxel = &it->second;
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
  if (best.found) {
    best.distance = std::sqrt(best_sq);
    best.surface = best_voxel->surface;
    best.normal = best_voxel->normal;
  }
  return best;
}

std::size_t VoxelHashMap::num_points() const {
  std::size_t n = 0;
  for (const auto& [index, voxel] : voxels_) n += voxel.points.size();
  return n;
}

std::vector<Eigen::Vector3d> VoxelHashMap::points() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(num_points());
  for (const auto& [index, voxel] : voxels_) out.insert(out.end(), voxel.points.begin(), voxel.points.end());
  return out;
}

}  // namespace tsgraphs::odometry
