#include "tsgraphs/io/kitti.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/io/coordinate_limit.hpp"

namespace tsgraphs::io {

namespace {

constexpr std::size_t kFloatsPerPoint = 4;  // x y z intensity
constexpr std::size_t kRecordBytes = kFloatsPerPoint * sizeof(float);
constexpr std::size_t kProbeBlockPoints = 1024;  // points read at a time looking for a finite one
constexpr int kPoseFields = 12;                  // row-major 3x4
// A pose row's 3x3 part is a rotation when R^T R is I within this (rows printed with six
// digits are off by ~1e-6; a scaled or sheared matrix by far more) and det(R) is +1.
constexpr double kOrthonormalTolerance = 1e-3;

bool is_data_line(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  return first != std::string::npos && text[first] != '#';
}

}  // namespace

namespace {

/// Opens a KITTI .bin scan and checks its size: its number of points. read_kitti_bin and
/// probe_kitti_bin refuse the same files with the same words.
std::size_t open_kitti_bin(const std::string& path, std::ifstream& in) {
  in.open(path, std::ios::binary);
  if (!in) throw input_error(path, 0, "cannot open scan");
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw input_error(path, 0, "cannot read scan (" + error.message() + ")");
  const std::size_t bytes = static_cast<std::size_t>(size);
  if (bytes % kRecordBytes != 0)
    throw input_error(path, 0, "size is not a multiple of 16 bytes (x y z intensity float32)");
  return bytes / kRecordBytes;
}

}  // namespace

PointCloud read_kitti_bin(const std::string& path) {
  std::ifstream in;
  const std::size_t n = open_kitti_bin(path, in);
  // Straight into the floats: a scan is read every 0.1 s of data, and copying it through a
  // string stream took more time than the ground stage's slowest step.
  std::vector<float> data(kFloatsPerPoint * n);
  if (!in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(n * kRecordBytes)))
    throw input_error(path, 0, "cannot read scan");
  PointCloud cloud;
  cloud.reserve(n, true, false);
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(data[4 * i], data[4 * i + 1], data[4 * i + 2]);
    cloud.intensity.push_back(data[4 * i + 3]);
  }
  return cloud;
}

KittiBinPresence probe_kitti_bin(const std::string& path) {
  std::ifstream in;
  KittiBinPresence out;
  out.points = open_kitti_bin(path, in);
  // Points read a block at a time until one is finite: for most scans the first block.
  std::vector<float> block(kFloatsPerPoint * kProbeBlockPoints);
  for (std::size_t done = 0; done < out.points && !out.has_finite;) {
    const std::size_t m = std::min(kProbeBlockPoints, out.points - done);
    if (!in.read(reinterpret_cast<char*>(block.data()), static_cast<std::streamsize>(m * kRecordBytes)))
      throw input_error(path, 0, "cannot read scan");
    for (std::size_t i = 0; i < m && !out.has_finite; ++i)
      out.has_finite =
          std::isfinite(block[4 * i]) && std::isfinite(block[4 * i + 1]) && std::isfinite(block[4 * i + 2]);
    done += m;
  }
  return out;
}

std::vector<Pose3> read_kitti_poses(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw input_error(path, 0, "cannot open pose file");
  std::vector<Pose3> poses;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (!is_data_line(text)) continue;
    std::istringstream fields(text);
    double v[kPoseFields + 1];
    int count = 0;
    for (std::string f; fields >> f;) {
      if (count == kPoseFields)
        throw input_error(path, line, "more than 12 numbers (KITTI poses: a 3x4 matrix a line)");
      char* end = nullptr;
      v[count] = std::strtod(f.c_str(), &end);
      if (end == f.c_str() || *end != '\0')
        throw input_error(path, line, "'" + printable(f) + "' is not a number");
      if (!std::isfinite(v[count])) throw input_error(path, line, "non-finite value");
      ++count;
    }
    if (count != kPoseFields)
      throw input_error(path, line,
                        std::to_string(count) + " numbers, expected 12 (KITTI poses: a 3x4 matrix a line)");
    Pose3 T = Pose3::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) T.linear()(r, c) = v[4 * r + c];
      T.translation()(r) = v[4 * r + 3];
    }
    // A position is bounded as a TUM file's is (coordinate_limit.hpp).
    if (!(T.translation().cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      char what[120];
      std::snprintf(what, sizeof what, "the position [%.6g, %.6g, %.6g] is not within 1e8 m",
                    T.translation().x(), T.translation().y(), T.translation().z());
      throw input_error(path, line, what);
    }
    // A zero, scaled or reflected matrix is no rotation; its nearest rotation would be a guess.
    const Eigen::Matrix3d R = T.linear();
    const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(off <= kOrthonormalTolerance))
      throw input_error(
          path, line, "the 3x3 part is not a rotation (R^T R differs from I by " + std::to_string(off) + ")");
    if (R.determinant() < 0.0)
      throw input_error(path, line, "the 3x3 part is a reflection (determinant -1), not a rotation");
    // Rows printed with few digits are not exactly orthonormal: take the nearest rotation.
    const Eigen::Quaterniond q(T.linear());
    T.linear() = q.normalized().toRotationMatrix();
    poses.push_back(T);
  }
  return poses;
}

std::vector<double> read_times(const std::string& path) {
  std::error_code ec;  // a stream opens a folder and reads it as empty
  if (std::filesystem::is_directory(path, ec)) throw input_error(path, 0, "is a folder, not a file");
  std::ifstream in(path);
  if (!in) throw input_error(path, 0, "cannot open file");
  std::vector<double> values;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (text.find_first_not_of(" \t\r") == std::string::npos || text[0] == '#') continue;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || text.find_first_not_of(" \t\r", end - text.c_str()) != std::string::npos) {
      throw input_error(path, line, "expected one number per line");
    }
    if (!std::isfinite(v)) throw input_error(path, line, "non-finite value");
    if (!values.empty() && v < values.back()) throw input_error(path, line, "times go backwards");
    values.push_back(v);
  }
  return values;
}

int fields_on_first_line(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw input_error(path, 0, "cannot open file");
  for (std::string text; std::getline(in, text);) {
    if (!is_data_line(text)) continue;
    std::istringstream fields(text);
    int count = 0;
    for (std::string f; fields >> f;) ++count;
    return count;
  }
  return 0;
}

}  // namespace tsgraphs::io
