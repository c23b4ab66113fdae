#pragma once
/// Rigid poses in SE(3), stored as Eigen isometries (map <- body).
#include <cmath>
#include <Eigen/Geometry>

namespace tsgraphs {

using Pose3 = Eigen::Isometry3d;

/// Pose from a position, a yaw about z and a pitch about the body's y axis (applied after yaw).
inline Pose3 make_pose(const Eigen::Vector3d& position, double yaw, double pitch = 0.0) {
  Pose3 T = Pose3::Identity();
  T.linear() =
      (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
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

/// The origin of a frame near `p` in which float32 stays precise (30 um within 500 m, against
/// 1/4 m at UTM coordinates): `p` rounded to whole kilometres, so it reads plainly and is 0 for
/// anything within 500 m of its own frame's origin. The pipeline's map frame, the export's clouds.
inline Eigen::Vector3d float_safe_origin(const Eigen::Vector3d& p) {
  constexpr double kGrid = 1000.0;
  return (p / kGrid).array().round().matrix() * kGrid;
}

}  // namespace tsgraphs
