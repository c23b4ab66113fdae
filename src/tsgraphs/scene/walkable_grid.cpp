#include "tsgraphs/scene/walkable_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::scene {
namespace {

constexpr double kHalfDiagonal = 0.7072;  // of a cell, in cells: a shape within it of a centre touches the cell
constexpr int kProbeRings = 4;            // rings of obstacle_distance's walkable-surface probe
constexpr int kProbeDirections = 24;      // probes per ring (15 degrees apart)
constexpr int kEdgeBisections = 12;       // halvings that place a surface edge between two rings (to 1e-4 of a ring)

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
      shapes.push_back({w.from + 0.5 * (p.s0 + p.s1) * dir, dir, 0.5 * (p.s1 - p.s0), 0.5 * w.thickness, p.z0, p.z1});
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
    shapes.push_back({0.5 * (b.min.head<2>() + b.max.head<2>()), Vec2(std::cos(yaw), std::sin(yaw)), half.x(), half.y(),
                      b.min.z(), b.max.z()});
  }
  return shapes;
}

// One pass of the 1-D squared distance transform (Felzenszwalb and Huttenlocher 2012) over
// f[0..n), in cells; v and z are scratch space.
void distance_transform_1d(const float* f, int n, float* out, std::vector<int>& v, std::vector<float>& z) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  v.resize(n);
  z.resize(n + 1);
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (!std::isfinite(f[q])) continue;
    float s = -kInf;
    while (k >= 0) {
      s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0f * (q - v[k]));
      if (s > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -kInf : s;
    z[k + 1] = kInf;
  }
  if (k < 0) {
    std::fill(out, out + n, kInf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < q) ++j;
    const float d = static_cast<float>(q - v[j]);
    out[q] = d * d + f[v[j]];
  }
}

}  // namespace

bool GridFrame::cell_of(const Vec2& p, int* c, int* r) const {
  const Vec2 q = (p - origin) / resolution;
  if (!(q.x() >= 0.0 && q.y() >= 0.0)) return false;
  *c = static_cast<int>(q.x());
  *r = static_cast<int>(q.y());
  return inside(*c, *r);
}

GridFrame GridFrame::covering(const Scene& scene, double resolution, double margin) {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Level& l : scene.levels) {
    for (const Vec2& p : l.slab) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  GridFrame f;
  f.resolution = resolution;
  f.origin = lo - Vec2::Constant(margin);
  f.cols = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * margin) / resolution));
  f.rows = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * margin) / resolution));
  return f;
}

double WalkableGrid::clearance_at(const Vec2& p) const {
  int c, r;
  if (!frame.cell_of(p, &c, &r) || free[frame.index(c, r)] == 0) return 0.0;
  return clearance[frame.index(c, r)];
}

WalkableGrid rasterise_walkable(const Scene& scene, int level, const GridFrame& frame, const WalkableRules& rules) {
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
    const int c0 = std::max(0, static_cast<int>(std::floor((s.c.x() - reach - frame.origin.x()) / frame.resolution)));
    const int c1 = std::min(frame.cols - 1, static_cast<int>(std::floor((s.c.x() + reach - frame.origin.x()) / frame.resolution)));
    const int r0 = std::max(0, static_cast<int>(std::floor((s.c.y() - reach_y - frame.origin.y()) / frame.resolution)));
    const int r1 = std::min(frame.rows - 1, static_cast<int>(std::floor((s.c.y() + reach_y - frame.origin.y()) / frame.resolution)));
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        if (s.distance(frame.center(c, r)) <= touch) g.free[frame.index(c, r)] = 0;
      }
    }
  }
  compute_clearance(&g);
  return g;
}

void compute_clearance(WalkableGrid* grid) {
  const GridFrame& f = grid->frame;
  constexpr float kInf = std::numeric_limits<float>::infinity();
  // Blocked cells are the sources; the raster's border counts as blocked (one ring outside).
  const int W = f.cols + 2, H = f.rows + 2;
  std::vector<float> d(static_cast<std::size_t>(W) * H, 0.0f);
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c) d[static_cast<std::size_t>(r + 1) * W + c + 1] = grid->free[f.index(c, r)] ? kInf : 0.0f;
  }
  std::vector<int> v;
  std::vector<float> z, col(H), out(std::max(W, H));
  for (int x = 0; x < W; ++x) {
    for (int y = 0; y < H; ++y) col[y] = d[static_cast<std::size_t>(y) * W + x];
    distance_transform_1d(col.data(), H, out.data(), v, z);
    for (int y = 0; y < H; ++y) d[static_cast<std::size_t>(y) * W + x] = out[y];
  }
  for (int y = 0; y < H; ++y) {
    float* row = &d[static_cast<std::size_t>(y) * W];
    distance_transform_1d(row, W, out.data(), v, z);
    std::copy(out.begin(), out.begin() + W, row);
  }
  grid->clearance.assign(f.size(), 0.0f);
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c) {
      grid->clearance[f.index(c, r)] =
          static_cast<float>(std::sqrt(d[static_cast<std::size_t>(r + 1) * W + c + 1]) * f.resolution);
    }
  }
}

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
      if (walkable_height(scene, static_cast<int>(l), p, &z) && std::abs(z - floor_z) <= rules.step) return true;
    }
    return false;
  };
  if (!walkable(xy)) return 0.0;
  for (int ring = 1; ring <= kProbeRings && ring * probe_radius / kProbeRings < best; ++ring) {
    const double radius = ring * probe_radius / kProbeRings;
    double edge = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kProbeDirections; ++k) {
      const Vec2 dir(std::cos(2.0 * M_PI * k / kProbeDirections), std::sin(2.0 * M_PI * k / kProbeDirections));
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
