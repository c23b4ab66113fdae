#pragma once
/// Sweep registration: a spinning LiDAR's sweep registered to a local map with the sensor's
/// motion during the sweep among the unknowns, beside its pose: a continuous-time ICP with one
/// constant turn rate and velocity per sweep (the idea of CT-ICP, Dellenbach et al., ICRA 2022,
/// reduced to the de-skewing it needs). When scans are kept far apart in time (a hand-held
/// 10 Hz sensor recorded at 2 Hz) the poses around a sweep do not tell the motion inside it:
/// a hand-held sensor's pitch turns back at every step, so the motion between two poses 0.5 s
/// apart can point the other way from the 0.1 s of the sweep.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/odometry/voxel_hash_map.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::odometry {

struct SweepRegistrationConfig {
  double voxel_size = 0.375;
  double initial_distance = 1.0;
  double final_distance = 0.25;
  double kernel_divisor = 3.0;
  double point_sigma = 0.05;
  double turn_rate_sigma = 0.2;
  double velocity_sigma = 0.3;
  double pose_sigma_deg = 0.5;
  double pose_sigma = 0.1;
  int max_iterations = 10;
  double convergence_criterion = 1e-4;
  int min_correspondences = 100;
  int window = 5;
  int reduction_grain = 256;

  template <class V>
  void visit(V& v) {
    v("voxel_size", voxel_size, above(0.0, 10.0), "m; registration: one point of the sweep per voxel");
    v("initial_distance", initial_distance, above(0.0, 100.0),
      "m; registration: pairs farther apart are ignored at first (a 4 deg unmodelled turn moves a point 10 m "
      "away by 0.7 m)...");
    v("final_distance", final_distance, above(0.0, 10.0), "m; ...halved at each convergence down to this");
    v.require(initial_distance >= final_distance, "final_distance", "must be <= initial_distance");
    v("kernel_divisor", kernel_divisor, above(0.0, 1000.0),
      "registration: Geman-McClure kernel scale = pair distance / this");
    v("point_sigma", point_sigma, above(0.0, 10.0),
      "m; registration: a point's distance to the map is trusted to this, against the priors");
    v("turn_rate_sigma", turn_rate_sigma, above(0.0, 1e6),
      "rad/s; registration: the turn rate is expected within this of the poses' (decides what the sweep "
      "observes weakly: a tilting, seen on floor and ceiling only)");
    v("velocity_sigma", velocity_sigma, above(0.0, 1e6),
      "m/s; registration: the velocity, within this of the poses' (a carrier's bob changes it by a few "
      "tenths within a step; held loosely, it takes up the tilting a sweep sees weakly)");
    v("pose_sigma_deg", pose_sigma_deg, above(0.0, 1e6),
      "deg; registration: the pose at the stamp, within this of the odometry's...");
    v("pose_sigma", pose_sigma, above(0.0, 1e6),
      "m; ...and this (a sweep's tilt and its tilting during the sweep are told apart only weakly)");
    v("max_iterations", max_iterations, between(1, 1000),
      "registration: Gauss-Newton iterations per pair distance at most");
    v("convergence_criterion", convergence_criterion, above(0.0, 1.0),
      "registration: a distance is done when the update's norm falls below this");
    v("min_correspondences", min_correspondences, between(12, 1000000),
      "registration: fewer pairs: the poses' motion is kept");
    v("window", window, between(1, 1000),
      "registration: the map holds the last this many sweeps (each sweep's error averages out, the first "
      "ones' do not stay for good)");
    v("reduction_grain", reduction_grain, between(1, 1000000),
      "registration: points per block of the parallel sums (fixed: same order whatever the threads)");
  }
};

/// A sweep's pose and the motion during it.
struct SweepMotion {
  Pose3 pose = Pose3::Identity();                       ///< sensor pose at the stamp (map frame)
  Eigen::Vector3d turn_rate = Eigen::Vector3d::Zero();  ///< rad/s about the stamp frame's axes
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();   ///< m/s in the stamp frame
  bool registered = false;                              ///< false: too few pairs, the prior was kept
  int iterations = 0;                                   ///< Gauss-Newton iterations over all distances
  std::size_t num_correspondences = 0;                  ///< pairs in the last iteration

  /// The sensor's pose `seconds` after the stamp in the stamp's frame: turning at turn_rate,
  /// moving at velocity (the model of deskew()).
  Pose3 after(double seconds) const;
  /// The constant rates that take the sensor through `motion` in `seconds` (> 0).
  static SweepMotion from_motion(const Pose3& pose, const Pose3& motion, double seconds);
};

/// Registers `points` (sensor frame, measured times[i] seconds after the stamp) to `map` from
/// `prior` (its pose and rates also anchor the rates' priors): point-to-plane pairs on the map's
/// flat voxels, point-to-point on scattered ones, none on unknown ones. Deterministic.
SweepMotion align_sweep_to_map(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& times,
                               const VoxelHashMap& map, const SweepMotion& prior,
                               const SweepRegistrationConfig& config);

}  // namespace tsgraphs::odometry
