#pragma once
/// Drives a Pipeline over a sequence folder: scans are read and prepared (prefilter, ground)
/// in parallel ahead of the pipeline, which takes them in order (TBB pipeline; --threads
/// bounds it). The result is the same as feeding the scans one at a time.
#include <functional>
#include <string>

#include "tsgraphs/io/scan_sequence.hpp"
#include "tsgraphs/pipeline/pipeline.hpp"
#include "tsgraphs/pipeline/run_outputs.hpp"

namespace tsgraphs::pipeline {

struct RunCallbacks {
  std::function<void(std::size_t done, std::size_t total)> progress;  ///< after each scan
  std::function<void(const std::string&)> warning;                    ///< one line per skipped scan
};

/// Feeds every scan of `sequence` with its odometry pose to `pipeline`, then finishes it.
/// A scan file that cannot be read (truncated, wrong label count) is skipped with a warning;
/// its pose still comes from the odometry. Returns the run's facts for run_info.json.
RunInfo run_sequence(const io::ScanSequence& sequence, Pipeline& pipeline, const RunCallbacks& callbacks = {});

/// Peak resident memory of this process so far, MB.
double peak_rss_mb();

}  // namespace tsgraphs::pipeline
