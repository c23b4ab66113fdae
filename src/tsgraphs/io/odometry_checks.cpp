#include "tsgraphs/io/odometry_checks.hpp"

#include <algorithm>
#include <cstdio>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::io {
namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

void check_odometry_motion(const SequenceInfo& info, const std::string& source) {
  const auto& poses = info.odometry;
  if (poses.empty()) return;
  const Eigen::Vector3d first = poses.front().translation();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector3d p = poses[i].translation();
    const std::string scan =
        "scan " + std::to_string(i) + (i < info.times.size() ? " (t " + fmt(info.times[i]) + " s)" : "");
    if ((p - first).norm() > kMaxRunExtent) {
      throw input_error(source, 0,
                        "odometry of " + scan + " is " + fmt((p - first).norm()) +
                            " m from the first scan's: more than 10 km, no building (corrupt pose?)");
    }
    if (i == 0) continue;
    const double step = (p - poses[i - 1].translation()).norm();
    const double dt = i < info.times.size() ? std::max(0.0, info.times[i] - info.times[i - 1]) : 0.0;
    if (step > kMaxPlatformSpeed * dt + kMaxUntimedStep) {
      throw input_error(source, 0,
                        "odometry of " + scan + " is " + fmt(step) + " m from the previous scan's, " +
                            fmt(dt) + " s earlier: faster than any platform (100 m/s; corrupt pose?)");
    }
  }
}

}  // namespace tsgraphs::io
