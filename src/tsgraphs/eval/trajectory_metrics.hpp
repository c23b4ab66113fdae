#pragma once
/// Trajectory figures of docs/metrics.md: ATE_loop and ATE_rmse.
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

}  // namespace tsgraphs::eval
