#pragma once
/// Drives a Pipeline over a sequence: scans are read and prepared (prefilter, ground) in
/// parallel ahead of the pipeline, which takes them in order (TBB pipeline; --threads bounds
/// it); between the two, in order, the LiDAR odometry when the poses are estimated. The result
/// is the same as feeding the scans one at a time.
#include <functional>
#include <string>

#include "tsgraphs/io/scan_sequence.hpp"
#include "tsgraphs/pipeline/pipeline.hpp"
#include "tsgraphs/pipeline/run_outputs.hpp"

namespace tsgraphs::pipeline {

struct RunCallbacks {
  std::function<void(std::size_t done, std::size_t total)> progress;  ///< after each scan
  std::function<void(const std::string&)>
      warning;                                   ///< one line per skipped scan, and the pipeline's warnings
  std::function<void(const std::string&)> note;  ///< what was measured of the platform
};

/// Where the scans' poses come from.
struct OdometryOptions {
  /// Estimate them from the scans (LiDAR odometry, the pipeline config's `lidar_odometry`)
  /// instead of taking the sequence's own; needed when the sequence has none.
  bool estimate = false;
  /// The first scan's pose in the map frame when estimated: the sequence's first odometry pose
  /// keeps its frame; the sensor's mount on a level base makes the map level.
  Pose3 initial_pose = Pose3::Identity();
};

/// Measures the platform for `pipeline` (Pipeline::set_platform) from platform.scans scans spread
/// evenly over `sequence` (one room may show little floor), with the gravity from the
/// sequence's poses unless `poses_estimated`. Unreadable scans are left out.
void measure_platform(const io::ScanSequence& sequence, bool poses_estimated, Pipeline& pipeline);

/// The origin of the pipeline's map frame for a run whose first pose is `first`: its position
/// rounded to whole kilometres. The pipeline keeps points in float32, precise to 30 um within
/// 500 m of its origin but to 1/4 m at UTM coordinates (4e6 m); runs near their frame's origin
/// get 0, so their map frame is the input's.
Eigen::Vector3d map_origin_of(const Pose3& first);

/// Feeds every scan of `sequence` with its odometry pose to `pipeline`, then finishes it. The
/// platform is measured first (measure_platform) unless the pipeline already has it. The
/// pipeline runs in a map frame at map_origin_of(first pose) (RunInfo::map_origin; its poses
/// and maps are relative to it, write_run_outputs adds it back).
/// A scan file that cannot be read (truncated, wrong label count) is skipped with a warning;
/// its pose still comes from the odometry (estimated: the constant-velocity prediction).
/// Returns the run's facts for run_info.json. A sequence without odometry and
/// `odometry.estimate` false is std::invalid_argument.
RunInfo run_sequence(const io::ScanSequence& sequence, Pipeline& pipeline, const RunCallbacks& callbacks = {},
                     const OdometryOptions& odometry = {});

/// Peak resident memory of this process so far, MB.
double peak_rss_mb();

}  // namespace tsgraphs::pipeline
