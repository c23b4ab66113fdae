#pragma once
/// Noisy odometry from true poses: errors accumulate as random walks in translation (per
/// metre travelled) and yaw (per radian turned and per metre travelled), seeded.
#include <cstdint>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::sim {

/// Returns odometry poses for the true body poses `truth` (odometry starts at truth[0]).
/// Between consecutive poses with true motion of d metres and a radians of yaw, the motion
/// measured in the previous body frame gets independent gaussian errors: per axis of
/// translation std trans_noise_per_m * sqrt(d), in yaw std
/// sqrt(yaw_noise_per_rad^2 * a + yaw_noise_per_m^2 * d). So after L metres the error of a
/// straight run has std trans_noise_per_m * sqrt(L) per axis, whatever the scan rate.
std::vector<Pose3> drift_odometry(const std::vector<Pose3>& truth, const scene::OdometryNoise& noise,
                                  std::uint64_t seed);

}  // namespace tsgraphs::sim
