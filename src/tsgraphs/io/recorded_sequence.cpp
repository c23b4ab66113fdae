#include "tsgraphs/io/recorded_sequence.hpp"

#include <algorithm>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs::io {

void add_tum_odometry(const BagOptions& options, std::vector<StampedBase>& odom) {
  if (options.odom_topic.empty() && !options.odom_tum.empty()) {
    for (const StampedPose& p : read_tum(options.odom_tum)) odom.push_back({p.t, p.pose});
  }
  const bool has_odometry = !options.odom_topic.empty() || !options.odom_tum.empty();
  if (has_odometry && odom.empty())
    throw input_error(
        options.bag, 0,
        "no odometry messages on " + (options.odom_topic.empty() ? options.odom_tum : options.odom_topic));
}

std::vector<std::size_t> RecordedSequence::place(const std::vector<double>& stamps,
                                                 std::vector<StampedBase> odom, bool has_odometry,
                                                 const std::string& points_topic) {
  ScanPlacement placed = place_scans(stamps, std::move(odom), has_odometry, sensor_to_base_);
  info_.times = std::move(placed.times);
  info_.odometry = std::move(placed.odometry);
  dropped_ = placed.dropped;
  if (info_.times.empty())
    throw input_error(name_, 0, "no scan on " + points_topic + " lies within the odometry's time span");
  return placed.kept;
}

Pose3 interpolate(const StampedBase& a, const StampedBase& b, double t) {
  const double s = b.t > a.t ? (t - a.t) / (b.t - a.t) : 0.0;
  Pose3 T = Pose3::Identity();
  T.translation() = (1.0 - s) * a.pose.translation() + s * b.pose.translation();
  T.linear() =
      Eigen::Quaterniond(a.pose.linear()).slerp(s, Eigen::Quaterniond(b.pose.linear())).toRotationMatrix();
  return T;
}

ScanPlacement place_scans(const std::vector<double>& cloud_stamps, std::vector<StampedBase> odom,
                          bool has_odometry, const Pose3& sensor_to_base) {
  std::stable_sort(odom.begin(), odom.end(),
                   [](const StampedBase& a, const StampedBase& b) { return a.t < b.t; });
  std::vector<std::size_t> order(cloud_stamps.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cloud_stamps[a] < cloud_stamps[b]; });
  ScanPlacement out;
  std::size_t k = 0;
  for (const std::size_t i : order) {
    const double t = cloud_stamps[i];
    if (!has_odometry) {
      out.kept.push_back(i);
      out.times.push_back(t);
      continue;
    }
    if (odom.empty() || t < odom.front().t || t > odom.back().t) {
      ++out.dropped;
      continue;
    }
    while (k + 1 < odom.size() && odom[k + 1].t < t) ++k;
    const Pose3 base = k + 1 < odom.size() ? interpolate(odom[k], odom[k + 1], t) : odom[k].pose;
    out.kept.push_back(i);
    out.times.push_back(t);
    out.odometry.push_back(base * sensor_to_base);
  }
  return out;
}

}  // namespace tsgraphs::io
