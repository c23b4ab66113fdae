#include "tsgraphs/pipeline/platform.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tsgraphs::pipeline {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
/// A beam less steep than this below the horizon meets no floor within any ground range.
constexpr double kMinDownwardBeamDeg = 0.5;

std::string fixed(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

}  // namespace

Platform resolve_platform(const PlatformConfig& config, const odometry::FloorLevellingConfig& levelling,
                          const ground::GroundConfig& ground, const std::vector<PointCloud>& scans,
                          const std::vector<Eigen::Vector3d>& ups) {
  check_config(config, "PlatformConfig");
  Platform p;
  p.estimate = odometry::estimate_platform(scans, levelling, config.measure, ups);
  const odometry::PlatformEstimate& e = p.estimate;

  if (config.sensor_height) {
    p.sensor_height = *config.sensor_height;
    p.sensor_height_source = "config";
  } else if (e.height_found) {
    p.sensor_height = e.height;
    p.sensor_height_source = "measured";
  } else {
    p.sensor_height = config.fallback_sensor_height;
    p.sensor_height_source = "fallback";
    p.warnings.push_back("no floor found under the " + std::to_string(e.scans_measured) +
                         " scans measured: the sensor is taken to be " + fixed(p.sensor_height, 2) +
                         " m above the floor (platform.fallback_sensor_height; give platform.sensor_height)");
  }

  if (config.seed_radius) {
    p.seed_radius = *config.seed_radius;
    p.seed_radius_source = "config";
  } else {
    // The first floor ring lies where the lowest beam meets the floor; on the side the sensor
    // leans away from, that beam is shallower by the tilt.
    const double below_deg = -e.beams.lowest_deg - e.tilt_deg;
    if (e.beams.rings > 0 && below_deg > kMinDownwardBeamDeg) {
      const double reach = p.sensor_height / std::tan(below_deg * kDegToRad) + config.seed_radius_margin;
      p.seed_radius = std::max(config.min_seed_radius, std::min(reach, ground.max_range));
      p.seed_radius_source = "beams";
    } else {
      p.seed_radius = config.min_seed_radius;
      p.seed_radius_source = "default";
    }
  }

  if (config.preset == "auto") {
    p.preset = ground::preset_for_ring_spacing(e.beams.spacing_deg);
    p.preset_source = p.preset.empty() ? "none" : "beams";
    if (p.preset.empty())
      p.warnings.push_back(
          "no beam layout found in the " + std::to_string(e.scans_measured) +
          " scans measured: the ground keeps its ring-density settings (give platform.preset)");
  } else if (config.preset == "none") {
    p.preset_source = "none";
  } else {
    p.preset = config.preset;
    p.preset_source = "config";
  }
  return p;
}

ground::GroundConfig apply_platform(const Platform& platform, ground::GroundConfig ground,
                                    const std::set<std::string>& given) {
  ground.sensor_height = platform.sensor_height;
  ground.seed_radius = platform.seed_radius;
  if (!platform.preset.empty())
    ground::copy_ring_density_fields(ground::per_sensor_preset(platform.preset), &ground,
                                     [&given](const char* key) { return given.count(key) > 0; });
  // The beams measured are the sensor's own: nearer the truth than a preset's nominal spacing.
  if (platform.estimate.beams.spacing_deg > 0.0)
    ground.ring_spacing_deg = platform.estimate.beams.spacing_deg;
  return ground;
}

std::string describe(const Platform& p) {
  const odometry::PlatformEstimate& e = p.estimate;
  std::string text = "sensor " + fixed(p.sensor_height, 2) + " m above the floor (";
  if (p.sensor_height_source == "measured") {
    text += "measured in " + std::to_string(e.floors_found) + " of " + std::to_string(e.scans_measured) +
            " scans, spread " + fixed(e.height_spread, 2) + " m), tilted " + fixed(e.tilt_deg, 1) + " deg";
  } else {
    text += p.sensor_height_source == "config" ? "platform.sensor_height)" : "fallback: no floor found)";
  }
  if (e.beams.rings > 0)
    text += "; " + std::to_string(e.beams.rings) + " rings " + fixed(e.beams.spacing_deg, 2) +
            " deg apart, lowest " + fixed(e.beams.lowest_deg, 1) + " deg";
  text +=
      "; ground preset " + (p.preset.empty() ? std::string("none") : p.preset) + " (" + p.preset_source + ")";
  text += "; seed radius " + fixed(p.seed_radius, 1) + " m (" + p.seed_radius_source + ")";
  return text;
}

}  // namespace tsgraphs::pipeline
