#include "tsgraphs/scene/scene_writer.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "tsgraphs/scene/platform_presets.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"

namespace tsgraphs::scene {
namespace {

/// A length to 0.1 mm, without trailing zeros.
std::string num(double v) {
  if (std::abs(v) < 5e-5) v = 0.0;
  char text[64];
  std::snprintf(text, sizeof(text), "%.4f", v);
  std::string s = text;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

/// A rate, a noise figure or an angle: the shortest text that reads back as the same double.
std::string fig(double v) {
  char text[64];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(text, sizeof(text), "%.*g", digits, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string point(const Vec2& p) { return "[" + num(p.x()) + ", " + num(p.y()) + "]"; }

std::string polygon(const Polygon2& poly) {
  std::string s = "[";
  for (std::size_t i = 0; i < poly.size(); ++i) s += (i ? ", " : "") + point(poly[i]);
  return s + "]";
}

const char* railing_style(RailingStyle s) {
  switch (s) {
    case RailingStyle::kSolid:
      return "solid";
    case RailingStyle::kBars:
      return "bars";
    case RailingStyle::kGlass:
      return "glass";
  }
  return "solid";
}

const char* voxel_label(VoxelLabel l) {
  switch (l) {
    case VoxelLabel::kWall:
      return "wall";
    case VoxelLabel::kBox:
      return "box";
    case VoxelLabel::kRailing:
      return "railing";
    case VoxelLabel::kAuto:
      return "auto";
  }
  return "auto";
}

std::string level_name(const Scene& scene, int i) { return quoted(scene.levels.at(i).name); }

void write_sensor(std::ostream& out, const SensorSpec& s) {
  out << "sensor:\n";
  SensorSpec preset;
  const bool has_preset = !s.preset.empty() && apply_preset(s.preset, &preset);
  if (has_preset) out << "  preset: " << s.preset << "\n";
  if (!has_preset || s.vertical_angles_deg != preset.vertical_angles_deg || s.columns != preset.columns) {
    out << "  columns: " << s.columns << "\n";
    if (s.vertical_angles_deg.empty()) {
      out << "  channels: " << s.channels << "\n  vertical_fov_deg: [" << fig(s.vertical_fov_min_deg) << ", "
          << fig(s.vertical_fov_max_deg) << "]\n";
    } else {
      out << "  vertical_angles_deg: [";
      for (std::size_t i = 0; i < s.vertical_angles_deg.size(); ++i)
        out << (i ? ", " : "") << fig(s.vertical_angles_deg[i]);
      out << "]\n";
    }
  }
  if (!has_preset || s.max_range != preset.max_range) out << "  max_range: " << fig(s.max_range) << "\n";
  if (!has_preset || s.min_range != preset.min_range) out << "  min_range: " << fig(s.min_range) << "\n";
  if (!has_preset || s.rate_hz != preset.rate_hz) out << "  rate_hz: " << fig(s.rate_hz) << "\n";
  if (s.record_hz > 0.0) out << "  record_hz: " << fig(s.record_hz) << "\n";
  if (!has_preset || s.range_noise_std != preset.range_noise_std)
    out << "  range_noise_std: " << fig(s.range_noise_std) << "\n";
  if (s.dropout > 0.0) out << "  dropout: " << fig(s.dropout) << "\n";
  out << "  mount_height: " << num(s.mount_height) << "\n";
  if (s.tilt_deg != 0.0) out << "  tilt_deg: " << fig(s.tilt_deg) << "\n";
}

/// Written only when it is not the wheeled platform's defaults.
void write_platform(std::ostream& out, const PlatformSpec& pf) {
  const PlatformSpec wheeled = platform_defaults(PlatformType::kWheeled);
  if (pf.type == PlatformType::kWheeled && pf.bob == wheeled.bob && pf.sway_deg == wheeled.sway_deg &&
      pf.yaw_jitter_deg == wheeled.yaw_jitter_deg && pf.vibration == wheeled.vibration &&
      pf.motion_distortion == wheeled.motion_distortion)
    return;
  out << "\nplatform:\n  type: " << platform_name(pf.type) << "\n  bob: " << fig(pf.bob)
      << "\n  step_hz: " << fig(pf.step_hz) << "\n  sway_deg: " << fig(pf.sway_deg)
      << "\n  yaw_jitter_deg: " << fig(pf.yaw_jitter_deg) << "\n  vibration: " << fig(pf.vibration)
      << "\n  vibration_hz: " << fig(pf.vibration_hz)
      << "\n  motion_distortion: " << (pf.motion_distortion ? "true" : "false") << "\n";
}

void write_levels(std::ostream& out, const std::vector<Level>& levels) {
  out << "\nlevels:\n";
  for (const Level& l : levels) {
    out << "  - name: " << quoted(l.name) << "\n    elevation: " << num(l.elevation)
        << "\n    ceiling: " << num(l.ceiling) << "\n    slab: " << polygon(l.slab) << "\n";
    if (!l.voids.empty()) {
      out << "    voids:\n";
      for (const Polygon2& v : l.voids) out << "      - " << polygon(v) << "\n";
    }
  }
}

void write_walls(std::ostream& out, const Scene& scene) {
  if (scene.walls.empty()) return;
  out << "\nwalls:\n";
  for (const Wall& w : scene.walls) {
    out << "  - {level: " << level_name(scene, w.level) << ", from: " << point(w.from)
        << ", to: " << point(w.to) << ", thickness: " << num(w.thickness) << ", height: " << num(w.height);
    if (!w.openings.empty()) {
      out << ", openings: [";
      for (std::size_t i = 0; i < w.openings.size(); ++i) {
        const Opening& o = w.openings[i];
        out << (i ? ", " : "") << "{at: " << num(o.at) << ", width: " << num(o.width)
            << ", height: " << num(o.height) << ", sill: " << num(o.sill);
        if (o.transmission < 1.0) out << ", transmission: " << num(o.transmission);
        out << "}";
      }
      out << "]";
    }
    out << "}\n";
  }
}

/// Railings, boxes, voxel maps and ramps: what stands in the building besides its walls.
void write_furnishings(std::ostream& out, const Scene& scene) {
  if (!scene.railings.empty()) out << "\nrailings:\n";
  for (const Railing& r : scene.railings) {
    out << "  - {level: " << level_name(scene, r.level) << ", from: " << point(r.from)
        << ", to: " << point(r.to) << ", height: " << num(r.height) << ", style: " << railing_style(r.style);
    if (r.style == RailingStyle::kGlass) out << ", transmission: " << fig(r.transmission);
    out << "}\n";
  }
  if (!scene.boxes.empty()) out << "\nboxes:\n";
  for (const Box& b : scene.boxes) {
    out << "  - {level: " << level_name(scene, b.level) << ", min: [" << num(b.min.x()) << ", "
        << num(b.min.y()) << ", " << num(b.min.z()) << "], max: [" << num(b.max.x()) << ", " << num(b.max.y())
        << ", " << num(b.max.z()) << "]";
    if (b.yaw_deg != 0.0) out << ", yaw_deg: " << fig(b.yaw_deg);
    out << ", label: " << quoted(b.label) << "}\n";
  }
  if (!scene.voxel_maps.empty()) out << "\nvoxel_maps:\n";
  for (const VoxelMap& v : scene.voxel_maps) {
    out << "  - {file: " << quoted(v.file) << ", voxel_size: " << fig(v.voxel_size)
        << ", level: " << level_name(scene, v.level) << ", label: " << voxel_label(v.label) << ", offset: ["
        << num(v.offset.x()) << ", " << num(v.offset.y()) << ", " << num(v.offset.z())
        << "], yaw_deg: " << fig(v.yaw_deg) << "}\n";
  }
  if (!scene.ramps.empty()) out << "\nramps:\n";
  for (const Ramp& r : scene.ramps) {
    out << "  - {from_level: " << level_name(scene, r.from_level)
        << ", to_level: " << level_name(scene, r.to_level) << ", polygon: " << polygon(r.polygon)
        << ", axis: [" << fig(r.axis.x()) << ", " << fig(r.axis.y()) << "]}\n";
  }
}

void write_rooms_and_people(std::ostream& out, const Scene& scene) {
  if (!scene.rooms.empty()) out << "\nrooms:\n";
  for (const Room& r : scene.rooms)
    out << "  - {name: " << quoted(r.name) << ", level: " << level_name(scene, r.level)
        << ", polygon: " << polygon(r.polygon) << "}\n";
  if (!scene.people.empty()) out << "\npeople:\n";
  for (const Person& p : scene.people) {
    out << "  - {level: " << level_name(scene, p.level) << ", path: [";
    for (std::size_t i = 0; i < p.path.size(); ++i) out << (i ? ", " : "") << point(p.path[i]);
    out << "], speed: " << fig(p.speed) << ", offset: " << fig(p.offset) << ", height: " << num(p.height)
        << ", radius: " << num(p.radius) << "}\n";
  }
}

/// A waypoint names its level only where the path changes level.
void write_trajectory(std::ostream& out, const Scene& scene) {
  const TrajectorySpec& t = scene.trajectory;
  out << "\ntrajectory:\n  level: " << level_name(scene, t.level) << "\n  waypoints:\n";
  int level = t.level;
  for (std::size_t i = 0; i < t.waypoints.size(); ++i) {
    const Waypoint& w = t.waypoints[i];
    out << "    - [" << num(w.xy.x()) << ", " << num(w.xy.y());
    if (w.level != level || (i == 0 && w.level != t.level)) out << ", " << level_name(scene, w.level);
    level = w.level;
    out << "]\n";
  }
  out << "  closed: " << (t.closed ? "true" : "false") << "\n  laps: " << t.laps
      << "\n  speed: " << fig(t.speed) << "\n  yaw_rate_deg: " << fig(t.yaw_rate_deg) << "\n";
}

}  // namespace

std::string scene_yaml(const Scene& scene, const std::string& header) {
  std::ostringstream out;
  if (!header.empty()) {
    std::istringstream lines(header);
    for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
    out << "\n";
  }
  out << "name: " << quoted(scene.name) << "\n";
  out << "seed: " << scene.seed << "\n\n";
  write_sensor(out, scene.sensor);
  write_platform(out, scene.platform);
  out << "\nodometry:\n  trans_noise_per_m: " << fig(scene.odometry.trans_noise_per_m)
      << "\n  yaw_noise_per_rad: " << fig(scene.odometry.yaw_noise_per_rad)
      << "\n  yaw_noise_per_m: " << fig(scene.odometry.yaw_noise_per_m) << "\n";
  write_levels(out, scene.levels);
  write_walls(out, scene);
  write_furnishings(out, scene);
  write_rooms_and_people(out, scene);
  write_trajectory(out, scene);
  return out.str();
}

}  // namespace tsgraphs::scene
