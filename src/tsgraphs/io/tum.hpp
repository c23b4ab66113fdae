#pragma once
/// TUM trajectory files: one pose a line, "t x y z qx qy qz qw".
#include <string>
#include <vector>

#include "tsgraphs/core/pose.hpp"

namespace tsgraphs::io {

struct StampedPose {
  double t = 0.0;
  Pose3 pose = Pose3::Identity();
};

/// TUM text for the poses (full double precision, so files round-trip).
std::string format_tum(const std::vector<StampedPose>& poses);
/// Reads a TUM file; '#' lines and blank lines are skipped; a malformed line, a non-finite
/// value, a number beyond a double or a position beyond kMaxCoordinate (coordinate_limit.hpp)
/// is an InputError naming the file, line and field; so is a folder in the file's place.
std::vector<StampedPose> read_tum(const std::string& path);

}  // namespace tsgraphs::io
