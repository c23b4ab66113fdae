#pragma once
/// metrics.json (docs/DESIGN.md): every key present, a figure that cannot be computed null.
#include <optional>
#include <string>

namespace tsgraphs::eval {

using Figure = std::optional<double>;

struct Metrics {
  struct {
    Figure N1st, N2nd, N_re, f_re, dcs, d_center;
  } consistency;
  struct {
    Figure ate_loop, ate_rmse, odom_ate_rmse;
  } trajectory;
  struct {
    Figure t_pgo_s, n_optimisations, n_variables, n_factors;
    Figure t_pgo_mean_s, t_pgo_p95_s;  ///< per optimisation
  } pgo;
  struct {
    Figure precision, recall, f1, mean_iou, under_segmented, over_segmented, n_rooms_final;
    Figure n_truth, n_truth_visited;  ///< ground-truth rooms, and those the path enters (recall's base)
    Figure unsupported;  ///< final rooms more than kMaxUnwalkableShare not walkable (room_support.hpp)
    Figure unsupported_fraction_max;  ///< the largest non-walkable share of a final room
    /// IPA room-segmentation figures (ipa_segmentation_metrics.hpp)
    Figure ipa_precision_micro, ipa_recall_micro, ipa_precision_macro, ipa_recall_macro;
  } rooms_gt;
  struct {
    Figure precision, recall, f1;
  } ground;
  struct {
    Figure mean_dist_err, mean_angle_err_deg, max_dist_err, max_angle_err_deg;
    Figure n_faces_seen, n_faces_mapped, n_duplicates;
  } walls;
  struct {
    Figure rtf, frontend_ms_mean, frontend_ms_p95, peak_rss_mb;
  } speed;
  struct {
    Figure n_loops, n_loops_correct;  ///< loop closures, and those within tolerance of the truth
    Figure n_loops_room,
        n_loops_room_correct;  ///< of them, proposed by a room re-detection (the rest by distance)
    Figure max_loop_err_m, max_loop_err_deg;
  } loops;
};

/// The JSON text of metrics.json.
std::string metrics_json(const Metrics& m);
/// A short human-readable table of the figures that exist.
std::string metrics_table(const Metrics& m);

}  // namespace tsgraphs::eval
