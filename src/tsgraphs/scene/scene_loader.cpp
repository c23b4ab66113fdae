#include "tsgraphs/scene/scene_loader.hpp"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/core/yaml_map.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/scene_loader_internal.hpp"
#include "tsgraphs/scene/trajectory.hpp"

namespace tsgraphs::scene {
namespace scene_loader_internal {
namespace {

// Bounds of a building (core/limits.hpp): no slab or wall reaches beyond kMaxSceneCoordinate
// (UTM northings stay below 1e7 m), and together they span at most kMaxSceneExtent (no building
// is 10 km across); drawings and rasters of the scene are sized by its extent.
using limits::kMaxSceneCoordinate;
using limits::kMaxSceneExtent;

}  // namespace

std::string fmt_point(const Vec2& p) {
  std::ostringstream s;
  s << "[" << p.x() << ", " << p.y() << "]";
  return s.str();
}

Scene SceneParser::parse() {
  root_.check_keys({"name", "seed", "sensor", "platform", "odometry", "levels", "walls", "railings", "boxes",
                    "voxel_maps", "ramps", "rooms", "people", "trajectory"});
  scene_.file = root_.file();
  scene_.name = root_.get<std::string>("name", std::filesystem::path(root_.file()).stem().string());
  const long long seed = root_.get<long long>("seed", 0);
  if (seed < 0) throw root_.error("seed", "must be >= 0");
  scene_.seed = static_cast<std::uint64_t>(seed);
  parse_sensor(root_.map("sensor"));
  parse_platform(root_.map("platform"));
  parse_odometry(root_.map("odometry"));
  parse_levels();
  for (const YamlMap& m : root_.maps("walls")) parse_wall(m);
  for (const YamlMap& m : root_.maps("railings")) parse_railing(m);
  for (const YamlMap& m : root_.maps("boxes")) parse_box(m);
  for (const YamlMap& m : root_.maps("voxel_maps")) parse_voxel_map(m);
  for (const YamlMap& m : root_.maps("ramps")) parse_ramp(m);
  for (const YamlMap& m : root_.maps("rooms")) parse_room(m);
  for (const YamlMap& m : root_.maps("people")) parse_person(m);
  parse_trajectory(root_.map("trajectory"));
  check_mount_height();
  check_sequence_length();
  join_wall_ends(&scene_);
  warn_about_path();
  warn_about_storeys();
  return std::move(scene_);
}

void SceneParser::check_extent(const YamlMap& m, const std::string& key, const Polygon2& points) {
  for (const Vec2& p : points) {
    if (!(p.cwiseAbs().maxCoeff() <= kMaxSceneCoordinate))
      throw m.error(key, fmt_point(p) + " is not a coordinate within 1e7 m");
    lo_ = lo_.cwiseMin(p);
    hi_ = hi_.cwiseMax(p);
  }
  if ((hi_ - lo_).maxCoeff() > kMaxSceneExtent)
    throw m.error(key, "the scene spans " + fmt_point(hi_ - lo_) + " m: more than 10 km, no building");
}

void SceneParser::require_positive(const YamlMap& m, const std::string& key, double v) {
  if (!(v > 0.0)) throw m.error(key, "must be > 0");
}

void SceneParser::require_non_negative(const YamlMap& m, const std::string& key, double v) {
  if (v < 0.0) throw m.error(key, "must be >= 0");
}

void SceneParser::require_within(const YamlMap& m, const std::string& key, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi)) {
    char range[64];
    std::snprintf(range, sizeof range, "must lie in [%g, %g]", lo, hi);
    throw m.error(key, range);
  }
}

int SceneParser::level_index(const YamlMap& m, const std::string& key) const {
  const std::string name = m.require<std::string>(key);
  for (std::size_t i = 0; i < scene_.levels.size(); ++i) {
    if (scene_.levels[i].name == name) return static_cast<int>(i);
  }
  throw m.error(key, "unknown level '" + name + "'" + known_levels());
}

std::string SceneParser::known_levels() const {
  std::string s;
  for (const Level& l : scene_.levels) s += (s.empty() ? " (levels: " : ", ") + l.name;
  return s.empty() ? "" : s + ")";
}

Polygon2 SceneParser::simple_polygon(const YamlMap& m, const YAML::Node& node,
                                     const std::string& where) const {
  Polygon2 poly = m.as_polygon(node, where);
  const int line = node.Mark().line + 1;
  if (const auto bad = find_self_intersection(poly)) {
    const auto [i, j] = *bad;
    const std::size_t n = poly.size();
    if (i == j) {
      throw input_error(m.file(), line,
                        where + ": repeated vertex " + fmt_point(poly[i]) + " (points " + std::to_string(i) +
                            " and " + std::to_string((i + 1) % n) + ")");
    }
    throw input_error(m.file(), line,
                      where + ": self-intersecting polygon: edge " + fmt_point(poly[i]) + "-" +
                          fmt_point(poly[(i + 1) % n]) + " meets edge " + fmt_point(poly[j]) + "-" +
                          fmt_point(poly[(j + 1) % n]));
  }
  if (area(poly) < 1e-9) throw input_error(m.file(), line, where + ": polygon has zero area");
  return poly;
}

Polygon2 SceneParser::simple_polygon(const YamlMap& m, const std::string& key) const {
  if (!m.has(key)) throw m.error_here("missing required key '" + key + "'");
  return simple_polygon(m, m.raw(key), m.key_path(key));
}

Eigen::Vector3d SceneParser::vec3(const YamlMap& m, const std::string& key) const {
  const YAML::Node n = m.raw(key);
  if (!n.IsDefined() || n.IsNull()) throw m.error_here("missing required key '" + key + "'");
  if (!n.IsSequence() || n.size() != 3) throw m.error(key, "expected [x, y, z]");
  return {m.as<double>(n[0], m.key_path(key)), m.as<double>(n[1], m.key_path(key)),
          m.as<double>(n[2], m.key_path(key))};
}

void SceneParser::warn(int line, const std::string& what) {
  scene_.warnings.push_back(root_.file() + ":" + std::to_string(line) + ": " + what);
}

}  // namespace scene_loader_internal

Scene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir) {
  const YamlMap root = YamlMap::load_string(text, file);
  Scene scene = scene_loader_internal::SceneParser(root, base_dir).parse();
  scene.source_text = text;
  return scene;
}

double sequence_scans(const Scene& scene) {
  const double hz = scene.sensor.record_hz > 0.0 ? scene.sensor.record_hz : scene.sensor.rate_hz;
  // Laps after the first repeat the second's duration (an open path's odd laps walk it back), so
  // one and two laps give every count.
  Scene probe = scene;
  probe.trajectory.laps = 1;
  const double one = Trajectory(probe).duration();
  if (scene.trajectory.laps <= 1) return one * hz + 1.0;
  probe.trajectory.laps = 2;
  const double two = Trajectory(probe).duration();
  return (one + (two - one) * (scene.trajectory.laps - 1)) * hz + 1.0;
}

std::string recording_over_limits(const Scene& scene) {
  const int laps = scene.trajectory.laps;
  if (laps < 1 || laps > limits::kMaxLaps)
    return std::to_string(laps) + " laps, more than " + std::to_string(limits::kMaxLaps);
  const double scans = sequence_scans(scene);
  if (scans <= limits::kMaxSequenceScans) return "";
  char what[160];
  std::snprintf(what, sizeof what, "the path makes %.3g scans, more than %.0f", scans,
                limits::kMaxSequenceScans);
  return what;
}

Scene load_scene(const std::string& file) {
  const std::string text = read_text_file(file);
  const std::string base = std::filesystem::path(file).parent_path().string();
  return parse_scene(text, file, base.empty() ? "." : base);
}

}  // namespace tsgraphs::scene
