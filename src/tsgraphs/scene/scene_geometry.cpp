#include "tsgraphs/scene/scene_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsgraphs::scene {

std::vector<WallPiece> wall_pieces(const Wall& wall) {
  const double length = (wall.to - wall.from).norm();
  const double start = wall.joined_from ? -0.5 * wall.thickness : 0.0;
  const double end = length + (wall.joined_to ? 0.5 * wall.thickness : 0.0);
  std::vector<WallPiece> pieces;
  double s = start;
  for (const Opening& o : wall.openings) {  // sorted by `at`, not overlapping
    const double a = o.at - 0.5 * o.width, b = o.at + 0.5 * o.width;
    if (a > s) pieces.push_back({s, a, 0.0, wall.height});  // also a joined end's corner square
    if (o.sill > 0.0) pieces.push_back({a, b, 0.0, o.sill});
    if (o.sill + o.height < wall.height) pieces.push_back({a, b, o.sill + o.height, wall.height});
    s = b;
  }
  if (s < end) pieces.push_back({s, end, 0.0, wall.height});
  return pieces;
}

std::vector<GlassPane> glass_panes(const Wall& wall) {
  std::vector<GlassPane> panes;
  for (const Opening& o : wall.openings) {
    if (o.transmission < 1.0)
      panes.push_back(
          {o.at - 0.5 * o.width, o.at + 0.5 * o.width, o.sill, o.sill + o.height, o.transmission});
  }
  return panes;
}

std::vector<Polygon2> ceiling_holes(const Scene& scene, int level) {
  std::vector<Polygon2> holes = scene.levels[level].voids;
  // The next level up by elevation: its floor and this ceiling are one slab.
  const double z = scene.levels[level].elevation;
  int above = -1;
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    const double zi = scene.levels[i].elevation;
    if (zi > z && (above < 0 || zi < scene.levels[above].elevation)) above = static_cast<int>(i);
  }
  if (above >= 0)
    holes.insert(holes.end(), scene.levels[above].voids.begin(), scene.levels[above].voids.end());
  return holes;
}

double ramp_height(const Scene& scene, const Ramp& ramp, const Vec2& xy) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec2& p : ramp.polygon) {
    lo = std::min(lo, p.dot(ramp.axis));
    hi = std::max(hi, p.dot(ramp.axis));
  }
  // `axis` is the direction of ascent, whichever of the two levels is named first.
  const double z_a = scene.levels[ramp.from_level].elevation;
  const double z_b = scene.levels[ramp.to_level].elevation;
  const double z0 = std::min(z_a, z_b), z1 = std::max(z_a, z_b);
  const double s = std::clamp((xy.dot(ramp.axis) - lo) / std::max(hi - lo, 1e-9), 0.0, 1.0);
  return z0 + s * (z1 - z0);
}

bool walkable_height(const Scene& scene, int level, const Vec2& xy, double* z) {
  for (const Ramp& r : scene.ramps) {
    if ((r.from_level == level || r.to_level == level) && contains(r.polygon, xy)) {
      *z = ramp_height(scene, r, xy);
      return true;
    }
  }
  const Level& l = scene.levels[level];
  if (!contains(l.slab, xy)) return false;
  for (const Polygon2& v : l.voids) {
    if (contains(v, xy)) return false;
  }
  *z = l.elevation;
  return true;
}

void join_wall_ends(Scene* scene) {
  constexpr double kJoinTolerance = 1e-3;  // m between two ends that count as one corner
  for (Wall& w : scene->walls) {
    w.joined_from = w.joined_to = false;
    for (const Wall& o : scene->walls) {
      if (&o == &w || o.level != w.level) continue;
      for (const Vec2& e : {o.from, o.to}) {
        w.joined_from = w.joined_from || (w.from - e).norm() < kJoinTolerance;
        w.joined_to = w.joined_to || (w.to - e).norm() < kJoinTolerance;
      }
    }
  }
}

int level_under(const Scene& scene, const Vec2& xy, double floor_z, double tolerance, int fallback) {
  int best = fallback;
  double gap = tolerance;
  for (std::size_t l = 0; l < scene.levels.size(); ++l) {
    double z;
    if (walkable_height(scene, static_cast<int>(l), xy, &z) && std::abs(z - floor_z) < gap) {
      gap = std::abs(z - floor_z);
      best = static_cast<int>(l);
    }
  }
  return best;
}

}  // namespace tsgraphs::scene
