#pragma once
/// Whether the rays have seen above a mapped plane's top: a shelf row's, a partition's (one
/// walks round them), or not (a wall up to the ceiling, of which a low sensor sees only the foot).
///
/// A ray counts for a plane when its track crosses the plane's segment (x-y), it is higher
/// there than the plane's top plus a margin, it ends beyond the plane (not on its face), and a
/// return at most as high as the plane's top lies where it crosses (the plane is there under
/// the ray: a ray through a door in the plane's line passes under the lintel, over nothing).
/// Judged per ray, not per raster cell: a cell on a wall's line is partly the room's air, where
/// rays to the ceiling pass high without ever crossing the wall.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "tsgraphs/freespace/sight_map.hpp"

namespace tsgraphs::freespace {

class WallTopRays {
 public:
  /// A vertical plane at floor height: its segment (map x-y) and the highest of its points.
  struct Wall {
    int id = -1;
    Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
    double top = 0.0;  ///< map z
  };

  /// `cell` (m, > 0): the resolution of where along a plane rays crossed it (the sight map's).
  explicit WallTopRays(double cell);

  /// Records the rays from `sensor` to `points` (map frame) that cross above one of `walls`
  /// (higher than its top + margin, ending at least `beyond` past its line); `sight` must
  /// already hold this scan.
  void add_scan(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points,
                const std::vector<Wall>& walls, const SightMap& sight, double margin, double beyond);

  /// Drops what was recorded for plane `id` (its rays are to be recorded again, from where
  /// their keyframes now are).
  void forget(int id) { crossed_.erase(id); }

  /// The share of the cells along the wall's segment that a recorded ray crossed higher than
  /// its (current) top + margin.
  double share_above(const Wall& wall, double margin) const;

 private:
  double cell_;
  /// Per wall id: per cell key along its line, the highest ray that crossed there.
  std::unordered_map<int, std::unordered_map<std::uint64_t, float>> crossed_;
  std::uint64_t key(const Eigen::Vector2d& p) const;
};

}  // namespace tsgraphs::freespace
