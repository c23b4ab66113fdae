// What the parts of the scene picture share (scene_drawing.hpp): colours, geometry, the
// sampled first lap and voxel maps seen from above.
#include "tsgraphs/report/scene_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/io/pcd.hpp"

namespace tsgraphs::report::scene_drawing {

/// Colour of the path at fraction u in [0, 1] of the lap.
std::string path_colour(double u) {
  u = std::clamp(u, 0.0, 1.0);
  for (std::size_t i = 1; i < kPathRamp.size(); ++i) {
    const ColourStop& a = kPathRamp[i - 1];
    const ColourStop& b = kPathRamp[i];
    if (u <= b.at || i + 1 == kPathRamp.size()) {
      const double f = std::clamp((u - a.at) / (b.at - a.at), 0.0, 1.0);
      return hex_colour(a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b));
    }
  }
  return hex_colour(kPathRamp.back().r, kPathRamp.back().g, kPathRamp.back().b);
}

/// Distinct colour of the i-th room: hues a golden angle apart.
std::string room_colour(std::size_t i) {
  return svg::hsl_colour(kRoomHueStartDeg + kGoldenAngleDeg * static_cast<double>(i), kRoomSaturation,
                         kRoomLightness);
}

// ---------------------------------------------------------------------------------------
// Geometry helpers

using svg::Extent;
std::string xy(const Vec2& p) { return num(p.x()) + "," + num(p.y()); }

std::string points_attr(const Frame& f, const Polygon2& poly) {
  std::string s;
  for (const Vec2& p : poly) s += (s.empty() ? "" : " ") + xy(f.px(p));
  return s;
}

Vec2 rotate(const Vec2& v, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

Vec2 left_normal(const Vec2& d) { return {-d.y(), d.x()}; }

/// The rectangle [s0, s1] along the segment a -> b, `thickness` wide about it.
Polygon2 strip(const Vec2& a, const Vec2& b, double s0, double s1, double thickness) {
  const Vec2 d = (b - a).normalized();
  const Vec2 n = 0.5 * thickness * left_normal(d);
  return {a + s0 * d - n, a + s1 * d - n, a + s1 * d + n, a + s0 * d + n};
}

Polygon2 box_corners(const scene::Box& box) {
  const Vec2 c = 0.5 * (box.min.head<2>() + box.max.head<2>());
  const Vec2 h = 0.5 * (box.max.head<2>() - box.min.head<2>());
  const double yaw = box.yaw_deg * M_PI / 180.0;
  return {c + rotate({-h.x(), -h.y()}, yaw), c + rotate({h.x(), -h.y()}, yaw),
          c + rotate({h.x(), h.y()}, yaw), c + rotate({-h.x(), h.y()}, yaw)};
}

/// A point inside `poly` to put its name at: the area centroid, or for shapes that do not
/// contain it (an L, a U) the centroid of the polygon's largest triangle.
Vec2 label_point(const Polygon2& poly) {
  const double a = signed_area(poly);
  Vec2 c = Vec2::Zero();
  if (std::abs(a) > kEps) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2& p = poly[i];
      const Vec2& q = poly[(i + 1) % poly.size()];
      const double cross = p.x() * q.y() - q.x() * p.y();
      c += (p + q) * cross;
    }
    c /= 6.0 * a;
    if (contains(poly, c)) return c;
  }
  double best = -1.0;
  for (const Triangle2& t : triangulate_region({poly})) {
    const double ta = std::abs((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x());
    if (ta > best) best = ta, c = (t[0] + t[1] + t[2]) / 3.0;
  }
  if (best < 0.0 && !poly.empty()) {
    c = Vec2::Zero();
    for (const Vec2& p : poly) c += p;
    c /= static_cast<double>(poly.size());
  }
  return c;
}

/// Direction in which a ramp climbs (its axis points up from `from_level` to `to_level`;
/// if `from_level` is the higher one the surface falls along the axis instead).
Vec2 ramp_uphill(const Scene& scene, const scene::Ramp& ramp) {
  const double rise = scene.levels[ramp.to_level].elevation - scene.levels[ramp.from_level].elevation;
  return rise >= 0.0 ? ramp.axis : Vec2(-ramp.axis);
}

// ---------------------------------------------------------------------------------------
// The path

namespace {

/// The level whose elevation is closest to the walkable surface under the sensor; among
/// levels at the same elevation, the first whose slab holds the point.
int level_at(const Scene& scene, double floor_z, const Vec2& p) {
  int best = 0;
  double best_gap = std::numeric_limits<double>::infinity();
  bool best_holds = false;
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    const double gap = std::abs(scene.levels[i].elevation - floor_z);
    const bool holds = contains(scene.levels[i].slab, p);
    if (gap < best_gap - kEps || (std::abs(gap - best_gap) <= kEps && holds && !best_holds)) {
      best = static_cast<int>(i), best_gap = gap, best_holds = holds;
    }
  }
  return best;
}

}  // namespace

/// The first lap, sampled every kSampleStepS seconds (and at its end).
std::vector<PathSample> sample_first_lap(const Scene& scene, const scene::Trajectory& trajectory) {
  const std::vector<double>& laps = trajectory.lap_starts();
  const double end = laps.size() > 1 ? laps[1] : trajectory.duration();
  const auto steps = static_cast<long>(std::floor(end / kSampleStepS + kEps));
  std::vector<PathSample> out;
  for (long k = 0; k <= steps + 1; ++k) {
    const double t = std::min(static_cast<double>(k) * kSampleStepS, end);
    if (!out.empty() && t <= out.back().t) break;
    const Pose3 pose = trajectory.body_pose(t);
    const Vec2 p = pose.translation().head<2>();
    const double floor_z = pose.translation().z() - scene.sensor.mount_height;
    out.push_back({p, yaw_of(pose), t, trajectory.distance_at(t), level_at(scene, floor_z, p)});
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Voxel maps: the occupied cells seen from above (floor and ceiling cubes left out)

VoxelFootprint voxel_footprint(const Scene& scene, const scene::VoxelMap& vm) {
  VoxelFootprint fp;
  fp.level = vm.level;
  fp.cell = vm.voxel_size;
  const PointCloud cloud = io::read_pcd(vm.file);
  const double c = std::cos(vm.yaw_deg * M_PI / 180.0), s = std::sin(vm.yaw_deg * M_PI / 180.0);
  const double ceiling = scene.levels[vm.level].ceiling;
  for (const Eigen::Vector3f& pf : cloud.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double z = p.z() + vm.offset.z();
    if (vm.label == scene::VoxelLabel::kAuto &&
        (std::abs(z) <= vm.voxel_size || std::abs(z - ceiling) <= vm.voxel_size)) {
      continue;
    }
    const double x = c * p.x() - s * p.y() + vm.offset.x(), y = s * p.x() + c * p.y() + vm.offset.y();
    fp.cells.emplace(std::lround(y / fp.cell), std::lround(x / fp.cell));  // row-major: rows merge into runs
  }
  return fp;
}
}  // namespace tsgraphs::report::scene_drawing
