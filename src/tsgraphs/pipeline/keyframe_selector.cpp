#include "tsgraphs/pipeline/keyframe_selector.hpp"

#include <cmath>

namespace tsgraphs::pipeline {

bool KeyframeSelector::is_keyframe(const Pose3& odom) const {
  if (!last_) return true;
  const Pose3 delta = last_->inverse() * odom;
  const double angle = Eigen::AngleAxisd(delta.linear()).angle();
  return delta.translation().norm() >= config_.delta_trans || angle >= config_.delta_angle_deg * M_PI / 180.0;
}

}  // namespace tsgraphs::pipeline
