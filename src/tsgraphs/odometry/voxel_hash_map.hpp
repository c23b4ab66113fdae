#pragma once
/// The odometry's local map: world-frame points hashed into cubic voxels, a bounded number per
/// voxel, with a nearest-neighbour query over the voxels around a point (KISS-ICP's design).
#include <tsl/robin_map.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tsgraphs/core/voxel_key.hpp"

namespace tsgraphs::odometry {

/// Integer coordinates of a voxel.
using VoxelIndex = Eigen::Vector3i;

/// The shape of a voxel's points, from the principal components of their spread.
enum class Surface : std::uint8_t {
  unknown,    ///< too few points, or a line (one scan ring): no direction can be trusted
  planar,     ///< a flat patch: its normal is the direction the patch constrains
  scattered,  ///< neither: a corner, an edge, clutter; only the point itself can be matched
};

/// When a voxel's points make a plane (VoxelHashMap::surface_of).
struct SurfaceConfig {
  int min_points = 4;  ///< fewer points: unknown
  double min_spread_factor =
      0.15;  ///< a plane spreads at least voxel_size * this (m, second principal sd) in
             ///< both directions; less is a line, such as one ring of a scan on the floor
  double max_thickness_ratio =
      0.3;  ///< a plane is at most this thick (smallest sd) for its width (second sd)
};

/// Result of VoxelHashMap::nearest.
struct Neighbour {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;                             ///< Euclidean distance from the query (m)
  bool found = false;                                ///< false when the 27 voxels around the query are empty
  Surface surface = Surface::unknown;                ///< the shape of the point's voxel
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit normal of that voxel when it is planar
};

class VoxelHashMap {
 public:
  /// `voxel_size` > 0 (m), `max_points_per_voxel` >= 1, a surface config with min_points >= 3
  /// and positive factors; otherwise std::invalid_argument.
  VoxelHashMap(double voxel_size, std::size_t max_points_per_voxel, const SurfaceConfig& surface = {});

  /// Adds world-frame points; a point whose voxel is already full is dropped, so the map's
  /// density stays bounded however often a place is seen. The voxels that took points have
  /// their surface fitted again.
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
  /// The shape of voxel `v`'s points (unknown when it holds none), and its normal when planar.
  Surface surface_of(const VoxelIndex& v, Eigen::Vector3d* normal = nullptr) const;

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

  struct Voxel {
    std::vector<Eigen::Vector3d> points;
    Surface surface = Surface::unknown;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    bool changed = false;  ///< took points in the current add_points call
  };
  /// Fits the voxel's surface to its points.
  void fit_surface(Voxel* voxel) const;

  double voxel_size_;
  double inv_voxel_size_;
  std::size_t max_points_per_voxel_;
  SurfaceConfig surface_;
  // Robin Hood open addressing (what KISS-ICP uses): the neighbour lookups of ICP are most of
  // the odometry's time, and a node-based map costs a cache miss per lookup more.
  tsl::robin_map<std::uint64_t, Voxel, KeyHash> voxels_;
};

}  // namespace tsgraphs::odometry
