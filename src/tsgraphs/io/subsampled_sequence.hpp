#pragma once
/// Every n-th scan of another sequence (a 10 Hz recording seen as 2 Hz: every 5th), with its
/// times, poses, ground truth and laps.
#include <memory>

#include "tsgraphs/io/scan_sequence.hpp"

namespace tsgraphs::io {

class SubsampledSequence : public ScanSequence {
 public:
  /// Scans 0, every, 2 * every, ... of `source` (kept alive by the caller). every >= 1.
  SubsampledSequence(const ScanSequence& source, std::size_t every);

  std::size_t size() const override { return info_.times.size(); }
  const SequenceInfo& info() const override { return info_; }
  const std::string& dir() const override { return source_.dir(); }
  PointCloud scan(std::size_t index) const override { return source_.scan(index * every_); }
  std::string scene_path() const override { return source_.scene_path(); }

 private:
  const ScanSequence& source_;
  std::size_t every_;
  SequenceInfo info_;
};

}  // namespace tsgraphs::io
