#pragma once
/// Every scan's record, kept in order without growing memory with the run: beyond the newest
/// records they spill to an unnamed temporary file (removed by the system however the process
/// ends), and are read back in order when the run's outputs are written.
#include <cstddef>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tsgraphs/core/pose.hpp"

namespace tsgraphs::pipeline {

/// What happened to one scan (one row of timings.csv).
struct ScanRecord {
  std::size_t scan_index = 0;
  double stamp = 0.0;
  int keyframe = -1;            ///< id of the keyframe made from this scan, or -1
  int reference_keyframe = -1;  ///< the keyframe this scan's pose hangs from (-1 before the first)
  Pose3 odom = Pose3::Identity();
  std::size_t num_points = 0;  ///< after prefiltering (keyframes: only they are prefiltered; else 0)
  double prefilter_ms = 0.0;
  double ground_ms = 0.0;            ///< traversable ground of the scan (keyframes)
  std::size_t num_ground_nodes = 0;  ///< traversable nodes of the scan (keyframes)
  double rooms_ms = 0.0;             ///< free space, flush rule and room extraction (keyframes)
  /// Ground points against the input's labels (1 floor, 2 ramp), over the points within the
  /// ground layer's range: true positives, false positives, false negatives; -1 without labels
  /// and for scans that are not keyframes (their ground is not segmented).
  long ground_tp = -1, ground_fp = -1, ground_fn = -1;
  double walls_ms = 0.0;     ///< plane extraction and association (keyframes)
  double loop_ms = 0.0;      ///< loop-closure search and registration (keyframes)
  double frontend_ms = 0.0;  ///< all of the above and bookkeeping, not the back-end (thread time summed)
  std::string warning;       ///< why the scan was skipped or not made a keyframe
};

class ScanLog {
 public:
  /// Records held in memory before they spill (0: the default, 4096, ~1 MB).
  explicit ScanLog(std::size_t in_memory = 0);
  ~ScanLog();
  ScanLog(ScanLog&&) noexcept;
  ScanLog& operator=(ScanLog&&) noexcept;

  /// Adds the next scan's record. Throws std::runtime_error when the spill file cannot be
  /// created or written (a full disk), naming $TMPDIR.
  void append(const ScanRecord& record);
  std::size_t size() const { return spilled_ + recent_.size(); }
  bool empty() const { return size() == 0; }
  /// Every record in the order appended.
  void for_each(const std::function<void(const ScanRecord&)>& visit) const;

 private:
  void spill();

  std::size_t in_memory_;
  std::vector<ScanRecord> recent_;  ///< the records after the spilled ones
  std::FILE* file_ = nullptr;       ///< the spilled records, or null before the first spill
  std::size_t spilled_ = 0;
};

}  // namespace tsgraphs::pipeline
