#pragma once
/// `tsgraphs eval`: the figures of docs/metrics.md from the files of a run folder and, when
/// given, the sequence folder it ran on (ground truth).
#include <string>

#include "tsgraphs/eval/metrics.hpp"
#include "tsgraphs/eval/wall_metrics.hpp"

namespace tsgraphs::eval {

struct EvalOptions {
  std::string run_dir;
  std::string seq_dir;               ///< "" when there is no ground truth
  WallMetricsConfig walls;
  double loop_tolerance_m = 0.10;    ///< a loop closure is correct within this of the true relative pose...
  double loop_tolerance_deg = 1.0;   ///< ...and this rotation
};

/// Reads the run (and sequence) and computes every figure it can; the rest stay null.
/// Missing or malformed files are InputErrors naming the file.
Metrics evaluate_run(const EvalOptions& options);

}  // namespace tsgraphs::eval
