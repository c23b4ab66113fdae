#include "tsgraphs/odometry/adaptive_threshold.hpp"

#include <cmath>
#include <stdexcept>

namespace tsgraphs::odometry {

double pose_displacement(const Pose3& delta, double max_range) {
  const Eigen::AngleAxisd rotation(delta.linear());
  const double chord = 2.0 * max_range * std::sin(0.5 * std::abs(rotation.angle()));
  return chord + delta.translation().norm();
}

AdaptiveThreshold::AdaptiveThreshold(double initial_threshold, double min_motion, double max_range)
    : initial_threshold_(initial_threshold), min_motion_(min_motion), max_range_(max_range) {
  if (!(initial_threshold > 0.0))
    throw std::invalid_argument("AdaptiveThreshold: initial_threshold must be > 0");
  if (!(min_motion >= 0.0)) throw std::invalid_argument("AdaptiveThreshold: min_motion must be >= 0");
  if (!(max_range > 0.0)) throw std::invalid_argument("AdaptiveThreshold: max_range must be > 0");
}

void AdaptiveThreshold::update(const Pose3& model_deviation, const Pose3& motion, double range) {
  if (pose_displacement(motion, max_range_) < min_motion_) return;
  const double error = pose_displacement(model_deviation, range > 0.0 ? range : max_range_);
  sum_sq_ += error * error;
  ++num_samples_;
}

double AdaptiveThreshold::threshold() const {
  if (num_samples_ == 0) return initial_threshold_;
  return std::sqrt(sum_sq_ / static_cast<double>(num_samples_));
}

}  // namespace tsgraphs::odometry
