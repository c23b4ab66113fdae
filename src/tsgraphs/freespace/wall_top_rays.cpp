#include "tsgraphs/freespace/wall_top_rays.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/core/voxel_key.hpp"

namespace tsgraphs::freespace {

WallTopRays::WallTopRays(double cell) : cell_(cell) {
  if (!(cell > 0.0)) throw std::invalid_argument("WallTopRays: cell must be > 0");
}

std::uint64_t WallTopRays::key(const Eigen::Vector2d& p) const {
  const auto c = static_cast<std::int64_t>(std::floor(p.x() / cell_)),
             r = static_cast<std::int64_t>(std::floor(p.y() / cell_));
  return cell_key(c, r);
}

void WallTopRays::add_scan(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points,
                           const std::vector<Wall>& walls, const SightMap& sight, double margin,
                           double beyond) {
  if (walls.empty() || points.empty()) return;
  const Eigen::Vector2d s = sensor.head<2>();
  // Only rays that rise above the lowest plane's top can count, and none reaches a plane
  // farther than the farthest point: one pass over the points, not one per plane.
  double lowest_over = std::numeric_limits<double>::infinity();
  for (const Wall& w : walls) lowest_over = std::min(lowest_over, w.top + margin);
  std::vector<const Eigen::Vector3d*> high;
  double reach = 0.0;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite() || std::max(sensor.z(), p.z()) <= lowest_over) continue;
    high.push_back(&p);
    reach = std::max(reach, (p.head<2>() - s).norm());
  }
  if (high.empty()) return;
  for (const Wall& w : walls) {
    const Eigen::Vector2d along = w.b - w.a;
    const double length = along.norm();
    if (!(length > 0.0)) continue;
    const Eigen::Vector2d n(-along.y() / length, along.x() / length);
    const double side_s = n.dot(s - w.a);
    if (std::abs(side_s) < beyond) continue;  // the sensor stands in the plane's line
    if (!(distance_to_segment(s, w.a, w.b) <= reach + cell_)) continue;  // a cell of slack for rounding
    const double over = w.top + margin;
    for (const Eigen::Vector3d* q : high) {
      const Eigen::Vector3d& p = *q;
      if (std::max(sensor.z(), p.z()) <= over) continue;  // never that high
      const double side_p = n.dot(p.head<2>() - w.a);
      if ((side_p > 0.0) == (side_s > 0.0) || std::abs(side_p) < beyond)
        continue;                                   // ends before or on its face
      const double t = side_s / (side_s - side_p);  // where the ray's track crosses the line
      const Eigen::Vector2d x = s + t * (p.head<2>() - s);
      const double u = along.dot(x - w.a) / (length * length);
      if (u < 0.0 || u > 1.0) continue;
      const double z = sensor.z() + t * (p.z() - sensor.z());
      if (z <= over || !sight.return_near(x, w.top)) continue;
      float& best = crossed_[w.id][key(x)];
      best = std::max(best, static_cast<float>(z));
    }
  }
}

double WallTopRays::share_above(const Wall& wall, double margin) const {
  const auto it = crossed_.find(wall.id);
  if (it == crossed_.end()) return 0.0;
  const double length = (wall.b - wall.a).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / cell_)));
  int above = 0;
  for (int k = 0; k <= steps; ++k) {
    const auto c = it->second.find(key(wall.a + (wall.b - wall.a) * (static_cast<double>(k) / steps)));
    if (c != it->second.end() && c->second > wall.top + margin) ++above;
  }
  return static_cast<double>(above) / (steps + 1);
}

}  // namespace tsgraphs::freespace
