#include "tsgraphs/io/tum.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/core/text_file.hpp"
#include "tsgraphs/io/coordinate_limit.hpp"

namespace tsgraphs::io {
namespace {

constexpr const char* kFieldNames[8] = {"t", "x", "y", "z", "qx", "qy", "qz", "qw"};

// One whitespace-separated word of a line as a finite double.
double number_of(const std::string& word, const char* field, const std::string& path, int line_no) {
  double x = 0.0;
  // from_chars takes no '+' sign, which streams (and so older files) accept.
  const char* begin = word.data() + (word.size() > 1 && word[0] == '+' && word[1] != '-' ? 1 : 0);
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(begin, end, x);
  if (ec == std::errc::result_out_of_range)
    throw input_error(path, line_no,
                      std::string(field) + " is " + printable(word) + ": out of the range of a double");
  if (ec != std::errc() || ptr != end)
    throw input_error(
        path, line_no,
        "expected 8 numbers: t x y z qx qy qz qw, " + std::string(field) + " is '" + printable(word) + "'");
  if (!std::isfinite(x)) throw input_error(path, line_no, "non-finite value");
  return x;
}

}  // namespace

std::string format_tum(const std::vector<StampedPose>& poses) {
  std::string out;
  char line[320];
  for (const StampedPose& p : poses) {
    const Eigen::Vector3d t = p.pose.translation();
    const Eigen::Quaterniond q(p.pose.linear());
    std::snprintf(line, sizeof(line), "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.t, t.x(), t.y(),
                  t.z(), q.x(), q.y(), q.z(), q.w());
    out += line;
  }
  return out;
}

std::vector<StampedPose> read_tum(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw input_error(path, 0, "is a folder, not a file");
  std::istringstream in(read_text_file(path));
  std::vector<StampedPose> poses;
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (text.empty() || text[0] == '#' || text.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream s(text);
    double v[8];
    for (int i = 0; i < 8; ++i) {
      std::string word;
      if (!(s >> word)) throw input_error(path, line_no, "expected 8 numbers: t x y z qx qy qz qw");
      v[i] = number_of(word, kFieldNames[i], path, line_no);
      // The stamp may be a Unix time; a position is bounded, the quaternion is checked below.
      if (i >= 1 && i <= 3 && std::abs(v[i]) > kMaxCoordinate)
        throw input_error(
            path, line_no,
            std::string(kFieldNames[i]) + " is " + printable(word) + ": not a coordinate within 1e8 m");
    }
    std::string rest;
    if (s >> rest)
      throw input_error(path, line_no,
                        "expected 8 numbers: t x y z qx qy qz qw, found more: '" + printable(rest) + "'");
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
