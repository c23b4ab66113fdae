#include "tsgraphs/scene/walkable_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::scene {
namespace {

constexpr double kHalfDiagonal =
    0.7072;                           // of a cell, in cells: a shape within it of a centre touches the cell
constexpr int kProbeRings = 4;        // rings of obstacle_distance's walkable-surface probe
constexpr int kProbeDirections = 24;  // probes per ring (15 degrees apart)
constexpr int kEdgeBisections =
    12;  // halvings that place a surface edge between two rings (to 1e-4 of a ring)

/// An oriented rectangle: centre, unit axis along its length, half length and half width, and
/// the heights it spans (relative to its level's floor).
struct Slab2 {
  Vec2 c, u;
  double hl, hw;
  double z0 = 0.0, z1 = 0.0;
  double distance(const Vec2& p) const {
    const Vec2 d = p - c;
    const double a = std::max(std::abs(d.dot(u)) - hl, 0.0);
    const double b = std::max(std::abs(d.x() * -u.y() + d.y() * u.x()) - hw, 0.0);
    return std::hypot(a, b);
  }
};

/// Everything on `level` that stops a walker, as oriented rectangles (a railing is a thin one).
std::vector<Slab2> blocking_shapes(const Scene& scene, int level, const WalkableRules& rules) {
  std::vector<Slab2> shapes;
  for (const Wall& w : scene.walls) {
    if (w.level != level) continue;
    const Vec2 dir = (w.to - w.from).normalized();
    for (const WallPiece& p : wall_pieces(w)) {
      if (p.z0 >= rules.headroom) continue;  // a lintel: walked under
      shapes.push_back(
          {w.from + 0.5 * (p.s0 + p.s1) * dir, dir, 0.5 * (p.s1 - p.s0), 0.5 * w.thickness, p.z0, p.z1});
    }
    for (const GlassPane& g : glass_panes(w)) {  // glass stops a walker as the wall does
      if (g.z0 >= rules.headroom) continue;
      shapes.push_back(
          {w.from + 0.5 * (g.s0 + g.s1) * dir, dir, 0.5 * (g.s1 - g.s0), 0.5 * w.thickness, g.z0, g.z1});
    }
  }
  for (const Railing& r : scene.railings) {
    if (r.level != level) continue;
    const Vec2 d = r.to - r.from;
    const double half = 0.5 * std::max(RailingGeometry::kSolidThickness, RailingGeometry::kPostWidth);
    shapes.push_back({0.5 * (r.from + r.to), d.normalized(), 0.5 * d.norm(), half, 0.0, r.height});
  }
  for (const Box& b : scene.boxes) {
    if (b.level != level || b.min.z() >= rules.headroom || b.max.z() <= 0.0) continue;
    const double yaw = b.yaw_deg * M_PI / 180.0;
    const Vec2 half = 0.5 * (b.max.head<2>() - b.min.head<2>());
    shapes.push_back({0.5 * (b.min.head<2>() + b.max.head<2>()), Vec2(std::cos(yaw), std::sin(yaw)), half.x(),
                      half.y(), b.min.z(), b.max.z()});
  }
  return shapes;
}

}  // namespace

GridFrame frame_covering(const Scene& scene, double resolution, double margin) {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Level& l : scene.levels) {
    for (const Vec2& p : l.slab) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  return GridFrame::around(lo, hi, resolution, margin);
}

double WalkableGrid::clearance_at(const Vec2& p) const {
  int c, r;
  if (!frame.cell_of(p, &c, &r) || free[frame.index(c, r)] == 0) return 0.0;
  return clearance[frame.index(c, r)];
}

WalkableGrid rasterise_walkable(const Scene& scene, int level, const GridFrame& frame,
                                const WalkableRules& rules) {
  WalkableGrid g;
  g.level = level;
  g.frame = frame;
  g.free.assign(frame.size(), 0);
  for (int r = 0; r < frame.rows; ++r) {
    for (int c = 0; c < frame.cols; ++c) {
      double z;
      if (walkable_height(scene, level, frame.center(c, r), &z)) g.free[frame.index(c, r)] = 1;
    }
  }
  // Each shape blocks every cell it touches, so that a 4 cm railing cannot slip between cells.
  const double touch = kHalfDiagonal * frame.resolution;
  for (const Slab2& s : blocking_shapes(scene, level, rules)) {
    const double reach = std::abs(s.u.x()) * s.hl + std::abs(s.u.y()) * s.hw + touch;
    const double reach_y = std::abs(s.u.y()) * s.hl + std::abs(s.u.x()) * s.hw + touch;
    const int c0 =
        std::max(0, static_cast<int>(std::floor((s.c.x() - reach - frame.origin.x()) / frame.resolution)));
    const int c1 =
        std::min(frame.cols - 1,
                 static_cast<int>(std::floor((s.c.x() + reach - frame.origin.x()) / frame.resolution)));
    const int r0 =
        std::max(0, static_cast<int>(std::floor((s.c.y() - reach_y - frame.origin.y()) / frame.resolution)));
    const int r1 =
        std::min(frame.rows - 1,
                 static_cast<int>(std::floor((s.c.y() + reach_y - frame.origin.y()) / frame.resolution)));
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        if (s.distance(frame.center(c, r)) <= touch) g.free[frame.index(c, r)] = 0;
      }
    }
  }
  compute_clearance(&g);
  return g;
}

void compute_clearance(WalkableGrid* grid) { grid->clearance = distance_transform(grid->frame, grid->free); }

double obstacle_distance(const Scene& scene, const Vec2& xy, double floor_z, double probe_radius,
                         const WalkableRules& rules) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t l = 0; l < scene.levels.size(); ++l) {
    const double e = scene.levels[l].elevation;
    for (const Slab2& s : blocking_shapes(scene, static_cast<int>(l), rules)) {
      if (e + s.z1 <= floor_z + rules.step || e + s.z0 >= floor_z + rules.headroom) continue;
      best = std::min(best, s.distance(xy));
    }
  }
  const auto walkable = [&](const Vec2& p) {
    for (std::size_t l = 0; l < scene.levels.size(); ++l) {
      double z;
      if (walkable_height(scene, static_cast<int>(l), p, &z) && std::abs(z - floor_z) <= rules.step)
        return true;
    }
    return false;
  };
  if (!walkable(xy)) return 0.0;
  for (int ring = 1; ring <= kProbeRings && ring * probe_radius / kProbeRings < best; ++ring) {
    const double radius = ring * probe_radius / kProbeRings;
    double edge = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kProbeDirections; ++k) {
      const Vec2 dir(std::cos(2.0 * M_PI * k / kProbeDirections),
                     std::sin(2.0 * M_PI * k / kProbeDirections));
      if (walkable(xy + radius * dir)) continue;
      // The edge lies between the last ring and this one: find it along this direction.
      double lo = (ring - 1) * probe_radius / kProbeRings, hi = radius;
      for (int i = 0; i < kEdgeBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        (walkable(xy + mid * dir) ? lo : hi) = mid;
      }
      edge = std::min(edge, hi);
    }
    if (std::isfinite(edge)) return std::min(best, edge);
  }
  return best;
}

}  // namespace tsgraphs::scene
