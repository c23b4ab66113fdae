#pragma once
/// KITTI files: scans as float32 x y z intensity records (.bin), poses as one row-major 3x4
/// matrix [R | t] a line (the odometry benchmark's poses/NN.txt).
#include <string>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"

namespace tsgraphs::io {

/// Reads a KITTI .bin scan with intensity. A file whose size is not a whole number of 16-byte
/// records, or that cannot be read, is an InputError naming it. Non-finite points are kept
/// (the pipeline's prefilter drops them).
PointCloud read_kitti_bin(const std::string& path);

/// What read_kitti_bin would find, as far as a run needs it of a scan it does not process:
/// its number of points and whether one has finite coordinates, read no further than the
/// first that has. The same InputErrors as read_kitti_bin.
struct KittiBinPresence {
  std::size_t points = 0;
  bool has_finite = false;
};
KittiBinPresence probe_kitti_bin(const std::string& path);

/// Reads KITTI poses: 12 numbers a line; blank and '#' lines are skipped. A line with another
/// count, a non-number or a non-finite value is an InputError naming the file and line.
std::vector<Pose3> read_kitti_poses(const std::string& path);

/// Reads a times file (KITTI's times.txt, the sequence folder's times.txt and laps.txt): one
/// number a line, never decreasing; blank and '#' lines skipped; else an InputError naming the
/// file and line.
std::vector<double> read_times(const std::string& path);

/// The number of whitespace-separated fields on the first data line of a text file (blank and
/// '#' lines skipped), 0 for a file without one: 12 for KITTI poses, 8 for TUM.
int fields_on_first_line(const std::string& path);

}  // namespace tsgraphs::io
