#include <cmath>
#include <string>
#include <vector>

#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/core/yaml_map.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_loader_internal.hpp"

namespace tsgraphs::scene::scene_loader_internal {
namespace {

// Bounds of a person (scene `people:`, the messages name them): faster than a sprinter or
// bigger than a room is a typo.
constexpr double kMaxPersonSpeed = 10.0;    // m/s
constexpr double kMaxPersonSize = 5.0;      // m, height or radius
constexpr double kMaxPlatformSpeed = 30.0;  // m/s, a car

}  // namespace

void SceneParser::parse_trajectory(const YamlMap& m) {
  if (!root_.has("trajectory")) throw root_.error_here("missing required key 'trajectory'");
  m.check_keys({"level", "waypoints", "closed", "laps", "speed", "yaw_rate_deg"});
  TrajectorySpec& t = scene_.trajectory;
  t.level = m.has("level") ? level_index(m, "level") : 0;
  t.closed = m.get<bool>("closed", true);
  t.laps = m.get<int>("laps", 2);
  if (t.laps < 1 || t.laps > limits::kMaxLaps)
    throw m.error("laps", "must be in [1, " + std::to_string(limits::kMaxLaps) + "]");
  t.speed = m.get<double>("speed", 1.0);
  require_positive(m, "speed", t.speed);
  if (t.speed > kMaxPlatformSpeed) throw m.error("speed", "must be <= 30 m/s");
  t.yaw_rate_deg = m.get<double>("yaw_rate_deg", 90.0);
  require_positive(m, "yaw_rate_deg", t.yaw_rate_deg);
  const YAML::Node wps = m.raw("waypoints");
  if (!wps.IsDefined() || !wps.IsSequence() || wps.size() < 2) {
    throw m.error("waypoints", "expected a list of at least two waypoints");
  }
  int level = t.level;
  for (std::size_t i = 0; i < wps.size(); ++i) {
    const YAML::Node n = wps[i];
    const std::string where = m.key_path("waypoints") + "[" + std::to_string(i) + "]";
    const int line = n.Mark().line + 1;
    if (!n.IsSequence() || (n.size() != 2 && n.size() != 3)) {
      throw input_error(m.file(), line, where + ": expected [x, y] or [x, y, level]");
    }
    Waypoint w;
    w.line = line;
    w.xy = Vec2(m.as<double>(n[0], where), m.as<double>(n[1], where));
    if (n.size() == 3) {
      const std::string name = m.as<std::string>(n[2], where);
      level = -1;
      for (std::size_t k = 0; k < scene_.levels.size(); ++k) {
        if (scene_.levels[k].name == name) level = static_cast<int>(k);
      }
      if (level < 0)
        throw input_error(m.file(), line, where + ": unknown level '" + name + "'" + known_levels());
    }
    w.level = level;
    check_waypoint(w, where);
    t.waypoints.push_back(w);
  }
  for (std::size_t i = 0; i + 1 < t.waypoints.size(); ++i) {
    if ((t.waypoints[i].xy - t.waypoints[i + 1].xy).norm() < 1e-6) {
      throw input_error(
          m.file(), t.waypoints[i + 1].line,
          m.key_path("waypoints") + "[" + std::to_string(i + 1) + "]: repeats the previous waypoint");
    }
  }
}

void SceneParser::check_waypoint(const Waypoint& w, const std::string& where) const {
  const Level& level = scene_.levels[w.level];
  double z = 0.0;
  if (!walkable_height(scene_, w.level, w.xy, &z)) {
    throw input_error(
        root_.file(), w.line,
        where + ": " + fmt_point(w.xy) + " is outside every slab of level " + level.name + " (or in a void)");
  }
  for (std::size_t i = 0; i < scene_.walls.size(); ++i) {
    const Wall& wall = scene_.walls[i];
    if (wall.level != w.level) continue;
    if (distance_to_segment(w.xy, wall.from, wall.to) >= 0.5 * wall.thickness) continue;
    // Inside the wall's footprint: allowed only in a door (an opening from the floor, no pane).
    const Vec2 dir = (wall.to - wall.from).normalized();
    const double s = (w.xy - wall.from).dot(dir);
    bool in_door = false;
    for (const Opening& o : wall.openings) {
      in_door = in_door || (o.sill <= 0.0 && o.transmission >= 1.0 && std::abs(s - o.at) < 0.5 * o.width);
    }
    if (!in_door) {
      throw input_error(root_.file(), w.line,
                        where + ": " + fmt_point(w.xy) + " is inside the wall walls[" + std::to_string(i) +
                            "] (line " + std::to_string(wall.line) + ")");
    }
  }
}

void SceneParser::check_sequence_length() const {
  const std::string what = recording_over_limits(scene_);
  if (what.empty()) return;
  const YamlMap m = root_.map("trajectory");
  for (const char* key : {"laps", "speed"})
    if (m.has(key)) throw m.error(key, what + " (speed, laps)");
  throw m.error_here(what);
}

void SceneParser::parse_person(const YamlMap& m) {
  m.check_keys({"level", "path", "speed", "offset", "height", "radius"});
  Person p;
  p.line = m.line();
  p.level = level_index(m, "level");
  const YAML::Node path = m.raw("path");
  if (!path.IsDefined() || !path.IsSequence() || path.size() < 2)
    throw m.error("path", "expected a list of at least two [x, y] points");
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string where = m.key_path("path") + "[" + std::to_string(i) + "]";
    const int line = path[i].Mark().line + 1;
    if (!path[i].IsSequence() || path[i].size() != 2)
      throw input_error(m.file(), line, where + ": expected [x, y]");
    const Vec2 xy(m.as<double>(path[i][0], where), m.as<double>(path[i][1], where));
    double z = 0.0;
    if (!walkable_height(scene_, p.level, xy, &z))
      throw input_error(m.file(), line,
                        where + ": " + fmt_point(xy) + " is outside every slab of level " +
                            scene_.levels[p.level].name + " (or over one of its voids)");
    if (!p.path.empty() && (xy - p.path.back()).norm() < 1e-6)
      throw input_error(m.file(), line, where + ": repeats the previous point");
    p.path.push_back(xy);
  }
  p.speed = m.get<double>("speed", p.speed);
  require_positive(m, "speed", p.speed);
  if (p.speed > kMaxPersonSpeed) throw m.error("speed", "must be <= 10 m/s (a sprinter)");
  p.offset = m.get<double>("offset", p.offset);
  p.height = m.get<double>("height", p.height);
  require_positive(m, "height", p.height);
  p.radius = m.get<double>("radius", p.radius);
  require_positive(m, "radius", p.radius);
  if (p.height > kMaxPersonSize || p.radius > kMaxPersonSize)
    throw m.error(p.height > kMaxPersonSize ? "height" : "radius", "must be <= 5 m");
  scene_.people.push_back(std::move(p));
}

void SceneParser::warn_about_path() {
  const std::vector<Waypoint>& wps = scene_.trajectory.waypoints;
  const std::size_t legs = scene_.trajectory.closed ? wps.size() : wps.size() - 1;
  for (std::size_t i = 0; i < legs; ++i) {
    const Waypoint& a = wps[i];
    const Waypoint& b = wps[(i + 1) % wps.size()];
    const std::string leg = "trajectory.waypoints[" + std::to_string(i) + "]-[" +
                            std::to_string((i + 1) % wps.size()) + "]: the path ";
    const int line = (i + 1 < wps.size()) ? b.line : a.line;
    // A leg between storeys climbs a ramp: what is under it on the lower storey is not in
    // the way, and the loader does not know the height along it; such legs are not checked.
    if (a.level != b.level) continue;
    for (std::size_t k = 0; k < scene_.walls.size(); ++k) {
      const Wall& w = scene_.walls[k];
      if (w.level != a.level) continue;
      const Vec2 dir = (w.to - w.from).normalized();
      std::vector<WallPiece> pieces = wall_pieces(w);
      for (const GlassPane& g : glass_panes(w))
        pieces.push_back({g.s0, g.s1, g.z0, g.z1});  // a glazed door is shut
      for (const WallPiece& p : pieces) {
        if (p.z0 > 0.0) continue;  // above a door: walked under
        OrientedRect r;
        r.center = w.from + 0.5 * (p.s0 + p.s1) * dir;
        r.size = Vec2(p.s1 - p.s0, w.thickness);
        r.yaw = std::atan2(dir.y(), dir.x());
        if (segment_meets(a.xy, b.xy, r)) {
          warn(line, leg + "crosses wall walls[" + std::to_string(k) + "] (line " + std::to_string(w.line) +
                         ") outside its openings");
          break;
        }
      }
    }
    for (std::size_t k = 0; k < scene_.boxes.size(); ++k) {
      const Box& bx = scene_.boxes[k];
      if (bx.level != a.level || bx.min.z() > 0.0) continue;
      OrientedRect r;
      r.center = 0.5 * (bx.min.head<2>() + bx.max.head<2>());
      r.size = bx.max.head<2>() - bx.min.head<2>();
      r.yaw = bx.yaw_deg * M_PI / 180.0;
      if (segment_meets(a.xy, b.xy, r)) {
        warn(line,
             leg + "crosses box boxes[" + std::to_string(k) + "] (line " + std::to_string(bx.line) + ")");
      }
    }
    for (const Polygon2& v : scene_.levels[a.level].voids) {
      bool crosses = false;
      for (std::size_t e = 0; e < v.size() && !crosses && !void_holds_ramp(a.level, v); ++e) {
        crosses = segments_intersect(a.xy, b.xy, v[e], v[(e + 1) % v.size()]);
      }
      if (crosses) warn(line, leg + "crosses a void of level " + scene_.levels[a.level].name);
    }
  }
}

bool SceneParser::void_holds_ramp(int level, const Polygon2& void_polygon) const {
  for (const Ramp& r : scene_.ramps) {
    if ((r.from_level == level || r.to_level == level) && intersection_area(r.polygon, void_polygon) > 0.0)
      return true;
  }
  return false;
}

bool SceneParser::segment_meets(const Vec2& a, const Vec2& b, const OrientedRect& r) {
  if (r.contains(a) || r.contains(b)) return true;
  const Polygon2 c = r.corners();
  for (std::size_t i = 0; i < 4; ++i) {
    if (segments_intersect(a, b, c[i], c[(i + 1) % 4])) return true;
  }
  return false;
}

}  // namespace tsgraphs::scene::scene_loader_internal
