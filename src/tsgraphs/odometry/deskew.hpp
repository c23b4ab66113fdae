#pragma once
/// De-skewing: a spinning LiDAR sweeps its scan over its period while it moves, so each point
/// is measured from a different pose; this moves every point into the sensor's frame at the
/// scan's stamp, from the points' times and the sensor's motion over the sweep.
#include <cstddef>
#include <utility>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"

namespace tsgraphs::odometry {

/// `scan` with each point, measured times[i] seconds after the stamp, in the sensor's frame at
/// the stamp. `motion`: the sensor's pose `duration` seconds after the stamp, in the stamp's
/// frame; between, the sensor turns at a constant rate about motion's axis and moves at a
/// constant velocity (within a sweep the difference to a screw motion is far below a
/// millimetre). A scan without times, or a duration <= 0, is returned as it is. The times stay.
PointCloud deskew(const PointCloud& scan, const Pose3& motion, double duration);

/// The sensor's motion over scan `index`'s sweep, as {motion, interval} for deskew(): from
/// `poses` (one per scan, with `times`) to the next scan (the last scan: from the one before),
/// or, when `odometry` is given and has just registered the scan, its motion into the scan over
/// the interval before it (constant velocity). Interval 0 when there is no motion to go by.
/// The LiDAR odometry itself registers scans as they are: a motion from before the sweep can
/// be far from the one during it (a hand-held sensor's pitch turns back at every step), and
/// de-skewing with it bent the simulated hand-held walls more than the sweep had (docs/run.md).
std::pair<Pose3, double> sweep_motion(std::size_t index, const std::vector<double>& times,
                                      const std::vector<Pose3>& poses, const LidarOdometry* odometry);

/// The motion over `duration` seconds at the rate of `delta`, a relative pose over `interval`
/// seconds (the same constant-velocity model as deskew()).
Pose3 scale_motion(const Pose3& delta, double interval, double duration);

}  // namespace tsgraphs::odometry
