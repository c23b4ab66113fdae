#include "tsgraphs/scene/scene_loader.hpp"

#include <algorithm>
#include <functional>
#include <cmath>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/core/yaml_map.hpp"
#include "tsgraphs/scene/platform_presets.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/trajectory.hpp"

namespace tsgraphs::scene {
namespace {

std::string fmt_point(const Vec2& p) {
  std::ostringstream s;
  s << "[" << p.x() << ", " << p.y() << "]";
  return s.str();
}

// 2^24 rays: 16 times an OS0-128 at 2048 columns, far below what runs out of memory.
constexpr long long kMaxRaysPerScan = 1LL << 24;
// Bounds of a person (scene `people:`, the messages name them): faster than a sprinter or
// bigger than a room is a typo.
constexpr double kMaxPersonSpeed = 10.0;  // m/s
constexpr double kMaxPersonSize = 5.0;    // m, height or radius
// Bounds of the recording (and limits::kMaxLaps, kMaxSequenceScans): LiDARs sweep at 5-20 Hz,
// platforms indoors walk or drive at a few m/s; beyond these a value is a typo.
constexpr double kMaxRateHz = 1000.0;
// Bounds of a building (core/limits.hpp): no slab or wall reaches beyond kMaxSceneCoordinate
// (UTM northings stay below 1e7 m), and together they span at most kMaxSceneExtent (no building
// is 10 km across); drawings and rasters of the scene are sized by its extent.
using limits::kMaxSceneCoordinate;
using limits::kMaxSceneExtent;
constexpr double kMaxPlatformSpeed = 30.0;  // m/s, a car
// A range noise beyond a metre or an odometry drifting more than its own motion (per metre or
// radian) simulates no sensor: every scan would be noise, the odometry a random walk.
constexpr double kMaxRangeNoise = 1.0;     // m
constexpr double kMaxOdometryNoise = 1.0;  // per m or rad

class SceneParser {
 public:
  SceneParser(const YamlMap& root, std::string base_dir) : root_(root), base_dir_(std::move(base_dir)) {}

  Scene parse() {
    root_.check_keys({"name", "seed", "sensor", "platform", "odometry", "levels", "walls", "railings",
                      "boxes", "voxel_maps", "ramps", "rooms", "people", "trajectory"});
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

 private:
  // The number of scans the path makes, against limits::kMaxSequenceScans: a slow speed or many
  // laps of a long path could otherwise fill the disk.
  void check_sequence_length() const {
    const std::string what = recording_over_limits(scene_);
    if (what.empty()) return;
    const YamlMap m = root_.map("trajectory");
    for (const char* key : {"laps", "speed"})
      if (m.has(key)) throw m.error(key, what + " (speed, laps)");
    throw m.error_here(what);
  }

  // Grows the scene's box by `points` (of `key` in `m`) and refuses a coordinate or a box
  // beyond the bounds of a building.
  void check_extent(const YamlMap& m, const std::string& key, const Polygon2& points) {
    for (const Vec2& p : points) {
      if (!(p.cwiseAbs().maxCoeff() <= kMaxSceneCoordinate))
        throw m.error(key, fmt_point(p) + " is not a coordinate within 1e7 m");
      lo_ = lo_.cwiseMin(p);
      hi_ = hi_.cwiseMax(p);
    }
    if ((hi_ - lo_).maxCoeff() > kMaxSceneExtent)
      throw m.error(key, "the scene spans " + fmt_point(hi_ - lo_) + " m: more than 10 km, no building");
  }

  static void require_positive(const YamlMap& m, const std::string& key, double v) {
    if (!(v > 0.0)) throw m.error(key, "must be > 0");
  }
  static void require_non_negative(const YamlMap& m, const std::string& key, double v) {
    if (v < 0.0) throw m.error(key, "must be >= 0");
  }
  static void require_within(const YamlMap& m, const std::string& key, double v, double lo, double hi) {
    if (!(v >= lo && v <= hi)) {
      char range[64];
      std::snprintf(range, sizeof range, "must lie in [%g, %g]", lo, hi);
      throw m.error(key, range);
    }
  }

  int level_index(const YamlMap& m, const std::string& key) const {
    const std::string name = m.require<std::string>(key);
    for (std::size_t i = 0; i < scene_.levels.size(); ++i) {
      if (scene_.levels[i].name == name) return static_cast<int>(i);
    }
    throw m.error(key, "unknown level '" + name + "'" + known_levels());
  }
  std::string known_levels() const {
    std::string s;
    for (const Level& l : scene_.levels) s += (s.empty() ? " (levels: " : ", ") + l.name;
    return s.empty() ? "" : s + ")";
  }

  // Reads a polygon and rejects repeated vertices, self-intersections and zero area.
  Polygon2 simple_polygon(const YamlMap& m, const YAML::Node& node, const std::string& where) const {
    Polygon2 poly = m.as_polygon(node, where);
    const int line = node.Mark().line + 1;
    if (const auto bad = find_self_intersection(poly)) {
      const auto [i, j] = *bad;
      const std::size_t n = poly.size();
      if (i == j) {
        throw input_error(m.file(), line,
                          where + ": repeated vertex " + fmt_point(poly[i]) + " (points " +
                              std::to_string(i) + " and " + std::to_string((i + 1) % n) + ")");
      }
      throw input_error(m.file(), line,
                        where + ": self-intersecting polygon: edge " + fmt_point(poly[i]) + "-" +
                            fmt_point(poly[(i + 1) % n]) + " meets edge " + fmt_point(poly[j]) + "-" +
                            fmt_point(poly[(j + 1) % n]));
    }
    if (area(poly) < 1e-9) throw input_error(m.file(), line, where + ": polygon has zero area");
    return poly;
  }
  Polygon2 simple_polygon(const YamlMap& m, const std::string& key) const {
    if (!m.has(key)) throw m.error_here("missing required key '" + key + "'");
    return simple_polygon(m, m.raw(key), m.key_path(key));
  }

  void parse_sensor(const YamlMap& m) {
    m.check_keys({"preset", "channels", "columns", "vertical_fov_deg", "vertical_angles_deg", "max_range",
                  "min_range", "rate_hz", "record_hz", "range_noise_std", "dropout", "mount_height",
                  "tilt_deg"});
    SensorSpec& s = scene_.sensor;
    if (m.has("preset")) {
      const std::string name = m.require<std::string>("preset");
      if (!apply_preset(name, &s)) {
        std::string list;
        for (const std::string& n : preset_names()) list += (list.empty() ? "" : ", ") + n;
        throw m.error("preset", "unknown preset '" + name + "' (presets: " + list + ")");
      }
    }
    s.channels = m.get<int>("channels", s.channels);
    s.columns = m.get<int>("columns", s.columns);
    if (s.channels < 1) throw m.error("channels", "must be >= 1");
    if (s.columns < 1) throw m.error("columns", "must be >= 1");
    if (static_cast<long long>(s.channels) * s.columns > kMaxRaysPerScan) {
      throw m.error(m.has("columns") ? "columns" : "channels",
                    "channels x columns = " + std::to_string(static_cast<long long>(s.channels) * s.columns) +
                        " rays per scan, more than the limit of " + std::to_string(kMaxRaysPerScan));
    }
    const bool layout_overridden = m.has("channels") || m.has("vertical_fov_deg");
    if (m.has("vertical_fov_deg")) {
      const Vec2 fov = m.vec2("vertical_fov_deg");
      if (!(fov.x() < fov.y()) && s.channels > 1)
        throw m.error("vertical_fov_deg", "expected [lowest, highest] with lowest < highest");
      if (fov.x() < -90.0 || fov.y() > 90.0)
        throw m.error("vertical_fov_deg", "angles must lie in [-90, 90]");
      s.vertical_fov_min_deg = fov.x();
      s.vertical_fov_max_deg = fov.y();
    }
    if (m.has("vertical_angles_deg")) {
      const YAML::Node n = m.raw("vertical_angles_deg");
      if (!n.IsSequence() || n.size() == 0)
        throw m.error("vertical_angles_deg", "expected a list of beam elevations");
      s.vertical_angles_deg.clear();
      for (std::size_t i = 0; i < n.size(); ++i) {
        const double a = m.as<double>(n[i], m.key_path("vertical_angles_deg"));
        if (a < -90.0 || a > 90.0) throw m.error("vertical_angles_deg", "angles must lie in [-90, 90]");
        s.vertical_angles_deg.push_back(a);
      }
      std::sort(s.vertical_angles_deg.begin(), s.vertical_angles_deg.end(), std::greater<>());
      if (m.has("channels") && s.channels != static_cast<int>(n.size())) {
        throw m.error("vertical_angles_deg", "has " + std::to_string(n.size()) + " beams but channels is " +
                                                 std::to_string(s.channels));
      }
      s.channels = static_cast<int>(n.size());
      s.vertical_fov_min_deg = s.vertical_angles_deg.back();
      s.vertical_fov_max_deg = s.vertical_angles_deg.front();
    } else if (layout_overridden || s.vertical_angles_deg.empty()) {
      s.vertical_angles_deg =
          evenly_spaced_angles(s.channels, s.vertical_fov_min_deg, s.vertical_fov_max_deg);
    }
    s.max_range = m.get<double>("max_range", s.max_range);
    s.min_range = m.get<double>("min_range", s.min_range);
    s.rate_hz = m.get<double>("rate_hz", s.rate_hz);
    s.record_hz = m.get<double>("record_hz", s.record_hz);
    s.range_noise_std = m.get<double>("range_noise_std", s.range_noise_std);
    s.dropout = m.get<double>("dropout", s.dropout);
    s.mount_height = m.get<double>("mount_height", s.mount_height);
    s.tilt_deg = m.get<double>("tilt_deg", s.tilt_deg);
    require_positive(m, "max_range", s.max_range);
    require_non_negative(m, "min_range", s.min_range);
    if (s.min_range >= s.max_range) throw m.error("min_range", "must be below max_range");
    require_positive(m, "rate_hz", s.rate_hz);
    if (s.rate_hz > kMaxRateHz) throw m.error("rate_hz", "must be <= 1000 Hz");
    if (m.has("record_hz") && !(s.record_hz > 0.0 && s.record_hz <= s.rate_hz))
      throw m.error("record_hz", "must lie in (0, rate_hz]");
    require_within(m, "range_noise_std", s.range_noise_std, 0.0, kMaxRangeNoise);
    if (s.dropout < 0.0 || s.dropout >= 1.0) throw m.error("dropout", "must lie in [0, 1)");
    require_positive(m, "mount_height", s.mount_height);
    if (std::abs(s.tilt_deg) > 90.0) throw m.error("tilt_deg", "must lie in [-90, 90]");
  }

  void parse_platform(const YamlMap& m) {
    m.check_keys({"type", "bob", "step_hz", "sway_deg", "yaw_jitter_deg", "vibration", "vibration_hz",
                  "motion_distortion"});
    PlatformSpec& p = scene_.platform;
    if (m.has("type")) {
      const std::string name = m.require<std::string>("type");
      const std::optional<PlatformType> type = platform_type(name);
      if (!type) throw m.error("type", "unknown platform '" + name + "' (wheeled, handheld or legged)");
      p = platform_defaults(*type);
    }
    p.bob = m.get<double>("bob", p.bob);
    p.step_hz = m.get<double>("step_hz", p.step_hz);
    p.sway_deg = m.get<double>("sway_deg", p.sway_deg);
    p.yaw_jitter_deg = m.get<double>("yaw_jitter_deg", p.yaw_jitter_deg);
    p.vibration = m.get<double>("vibration", p.vibration);
    p.vibration_hz = m.get<double>("vibration_hz", p.vibration_hz);
    p.motion_distortion = m.get<bool>("motion_distortion", p.motion_distortion);
    // Bounds that keep a sensor a sensor: a bob beyond half a metre, a sway past 30 degrees or
    // a vibration beyond 100 Hz describe no platform that walks a building.
    const auto within = [&m](const char* key, double v, double lo, double hi) {
      require_within(m, key, v, lo, hi);
    };
    within("bob", p.bob, 0.0, 0.5);
    within("step_hz", p.step_hz, 0.0, 10.0);
    within("sway_deg", p.sway_deg, 0.0, 30.0);
    within("yaw_jitter_deg", p.yaw_jitter_deg, 0.0, 30.0);
    within("vibration", p.vibration, 0.0, 0.1);
    within("vibration_hz", p.vibration_hz, 0.0, 100.0);
    if (p.bob > 0.0 && p.step_hz <= 0.0) throw m.error("step_hz", "must be > 0 when bob is");
    if (p.sway_deg > 0.0 && p.step_hz <= 0.0) throw m.error("step_hz", "must be > 0 when sway_deg is");
    if (p.vibration > 0.0 && p.vibration_hz <= 0.0)
      throw m.error("vibration_hz", "must be > 0 when vibration is");
  }

  void parse_odometry(const YamlMap& m) {
    m.check_keys({"trans_noise_per_m", "yaw_noise_per_rad", "yaw_noise_per_m"});
    OdometryNoise& o = scene_.odometry;
    o.trans_noise_per_m = m.get<double>("trans_noise_per_m", o.trans_noise_per_m);
    o.yaw_noise_per_rad = m.get<double>("yaw_noise_per_rad", o.yaw_noise_per_rad);
    o.yaw_noise_per_m = m.get<double>("yaw_noise_per_m", o.yaw_noise_per_m);
    require_within(m, "trans_noise_per_m", o.trans_noise_per_m, 0.0, kMaxOdometryNoise);
    require_within(m, "yaw_noise_per_rad", o.yaw_noise_per_rad, 0.0, kMaxOdometryNoise);
    require_within(m, "yaw_noise_per_m", o.yaw_noise_per_m, 0.0, kMaxOdometryNoise);
  }

  void parse_levels() {
    const std::vector<YamlMap> maps = root_.maps("levels");
    if (maps.empty()) throw root_.error("levels", "a scene needs at least one level");
    for (const YamlMap& m : maps) {
      m.check_keys({"name", "elevation", "ceiling", "slab", "voids"});
      Level l;
      l.line = m.line();
      l.name = m.require<std::string>("name");
      for (const Level& other : scene_.levels) {
        if (other.name == l.name) throw m.error("name", "level '" + l.name + "' is defined twice");
      }
      l.elevation = m.get<double>("elevation", 0.0);
      require_within(m, "elevation", l.elevation, -kMaxSceneExtent, kMaxSceneExtent);
      l.ceiling = m.get<double>("ceiling", 3.0);
      require_positive(m, "ceiling", l.ceiling);
      if (!m.has("slab")) throw m.error_here("level '" + l.name + "' has no slab (the outline of its floor)");
      l.slab = simple_polygon(m, "slab");
      check_extent(m, "slab", l.slab);
      if (m.has("voids")) {
        const YAML::Node vs = m.raw("voids");
        if (!vs.IsSequence()) throw m.error("voids", "expected a list of polygons");
        for (std::size_t i = 0; i < vs.size(); ++i) {
          l.voids.push_back(simple_polygon(m, vs[i], m.key_path("voids") + "[" + std::to_string(i) + "]"));
        }
      }
      scene_.levels.push_back(std::move(l));
    }
  }

  void parse_wall(const YamlMap& m) {
    m.check_keys({"level", "from", "to", "thickness", "height", "openings"});
    Wall w;
    w.line = m.line();
    w.level = level_index(m, "level");
    w.from = m.vec2("from");
    w.to = m.vec2("to");
    check_extent(m, "from", {w.from});
    check_extent(m, "to", {w.to});
    const double length = (w.to - w.from).norm();
    if (length < 1e-6)
      throw m.error("to", "zero-length wall: from and to are the same point " + fmt_point(w.from));
    w.thickness = m.get<double>("thickness", 0.2);
    w.height = m.get<double>("height", scene_.levels[w.level].ceiling);
    require_positive(m, "thickness", w.thickness);
    require_positive(m, "height", w.height);
    std::vector<std::pair<double, double>> spans;
    for (const YamlMap& om : m.maps("openings")) {
      om.check_keys({"at", "width", "height", "sill", "transmission"});
      Opening o;
      o.at = om.require<double>("at");
      o.width = om.require<double>("width");
      o.height = om.get<double>("height", 2.1);
      o.sill = om.get<double>("sill", 0.0);
      o.transmission = om.get<double>("transmission", 1.0);
      if (!(o.transmission >= 0.0 && o.transmission <= 1.0))
        throw om.error("transmission", "must lie in [0, 1]");
      require_positive(om, "width", o.width);
      require_positive(om, "height", o.height);
      require_non_negative(om, "sill", o.sill);
      if (o.width > length + 1e-9) {
        std::ostringstream s;
        s << "opening " << o.width << " m wide is wider than its wall (" << length << " m)";
        throw om.error("width", s.str());
      }
      if (o.at - 0.5 * o.width < -1e-9 || o.at + 0.5 * o.width > length + 1e-9) {
        std::ostringstream s;
        s << "opening spans " << o.at - 0.5 * o.width << " to " << o.at + 0.5 * o.width
          << " m along a wall of " << length << " m";
        throw om.error("at", s.str());
      }
      if (o.sill + o.height > w.height + 1e-9) {
        throw om.error("height", "sill + height exceeds the wall's height");
      }
      for (const auto& [lo, hi] : spans) {
        if (o.at - 0.5 * o.width < hi - 1e-9 && o.at + 0.5 * o.width > lo + 1e-9) {
          throw om.error("at", "opening overlaps another opening of the same wall");
        }
      }
      spans.emplace_back(o.at - 0.5 * o.width, o.at + 0.5 * o.width);
      w.openings.push_back(o);
    }
    std::sort(w.openings.begin(), w.openings.end(),
              [](const Opening& a, const Opening& b) { return a.at < b.at; });
    scene_.walls.push_back(std::move(w));
  }

  void parse_railing(const YamlMap& m) {
    m.check_keys({"level", "from", "to", "height", "style", "transmission"});
    Railing r;
    r.line = m.line();
    r.level = level_index(m, "level");
    r.from = m.vec2("from");
    r.to = m.vec2("to");
    check_extent(m, "from", {r.from});
    check_extent(m, "to", {r.to});
    if ((r.to - r.from).norm() < 1e-6) throw m.error("to", "zero-length railing");
    r.height = m.get<double>("height", 1.0);
    require_positive(m, "height", r.height);
    const std::string style = m.get<std::string>("style", "solid");
    if (style == "solid")
      r.style = RailingStyle::kSolid;
    else if (style == "bars")
      r.style = RailingStyle::kBars;
    else if (style == "glass")
      r.style = RailingStyle::kGlass;
    else
      throw m.error("style", "unknown railing style '" + style + "' (solid, bars, glass)");
    if (m.has("transmission") && r.style != RailingStyle::kGlass)
      throw m.error("transmission", "only a glass railing lets rays through (style: glass)");
    r.transmission = m.get<double>("transmission", r.transmission);
    if (!(r.transmission >= 0.0 && r.transmission <= 1.0))
      throw m.error("transmission", "must lie in [0, 1]");
    scene_.railings.push_back(r);
  }

  void parse_box(const YamlMap& m) {
    m.check_keys({"level", "min", "max", "yaw_deg", "label"});
    Box b;
    b.line = m.line();
    b.level = level_index(m, "level");
    b.min = vec3(m, "min");
    b.max = vec3(m, "max");
    check_extent(m, "min", {b.min.head<2>()});
    check_extent(m, "max", {b.max.head<2>()});
    require_within(m, "min", b.min.z(), -kMaxSceneExtent, kMaxSceneExtent);
    require_within(m, "max", b.max.z(), -kMaxSceneExtent, kMaxSceneExtent);
    if ((b.max - b.min).minCoeff() <= 0.0) throw m.error("max", "must exceed min on every axis");
    b.yaw_deg = m.get<double>("yaw_deg", 0.0);
    b.label = m.get<std::string>("label", "box");
    scene_.boxes.push_back(b);
  }

  Eigen::Vector3d vec3(const YamlMap& m, const std::string& key) const {
    const YAML::Node n = m.raw(key);
    if (!n.IsDefined() || n.IsNull()) throw m.error_here("missing required key '" + key + "'");
    if (!n.IsSequence() || n.size() != 3) throw m.error(key, "expected [x, y, z]");
    return {m.as<double>(n[0], m.key_path(key)), m.as<double>(n[1], m.key_path(key)),
            m.as<double>(n[2], m.key_path(key))};
  }

  void parse_voxel_map(const YamlMap& m) {
    m.check_keys({"file", "voxel_size", "level", "label", "offset", "yaw_deg"});
    VoxelMap v;
    v.line = m.line();
    const std::string file = m.require<std::string>("file");
    const std::filesystem::path p(file);
    v.file =
        p.is_absolute() ? p.string() : (std::filesystem::path(base_dir_) / p).lexically_normal().string();
    if (!std::filesystem::is_regular_file(v.file)) throw m.error("file", "no such file: " + v.file);
    v.voxel_size = m.require<double>("voxel_size");
    require_positive(m, "voxel_size", v.voxel_size);
    v.level = level_index(m, "level");
    const std::string label = m.get<std::string>("label", "auto");
    if (label == "wall")
      v.label = VoxelLabel::kWall;
    else if (label == "box")
      v.label = VoxelLabel::kBox;
    else if (label == "railing")
      v.label = VoxelLabel::kRailing;
    else if (label == "auto")
      v.label = VoxelLabel::kAuto;
    else
      throw m.error("label", "unknown voxel label '" + label + "' (wall, box, railing, auto)");
    v.offset = m.has("offset") ? vec3(m, "offset") : Eigen::Vector3d::Zero();
    check_extent(m, "offset", {v.offset.head<2>()});
    require_within(m, "offset", v.offset.z(), -kMaxSceneExtent, kMaxSceneExtent);
    v.yaw_deg = m.get<double>("yaw_deg", 0.0);
    scene_.voxel_maps.push_back(v);
  }

  void parse_ramp(const YamlMap& m) {
    m.check_keys({"from_level", "to_level", "polygon", "axis"});
    Ramp r;
    r.line = m.line();
    r.from_level = level_index(m, "from_level");
    r.to_level = level_index(m, "to_level");
    if (r.from_level == r.to_level) throw m.error("to_level", "a ramp joins two different levels");
    r.polygon = simple_polygon(m, "polygon");
    r.axis = m.vec2("axis");
    if (r.axis.norm() < 1e-9) throw m.error("axis", "must be a non-zero direction");
    r.axis.normalize();
    scene_.ramps.push_back(r);
  }

  void parse_room(const YamlMap& m) {
    m.check_keys({"name", "level", "polygon"});
    Room r;
    r.name = m.require<std::string>("name");
    r.level = level_index(m, "level");
    r.polygon = simple_polygon(m, "polygon");
    scene_.rooms.push_back(r);
  }

  void parse_person(const YamlMap& m) {
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

  // A sensor at or above the ceiling of a level the path walks sees nothing of that level.
  void check_mount_height() const {
    const double h = scene_.sensor.mount_height;
    for (const Waypoint& w : scene_.trajectory.waypoints) {
      const Level& l = scene_.levels[w.level];
      if (h < l.ceiling) continue;
      char what[200];
      std::snprintf(what, sizeof what,
                    "%g m is not below the ceiling of level '%s' (%g m), which the path walks", h,
                    l.name.c_str(), l.ceiling);
      const YamlMap m = root_.map("sensor");
      throw m.has("mount_height") ? m.error("mount_height", what)
                                  : m.error_here(std::string("mount_height: ") + what);
    }
  }

  void parse_trajectory(const YamlMap& m) {
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

  void check_waypoint(const Waypoint& w, const std::string& where) const {
    const Level& level = scene_.levels[w.level];
    double z = 0.0;
    if (!walkable_height(scene_, w.level, w.xy, &z)) {
      throw input_error(root_.file(), w.line,
                        where + ": " + fmt_point(w.xy) + " is outside every slab of level " + level.name +
                            " (or in a void)");
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

  void warn(int line, const std::string& what) {
    scene_.warnings.push_back(root_.file() + ":" + std::to_string(line) + ": " + what);
  }

  // Straight legs of the path that pass through a wall (outside a door), a box standing on
  // the floor or a void: the simulator would carry the sensor through them.
  void warn_about_path() {
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

  // True when the void is the opening of a ramp joining `level` (the ramp is walked over it).
  bool void_holds_ramp(int level, const Polygon2& void_polygon) const {
    for (const Ramp& r : scene_.ramps) {
      if ((r.from_level == level || r.to_level == level) && intersection_area(r.polygon, void_polygon) > 0.0)
        return true;
    }
    return false;
  }

  static bool segment_meets(const Vec2& a, const Vec2& b, const OrientedRect& r) {
    if (r.contains(a) || r.contains(b)) return true;
    const Polygon2 c = r.corners();
    for (std::size_t i = 0; i < 4; ++i) {
      if (segments_intersect(a, b, c[i], c[(i + 1) % 4])) return true;
    }
    return false;
  }

  // A ceiling above the floor of the storey on top of it (where their slabs overlap).
  void warn_about_storeys() {
    for (const Level& low : scene_.levels) {
      for (const Level& high : scene_.levels) {
        if (high.elevation <= low.elevation || low.elevation + low.ceiling <= high.elevation + 1e-9) continue;
        if (intersection_area(low.slab, high.slab) <= 0.0) continue;
        std::ostringstream msg;
        msg << "levels: the ceiling of " << low.name << " (z " << low.elevation + low.ceiling
            << ") is above the floor of " << high.name << " (z " << high.elevation << ")";
        warn(high.line, msg.str());
      }
    }
  }

  const YamlMap& root_;
  std::string base_dir_;
  Scene scene_;
  Vec2 lo_ = Vec2::Constant(std::numeric_limits<double>::infinity());  // the slabs' and walls' box so far
  Vec2 hi_ = -Vec2::Constant(std::numeric_limits<double>::infinity());
};

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir) {
  const YamlMap root = YamlMap::load_string(text, file);
  Scene scene = SceneParser(root, base_dir).parse();
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
