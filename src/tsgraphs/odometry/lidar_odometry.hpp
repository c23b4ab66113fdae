#pragma once
/// LiDAR odometry from the scans alone: KISS-ICP-style (Vizzo et al., RA-L 2023) point-to-point
/// ICP of each scan against a local voxel map, from a constant-velocity prediction, with a
/// robust kernel whose scale follows an adaptive threshold.
#include <cstddef>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/odometry/adaptive_threshold.hpp"
#include "tsgraphs/odometry/voxel_hash_map.hpp"

namespace tsgraphs::odometry {

struct LidarOdometryConfig {
  double min_range = 0.5;                      ///< returns nearer than this are dropped (m): the robot and its operator
  double max_range = 50.0;                     ///< returns farther are dropped (m); also the local map's radius
  double voxel_size = 0.25;                    ///< edge of the local map's voxels (m)
  double map_voxel_factor = 0.5;               ///< the scan added to the map is downsampled to voxel_size * this
  double registration_voxel_factor = 1.5;      ///< the scan registered is downsampled to voxel_size * this (coarser: faster)
  int max_points_per_voxel = 20;               ///< local map points kept per voxel; later ones are dropped
  double initial_threshold = 2.0;              ///< correspondence threshold (m) until the robot has moved
  double min_threshold = 0.5;                  ///< the adaptive threshold never goes below this (m): turns that start
                                               ///< abruptly (in place, 90 deg/s) must stay within ICP's reach
  double min_motion = 0.1;                     ///< a scan teaches the threshold only if it moved this much (m, at max_range)
  double correspondence_factor = 3.0;          ///< correspondences farther than threshold * this are ignored
  double kernel_scale_factor = 1.0 / 3.0;      ///< Geman-McClure kernel scale = threshold * this (m)
  int max_iterations = 500;                    ///< Gauss-Newton iterations per scan at most
  double convergence_criterion = 1e-4;         ///< stop when the update's norm (rad and m) falls below this
  int min_correspondences = 50;                ///< fewer correspondences than this: keep the prediction
  int reduction_grain = 256;                   ///< points per block of the parallel reduction (fixed: the sums are
                                               ///< then added in the same order whatever the threads)

  template <class V>
  void visit(V& v) {
    v("min_range", min_range);
    v("max_range", max_range);
    v("voxel_size", voxel_size);
    v("map_voxel_factor", map_voxel_factor);
    v("registration_voxel_factor", registration_voxel_factor);
    v("max_points_per_voxel", max_points_per_voxel);
    v("initial_threshold", initial_threshold);
    v("min_threshold", min_threshold);
    v("min_motion", min_motion);
    v("correspondence_factor", correspondence_factor);
    v("kernel_scale_factor", kernel_scale_factor);
    v("max_iterations", max_iterations);
    v("convergence_criterion", convergence_criterion);
    v("min_correspondences", min_correspondences);
    v("reduction_grain", reduction_grain);
  }

  /// Throws std::invalid_argument naming the first field out of range.
  void validate() const;
};

/// Outcome of one ICP run (for diagnostics and tests).
struct IcpResult {
  Pose3 pose = Pose3::Identity();  ///< sensor pose in the map frame
  int iterations = 0;
  std::size_t num_correspondences = 0;  ///< in the last iteration
  bool converged = false;               ///< the update fell below convergence_criterion
};

/// Point-to-point ICP of `source` (sensor frame) against `map` from `initial_guess`, Gauss-Newton
/// on SE(3) with a Geman-McClure kernel of scale `kernel_scale`, pairs farther than
/// `max_correspondence_distance` ignored. Deterministic for the same inputs and config.
IcpResult align_to_map(const std::vector<Eigen::Vector3d>& source, const VoxelHashMap& map, const Pose3& initial_guess,
                       double max_correspondence_distance, double kernel_scale, const LidarOdometryConfig& config);

class LidarOdometry {
 public:
  /// std::invalid_argument for a config out of range (LidarOdometryConfig::validate).
  explicit LidarOdometry(LidarOdometryConfig config = {});

  /// Registers the next scan (sensor frame) and returns its sensor pose in the odometry frame
  /// (the first scan's frame: the first pose is the identity). A scan with no usable point
  /// keeps the constant-velocity prediction and leaves the map as it is.
  Pose3 register_scan(const PointCloud& scan);

  /// One pose per registered scan.
  const std::vector<Pose3>& poses() const { return poses_; }
  const VoxelHashMap& local_map() const { return map_; }
  /// The correspondence threshold the next scan will use (m).
  double threshold() const;
  /// ICP details of the last scan (iterations 0 when it was not registered).
  const IcpResult& last_icp() const { return last_icp_; }
  const LidarOdometryConfig& config() const { return config_; }

 private:
  Pose3 predict() const;

  LidarOdometryConfig config_;
  VoxelHashMap map_;
  AdaptiveThreshold threshold_;
  std::vector<Pose3> poses_;
  IcpResult last_icp_;
};

}  // namespace tsgraphs::odometry
