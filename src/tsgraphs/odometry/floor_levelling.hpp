#pragma once
/// Where the map frame starts when nothing gives the sensor's mount: level with the floor under
/// the first scan. The pipeline takes z as up (walls are vertical planes, the ground's normals
/// point up); a handheld or tilted sensor's own frame would tilt the whole map.
#include <cstddef>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::odometry {

struct FloorLevellingConfig {
  double min_range = 1.0;
  double max_range = 10.0;  ///< nor farther ones (m): sparse rings, other rooms
  double min_depth = 0.2;
  double max_tilt_deg = 30.0;
  double distance_threshold = 0.05;
  int min_inliers = 200;
  double cell_size = 0.25;
  int min_cells = 50;
  double below_margin = 0.3;
  int max_iterations = 1000;
  double ransac_probability = 0.9999;

  template <class V>
  void visit(V& v) {
    v("min_range", min_range, between(0.0, 1000.0),
      "m; floor points nearer than this are not used (the platform, the operator's feet)");
    v("max_range", max_range, above(0.0, 1000.0), "m; nor farther ones");
    v.require(max_range > min_range, "max_range", "must be > min_range");
    v("min_depth", min_depth, between(0.0, 100.0),
      "m; the floor lies at least this far below the sensor (along its z)");
    v("max_tilt_deg", max_tilt_deg, above(0.0, 89.0),
      "the floor's normal is within this of the sensor's z axis");
    v("distance_threshold", distance_threshold, above(0.0, 10.0), "m; RANSAC inlier distance");
    v("min_inliers", min_inliers, between(3, 10000000),
      "fewer inliers: no floor found (the map frame is then the first scan's)");
    v("cell_size", cell_size, between(0.01, 10.0),
      "m; grid cell of the lowest points the floor is fitted to");
    v("min_cells", min_cells, between(3, 10000000), "fewer cells on the floor: no floor found");
    v("below_margin", below_margin, between(0.0, 100.0),
      "m; returns this far below a plane are beneath it: a floor has fewer than it holds");
    v("max_iterations", max_iterations, between(1, 1000000), "RANSAC iterations at most");
    v("ransac_probability", ransac_probability, above(0.0, 0.999999999),
      "RANSAC stops once this sure to have drawn one all-floor sample");
  }
};

/// The floor under a scan, and the sensor's pose in a frame level with it.
struct FloorLevel {
  bool found = false;
  /// Level frame <- sensor: the rotation that makes the floor's normal z (no turn about z),
  /// and the sensor's height above the floor, so the floor is at z = 0. Identity when not found.
  Pose3 sensor_pose = Pose3::Identity();
  double height = 0.0;    ///< the sensor above the floor (m)
  double tilt_deg = 0.0;  ///< the angle between the sensor's z and the floor's normal
  std::size_t num_inliers = 0;
};

/// The floor below the sensor: a plane whose normal is within max_tilt_deg of the sensor's z,
/// fitted (RANSAC with a fixed seed: the same scan gives the same answer, then least squares)
/// to the lowest point of each grid cell, so that a scanner's ring traces on walls above the
/// floor do not tilt it.
FloorLevel level_from_floor(const PointCloud& scan, const FloorLevellingConfig& config = {});

}  // namespace tsgraphs::odometry
