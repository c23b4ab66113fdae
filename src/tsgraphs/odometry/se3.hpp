#pragma once
/// The few Lie-group pieces Gauss-Newton on SE(3) needs: the cross-product matrix and the
/// exponential of a twist.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "tsgraphs/core/pose.hpp"

namespace tsgraphs::odometry {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// [v]x: skew(v) * w == v.cross(w).
inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// SE(3) exponential of (translation part rho, rotation part phi).
inline Pose3 se3_exp(const Vector6d& xi) {
  constexpr double kSmallAngle = 1e-10;  // below it the series of the coefficients avoids 0/0
  const Eigen::Vector3d rho = xi.head<3>();
  const Eigen::Vector3d phi = xi.tail<3>();
  const double theta = phi.norm();
  const Eigen::Matrix3d K = skew(phi);
  Eigen::Matrix3d R;
  Eigen::Matrix3d V;
  if (theta < kSmallAngle) {
    R = Eigen::Matrix3d::Identity() + K;
    V = Eigen::Matrix3d::Identity() + 0.5 * K;
  } else {
    const double t2 = theta * theta;
    R = Eigen::AngleAxisd(theta, phi / theta).toRotationMatrix();
    V = Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / t2 * K +
        (theta - std::sin(theta)) / (t2 * theta) * K * K;
  }
  Pose3 T = Pose3::Identity();
  T.linear() = R;
  T.translation() = V * rho;
  return T;
}

}  // namespace tsgraphs::odometry
