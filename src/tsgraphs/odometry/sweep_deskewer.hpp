#pragma once
/// De-skewing a run of scans by sweep registration (sweep_registration.hpp) against a local
/// map of the last few sweeps, for scans whose poses come from elsewhere (given odometry).
#include <cstddef>
#include <deque>
#include <vector>

#include <Eigen/Core>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"
#include "tsgraphs/odometry/sweep_registration.hpp"
#include "tsgraphs/odometry/voxel_hash_map.hpp"

namespace tsgraphs::odometry {

/// De-skews a run of scans by registering each sweep to a local map of the last few before it
/// (de-skewed, placed at their poses). The map's voxels, range and surfaces follow the LiDAR
/// odometry's config.
class SweepDeskewer {
 public:
  /// std::invalid_argument for a config out of range.
  SweepDeskewer(const LidarOdometryConfig& map_config, const SweepRegistrationConfig& config);

  /// `scan` (with per-point times) in the sensor's frame at its stamp, the motion during the
  /// sweep estimated from `prior_motion` (the sensor's motion over `prior_interval` seconds
  /// after the stamp, as deskew() takes it; interval 0: no prior, standing still) and the map;
  /// `pose`: the sensor's pose at the stamp in the map's frame (the odometry's). The sweep
  /// then joins the map. A scan without times is returned as it is.
  PointCloud deskew(const PointCloud& scan, const Pose3& pose, const Pose3& prior_motion,
                    double prior_interval);

  /// The last sweep's estimate.
  const SweepMotion& last() const { return last_; }
  std::size_t num_registered() const { return num_registered_; }

 private:
  LidarOdometryConfig map_config_;
  SweepRegistrationConfig config_;
  VoxelHashMap map_;
  std::deque<std::vector<Eigen::Vector3d>> window_;  ///< the last sweeps, de-skewed, in the map's frame
  SweepMotion last_;
  std::size_t num_registered_ = 0;
};

}  // namespace tsgraphs::odometry
