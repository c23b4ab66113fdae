#pragma once
/// Trajectory figures of docs/metrics.md: ATE_loop and ATE_rmse; and odometry drift over
/// segments of the path (the KITTI odometry benchmark's relative translation error).
#include <cstddef>
#include <vector>

#include "tsgraphs/core/pose.hpp"

namespace tsgraphs::eval {

/// Distance between the first and the last estimated position (the sequences return to
/// their start, so the truth is 0). 0 for fewer than two poses.
double ate_loop(const std::vector<Pose3>& estimate);

/// RMSE of position error after aligning the first estimated pose to the first true pose
/// (SE(3), no scale): the estimate is mapped by T = truth[0] * estimate[0]^-1. Poses pair
/// by index; the sizes must match (std::invalid_argument otherwise).
double ate_rmse(const std::vector<Pose3>& estimate, const std::vector<Pose3>& truth);

/// Drift over segments of the path, as the KITTI odometry benchmark measures it (Geiger et al.,
/// CVPR 2012): from every `stride`-th pose, for each length in `lengths` (m, along the true
/// path), the error of the estimated motion to the first pose that far along, over the length;
/// the mean over all such segments (a fraction). Segments longer than the path are left out;
/// -1 when none is left. Unlike the error at the end of a path, a wrong turn early on counts
/// only in the segments it falls in. Poses pair by index (std::invalid_argument otherwise).
double segment_drift(const std::vector<Pose3>& estimate, const std::vector<Pose3>& truth,
                     const std::vector<double>& lengths, std::size_t stride = 1);

}  // namespace tsgraphs::eval
