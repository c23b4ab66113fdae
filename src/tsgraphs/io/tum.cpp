#include "tsgraphs/io/tum.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::io {

std::string format_tum(const std::vector<StampedPose>& poses) {
  std::string out;
  char line[320];
  for (const StampedPose& p : poses) {
    const Eigen::Vector3d t = p.pose.translation();
    const Eigen::Quaterniond q(p.pose.linear());
    std::snprintf(line, sizeof(line), "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.t, t.x(), t.y(), t.z(),
                  q.x(), q.y(), q.z(), q.w());
    out += line;
  }
  return out;
}

std::vector<StampedPose> read_tum(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw input_error(path, 0, "cannot open file");
  std::vector<StampedPose> poses;
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (text.empty() || text[0] == '#' || text.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream s(text);
    double v[8];
    for (double& x : v) {
      if (!(s >> x)) throw input_error(path, line_no, "expected 8 numbers: t x y z qx qy qz qw");
      if (!std::isfinite(x)) throw input_error(path, line_no, "non-finite value");
    }
    std::string rest;
    if (s >> rest) throw input_error(path, line_no, "expected 8 numbers: t x y z qx qy qz qw, found more: '" + rest + "'");
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) throw input_error(path, line_no, "quaternion is not unit length");
    StampedPose p;
    p.t = v[0];
    p.pose = Pose3::Identity();
    p.pose.linear() = q.normalized().toRotationMatrix();
    p.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    if (!poses.empty() && p.t < poses.back().t) throw input_error(path, line_no, "timestamps go backwards");
    poses.push_back(p);
  }
  return poses;
}

}  // namespace tsgraphs::io
