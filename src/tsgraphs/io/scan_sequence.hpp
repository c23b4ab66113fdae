#pragma once
/// What `run` reads: timestamped scans, with an odometry pose each where the source has one,
/// from a sequence folder (SequenceReader), a folder of PCD / KITTI scans (ScanFolderReader)
/// or a ROS1 bag (BagSequence).
#include <cstddef>
#include <string>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/io/sequence_info.hpp"

namespace tsgraphs::io {

/// What a run needs of a scan it will not process (no keyframe): whether it holds points,
/// finite ones, and per-point times (de-skewing needs the scan itself).
struct ScanPresence {
  bool empty = true;        ///< no point at all
  bool has_finite = false;  ///< a point with finite coordinates
  bool has_times = false;   ///< per-point times
};

class ScanSequence {
 public:
  virtual ~ScanSequence() = default;
  /// Number of scans.
  virtual std::size_t size() const = 0;
  /// Times (one per scan), odometry (one per scan, or none when the source has none: `run`
  /// then estimates it from the scans), and ground truth where the source has it.
  virtual const SequenceInfo& info() const = 0;
  /// Where it was read from, for messages and run_info.json.
  virtual const std::string& dir() const = 0;
  /// Scan `index` in the sensor frame. Safe to call from several threads at once. A scan that
  /// cannot be read is an InputError naming its file.
  virtual PointCloud scan(std::size_t index) const = 0;
  /// Whether presence() is cheaper than scan(): only then does a run ask it first.
  virtual bool presence_is_cheap() const { return false; }
  /// What scan(index) holds as far as ScanPresence tells, with scan()'s InputErrors. This
  /// reads the scan; a source that can tell more cheaply overrides it (a sequence folder: from
  /// the file's size and its first finite point). Safe to call from several threads at once.
  virtual ScanPresence presence(std::size_t index) const {
    const PointCloud cloud = scan(index);
    ScanPresence p;
    p.empty = cloud.empty();
    p.has_times = cloud.has_times();
    p.has_finite = cloud.has_finite_point();
    return p;
  }
  /// Path of the simulator's scene.yaml, "" for real data.
  virtual std::string scene_path() const { return ""; }
};

}  // namespace tsgraphs::io
