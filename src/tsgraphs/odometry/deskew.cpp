#include "tsgraphs/odometry/deskew.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

namespace tsgraphs::odometry {

Pose3 scale_motion(const Pose3& delta, double interval, double duration) {
  if (!(interval > 0.0)) throw std::invalid_argument("scale_motion: the interval must be > 0");
  const double s = duration / interval;
  const Eigen::AngleAxisd turn(delta.linear());
  Pose3 out = Pose3::Identity();
  out.linear() = Eigen::AngleAxisd(turn.angle() * s, turn.axis()).toRotationMatrix();
  out.translation() = delta.translation() * s;
  return out;
}

std::pair<Pose3, double> sweep_motion(std::size_t index, const std::vector<double>& times,
                                      const std::vector<Pose3>& poses, const LidarOdometry* odometry) {
  if (odometry) {
    if (index < 1 || index >= times.size()) return {Pose3::Identity(), 0.0};
    return {odometry->last_motion(), times[index] - times[index - 1]};
  }
  if (poses.size() != times.size() || times.size() < 2 || index >= times.size())
    return {Pose3::Identity(), 0.0};
  const std::size_t a = index + 1 < times.size() ? index : index - 1;
  return {poses[a].inverse() * poses[a + 1], times[a + 1] - times[a]};
}

PointCloud deskew(const PointCloud& scan, const Pose3& motion, double duration) {
  if (!scan.has_times() || !(duration > 0.0)) return scan;
  if (scan.times.size() != scan.size()) throw std::invalid_argument("deskew: one time per point");
  PointCloud out = scan;
  // A spinning sensor's points come in columns that share a time: one pose per run of them.
  float last_time = 0.0f;
  Eigen::Matrix3f R = Eigen::Matrix3f::Identity();
  Eigen::Vector3f t = Eigen::Vector3f::Zero();
  bool have = false;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!have || out.times[i] != last_time) {
      const Pose3 at = scale_motion(motion, duration, out.times[i]);
      R = at.linear().cast<float>();
      t = at.translation().cast<float>();
      last_time = out.times[i];
      have = true;
    }
    out.points[i] = R * out.points[i] + t;
  }
  return out;
}

}  // namespace tsgraphs::odometry
