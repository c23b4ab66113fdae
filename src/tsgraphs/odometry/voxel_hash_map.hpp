#pragma once
/// The odometry's local map: world-frame points hashed into cubic voxels, a bounded number per
/// voxel, with a nearest-neighbour query over the voxels around a point (KISS-ICP's design).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace tsgraphs::odometry {

/// Integer coordinates of a voxel.
using VoxelIndex = Eigen::Vector3i;

/// Result of VoxelHashMap::nearest.
struct Neighbour {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;  ///< Euclidean distance from the query (m)
  bool found = false;     ///< false when the 27 voxels around the query are empty
};

class VoxelHashMap {
 public:
  /// `voxel_size` > 0 (m), `max_points_per_voxel` >= 1; otherwise std::invalid_argument.
  VoxelHashMap(double voxel_size, std::size_t max_points_per_voxel);

  /// Adds world-frame points; a point whose voxel is already full is dropped, so the map's
  /// density stays bounded however often a place is seen.
  void add_points(const std::vector<Eigen::Vector3d>& points);
  /// Removes every voxel whose centre is farther than `max_distance` from `origin`.
  void remove_far(const Eigen::Vector3d& origin, double max_distance);
  /// The closest stored point among the 27 voxels around `query` (the query's voxel and its
  /// neighbours): exact whenever the true nearest point is within one voxel_size. Ties go to
  /// the first point in a fixed visiting order (own voxel first), so the answer does not depend
  /// on hashing.
  Neighbour nearest(const Eigen::Vector3d& query) const;

  /// The voxel that holds `p`.
  VoxelIndex voxel_of(const Eigen::Vector3d& p) const;
  /// Centre of voxel `v` (m).
  Eigen::Vector3d voxel_centre(const VoxelIndex& v) const;
  /// The points of voxel `v` (empty when it holds none), in insertion order.
  const std::vector<Eigen::Vector3d>& voxel_points(const VoxelIndex& v) const;

  bool empty() const { return voxels_.empty(); }
  std::size_t num_voxels() const { return voxels_.size(); }
  std::size_t num_points() const;
  /// Every stored point (unordered; for inspection and output).
  std::vector<Eigen::Vector3d> points() const;
  void clear() { voxels_.clear(); }

  double voxel_size() const { return voxel_size_; }
  std::size_t max_points_per_voxel() const { return max_points_per_voxel_; }

 private:
  /// 21 bits per axis (+-1e6 voxels, far beyond any LiDAR range at useful sizes) in one word.
  static std::uint64_t pack(const VoxelIndex& v);
  static VoxelIndex unpack(std::uint64_t key);
  struct KeyHash {
    std::size_t operator()(std::uint64_t k) const {
      // A full-avalanche mix (splitmix64's finaliser): neighbouring voxels differ in few bits,
      // and a weak hash chained them into the same buckets, which dominated the query time.
      k ^= k >> 30;
      k *= 0xBF58476D1CE4E5B9ULL;
      k ^= k >> 27;
      k *= 0x94D049BB133111EBULL;
      k ^= k >> 31;
      return static_cast<std::size_t>(k);
    }
  };

  double voxel_size_;
  double inv_voxel_size_;
  std::size_t max_points_per_voxel_;
  std::unordered_map<std::uint64_t, std::vector<Eigen::Vector3d>, KeyHash> voxels_;
};

}  // namespace tsgraphs::odometry
