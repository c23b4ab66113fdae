#pragma once
/// Rigid poses in SE(3), stored as Eigen isometries (map <- body).
#include <cmath>
#include <Eigen/Geometry>

namespace tsgraphs {

using Pose3 = Eigen::Isometry3d;

/// Pose from a position, a yaw about z and a pitch about the body's y axis (applied after yaw).
inline Pose3 make_pose(const Eigen::Vector3d& position, double yaw, double pitch = 0.0) {
  Pose3 T = Pose3::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  T.translation() = position;
  return T;
}

/// Heading of the body x axis projected on the ground plane, in (-pi, pi].
inline double yaw_of(const Pose3& T) {
  const Eigen::Vector3d x = T.linear().col(0);
  return std::atan2(x.y(), x.x());
}

/// Wraps an angle to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

}  // namespace tsgraphs
