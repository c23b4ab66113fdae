#pragma once
/// A folder of scans as recordings come: PCD files (any of PCD's encodings: ascii, binary,
/// binary_compressed) or KITTI .bin files, with a pose file (TUM, or KITTI 3x4 rows) or none
/// (the odometry is then empty, for `run` to estimate from the scans).
///
/// Layout detection when only the folder is given: the scans are the .pcd or the .bin files
/// in it, or in its `velodyne/` subfolder (the KITTI odometry layout), in name order; the
/// poses are `poses.txt` or `odom.txt` beside them, TUM when a line has 8 fields and KITTI
/// when it has 12; the times are the TUM stamps, else `times.txt`, else one scan every
/// `scan_period`.
#include <string>
#include <vector>

#include "tsgraphs/io/scan_sequence.hpp"

namespace tsgraphs::io {

struct ScanFolderOptions {
  std::string folder;                ///< the folder to detect the layout in ("" with a `scans` glob)
  std::string scans;                 ///< a glob of scan files (e.g. "run1/*.pcd"), or "" to detect
  std::string poses;                 ///< the pose file, or "" to detect
  std::string pose_format = "auto";  ///< "tum", "kitti", or "auto" (by the first line's field count)
  std::string times;                 ///< a times file (one number a line), or "" to detect
  double scan_period = 0.1;          ///< s between scans when no times are given (a 10 Hz LiDAR)
};

/// Whether `dir` is a sequence folder of docs/scene-format.md (times.txt, odom.txt, scans/).
bool is_sequence_folder(const std::string& dir);

class ScanFolderReader : public ScanSequence {
 public:
  /// Finds the scans, poses and times; InputError naming the file (and line) for no scans,
  /// scans of two kinds, no pose file, a pose or time count other than the scan count, or a
  /// malformed line.
  explicit ScanFolderReader(const ScanFolderOptions& options);
  std::size_t size() const override { return files_.size(); }
  const SequenceInfo& info() const override { return info_; }
  const std::string& dir() const override { return name_; }
  PointCloud scan(std::size_t index) const override;
  /// The scan files, in order.
  const std::vector<std::string>& files() const { return files_; }

 private:
  std::string name_;
  std::vector<std::string> files_;
  bool pcd_ = false;
  SequenceInfo info_;
};

}  // namespace tsgraphs::io
