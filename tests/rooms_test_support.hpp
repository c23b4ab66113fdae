#pragma once
// Constructed inputs shared by the room extraction tests: wall candidates, free-space grids,
// the walls of a 5 x 4 m room, and the axis-aligned bounds of a footprint.
#include <algorithm>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/rooms/room.hpp"

namespace tsgraphs::rooms::test {

/// A vertical wall through `point` with 2-D `normal` (into the room), its face from a to b.
inline WallCandidate wall(int id, Vec2 point, Vec2 normal, Vec2 a, Vec2 b) {
  WallCandidate w;
  w.id = id;
  w.plane = Plane::from_point_normal(Eigen::Vector3d(point.x(), point.y(), 0.0),
                                     Eigen::Vector3d(normal.x(), normal.y(), 0.0));
  w.end_a = a;
  w.end_b = b;
  return w;
}

/// Free-space points on a grid of spacing `step` over [x0, x1] x [y0, y1], 0.3 m above the floor.
inline std::vector<Eigen::Vector3d> grid(double step, double x0, double x1, double y0, double y1) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; x0 + i * step <= x1 + 1e-9; ++i) {
    for (int j = 0; y0 + j * step <= y1 + 1e-9; ++j) out.emplace_back(x0 + i * step, y0 + j * step, 0.3);
  }
  return out;
}

/// The four walls of the room [0, 5] x [0, 4], ids 0..3, normals into the room.
inline std::vector<WallCandidate> room_walls() {
  return {wall(0, {0, 0}, {1, 0}, {0, 0}, {0, 4}), wall(1, {5, 0}, {-1, 0}, {5, 0}, {5, 4}),
          wall(2, {0, 0}, {0, 1}, {0, 0}, {5, 0}), wall(3, {0, 4}, {0, -1}, {0, 4}, {5, 4})};
}

/// room_walls() turned by `R` about the origin, then moved by `t`.
inline std::vector<WallCandidate> moved_room_walls(const Eigen::Rotation2Dd& R, const Vec2& t) {
  std::vector<WallCandidate> walls;
  for (const WallCandidate& w : room_walls()) {
    const Vec2 n = R * w.plane.n.head<2>();
    walls.push_back(wall(w.id, R * w.end_a + t, n, R * w.end_a + t, R * w.end_b + t));
  }
  return walls;
}

struct Bounds {
  double x0, x1, y0, y1;
};

/// The axis-aligned bounds of a footprint's corners.
inline Bounds bounds(const OrientedRect& r) {
  Bounds b{1e9, -1e9, 1e9, -1e9};
  for (const Vec2& c : r.corners()) {
    b.x0 = std::min(b.x0, c.x());
    b.x1 = std::max(b.x1, c.x());
    b.y0 = std::min(b.y0, c.y());
    b.y1 = std::max(b.y1, c.y());
  }
  return b;
}

}  // namespace tsgraphs::rooms::test
