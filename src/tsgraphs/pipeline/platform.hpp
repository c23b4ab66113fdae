#pragma once
/// The platform the sensor rides on, as the pipeline uses it: the sensor's height above the
/// floor, where the ground search may start, and the ground's settings for the density of the
/// floor's rings. Each is measured from scans spread over the run (odometry/platform_estimate.hpp) unless
/// the configuration gives it.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/odometry/floor_levelling.hpp"
#include "tsgraphs/odometry/platform_estimate.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::pipeline {

/// The `platform` section of the parameters. `auto` (unset) values are measured.
struct PlatformConfig {
  std::optional<double> sensor_height;
  std::optional<double> seed_radius;
  std::string preset = "auto";
  double seed_radius_margin = 1.5;
  double min_seed_radius = 3.0;
  double fallback_sensor_height = 0.55;
  odometry::PlatformEstimateConfig measure;  ///< how the scans are measured

  template <class V>
  void visit(V& v) {
    v("sensor_height", sensor_height, above(0.0, 100.0),
      "m above the floor under the robot; auto: the median floor under the scans measured");
    v("seed_radius", seed_radius, above(0.0, 1000.0),
      "m; the ground search starts within this; auto: where the lowest beam meets the floor + "
      "seed_radius_margin");
    v("preset", preset, Words{"auto", "none", "os1-64", "os0-128", "vlp-16", "hesai-xt32"},
      "the ground's ring-density settings: auto (from the measured ring spacing) | os1-64 | os0-128 | vlp-16 "
      "| hesai-xt32 | none");
    v("seed_radius_margin", seed_radius_margin, between(0.0, 100.0),
      "m beyond the first floor ring (it is thin: seeds come from the next rings too)");
    v("min_seed_radius", min_seed_radius, above(0.0, 1000.0), "m; an auto seed radius is never smaller");
    v("fallback_sensor_height", fallback_sensor_height, above(0.0, 100.0),
      "m; used, with a warning, when no floor is found under the scans measured");
    measure.visit(v);
  }
};

/// The platform resolved: every value the pipeline uses, and where each came from.
struct Platform {
  odometry::PlatformEstimate estimate;
  double sensor_height = 0.0;        ///< m
  std::string sensor_height_source;  ///< "measured", "config" or "fallback"
  double seed_radius = 0.0;          ///< m
  std::string
      seed_radius_source;     ///< "beams" (the rule above), "config" or "default" (no ring below the horizon)
  std::string preset;         ///< the ground settings' preset, "" for none
  std::string preset_source;  ///< "beams", "config" or "none"
  std::vector<std::string> warnings;  ///< what could not be measured, one line each
};

/// Resolves the platform from `config` and scans of the run (sensor frames; `ups`, empty or
/// one per scan: the gravity's up in each, when the poses give it).
Platform resolve_platform(const PlatformConfig& config, const odometry::FloorLevellingConfig& levelling,
                          const ground::GroundConfig& ground, const std::vector<PointCloud>& scans,
                          const std::vector<Eigen::Vector3d>& ups = {});

/// `ground` with the platform's values: the height, the seed radius, and the preset's
/// ring-density fields except those named in `given` ("num_min_pts", "max_gap": set by the
/// user's parameter file).
ground::GroundConfig apply_platform(const Platform& platform, ground::GroundConfig ground,
                                    const std::set<std::string>& given = {});

/// One line for a log: "sensor 1.62 m above the floor (measured in 9 of 10 scans), ...".
std::string describe(const Platform& platform);

}  // namespace tsgraphs::pipeline
