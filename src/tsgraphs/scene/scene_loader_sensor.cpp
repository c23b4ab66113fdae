#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>

#include "tsgraphs/core/yaml_map.hpp"
#include "tsgraphs/scene/platform_presets.hpp"
#include "tsgraphs/scene/scene_loader_internal.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"

namespace tsgraphs::scene::scene_loader_internal {
namespace {

// 2^24 rays: 16 times an OS0-128 at 2048 columns, far below what runs out of memory.
constexpr long long kMaxRaysPerScan = 1LL << 24;
// Bounds of the recording (and limits::kMaxLaps, kMaxSequenceScans): LiDARs sweep at 5-20 Hz,
// platforms indoors walk or drive at a few m/s; beyond these a value is a typo.
constexpr double kMaxRateHz = 1000.0;
// A range noise beyond a metre or an odometry drifting more than its own motion (per metre or
// radian) simulates no sensor: every scan would be noise, the odometry a random walk.
constexpr double kMaxRangeNoise = 1.0;     // m
constexpr double kMaxOdometryNoise = 1.0;  // per m or rad

}  // namespace

void SceneParser::parse_sensor(const YamlMap& m) {
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
    if (fov.x() < -90.0 || fov.y() > 90.0) throw m.error("vertical_fov_deg", "angles must lie in [-90, 90]");
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
    s.vertical_angles_deg = evenly_spaced_angles(s.channels, s.vertical_fov_min_deg, s.vertical_fov_max_deg);
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

void SceneParser::parse_platform(const YamlMap& m) {
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

void SceneParser::parse_odometry(const YamlMap& m) {
  m.check_keys({"trans_noise_per_m", "yaw_noise_per_rad", "yaw_noise_per_m"});
  OdometryNoise& o = scene_.odometry;
  o.trans_noise_per_m = m.get<double>("trans_noise_per_m", o.trans_noise_per_m);
  o.yaw_noise_per_rad = m.get<double>("yaw_noise_per_rad", o.yaw_noise_per_rad);
  o.yaw_noise_per_m = m.get<double>("yaw_noise_per_m", o.yaw_noise_per_m);
  require_within(m, "trans_noise_per_m", o.trans_noise_per_m, 0.0, kMaxOdometryNoise);
  require_within(m, "yaw_noise_per_rad", o.yaw_noise_per_rad, 0.0, kMaxOdometryNoise);
  require_within(m, "yaw_noise_per_m", o.yaw_noise_per_m, 0.0, kMaxOdometryNoise);
}

void SceneParser::check_mount_height() const {
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

}  // namespace tsgraphs::scene::scene_loader_internal
