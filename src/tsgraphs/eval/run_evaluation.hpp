#pragma once
/// `tsgraphs eval`: the figures of docs/metrics.md from the files of a run folder and, when
/// given, the sequence folder it ran on (ground truth).
#include <string>
#include <vector>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/eval/metrics.hpp"
#include "tsgraphs/eval/room_metrics.hpp"
#include "tsgraphs/eval/wall_metrics.hpp"

namespace tsgraphs::eval {

struct EvalOptions {
  std::string run_dir;
  std::string seq_dir;  ///< "" when there is no ground truth
  WallMetricsConfig walls;
  double loop_tolerance_m = 0.10;   ///< a loop closure is correct within this of the true relative pose...
  double loop_tolerance_deg = 1.0;  ///< ...and this rotation
};

/// Reads the run (and sequence) and computes every figure it can; the rest stay null.
/// Missing or malformed files are InputErrors naming the file.
Metrics evaluate_run(const EvalOptions& options);

/// A footprint of the room map at the end of a run (scene_graph.json "rooms"), map frame.
struct FinalRoom {
  OrientedRect rect;
  int level = 0;     ///< index into the run's levels
  Polygon2 polygon;  ///< the footprint when it is no rectangle (empty: rect)
};

/// The final rooms of a run folder. Missing or malformed scene_graph.json: InputError.
std::vector<FinalRoom> read_final_rooms(const std::string& run_dir);

/// `eval RUN_A --against RUN_B`: the final rooms of two runs paired one-to-one by Dice as the
/// two laps of one run are (consistency_between; N1st counts run A's rooms, N2nd run B's),
/// e.g. the same scene from two platforms. The runs' map frames must coincide (the same start).
Consistency compare_runs(const std::string& run_a, const std::string& run_b);

/// The comparison as JSON: run, against, N_a, N_b, N_re, f_re, dcs, d_center, pairs.
std::string comparison_json(const Consistency& c, const std::string& run_a, const std::string& run_b);

}  // namespace tsgraphs::eval
