#include "tsgraphs/eval/metrics.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>

namespace tsgraphs::eval {
namespace {

nlohmann::json value(const Figure& f) { return f ? nlohmann::json(*f) : nlohmann::json(nullptr); }

std::string cell(const Figure& f, const char* format) {
  if (!f) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, *f);
  return buf;
}

}  // namespace

std::string metrics_json(const Metrics& m) {
  nlohmann::ordered_json j;
  const auto& c = m.consistency;
  j["consistency"] = {{"N1st", value(c.N1st)}, {"N2nd", value(c.N2nd)}, {"N_re", value(c.N_re)},
                      {"f_re", value(c.f_re)}, {"dcs", value(c.dcs)},   {"d_center", value(c.d_center)}};
  const auto& t = m.trajectory;
  j["trajectory"] = {{"ate_loop", value(t.ate_loop)},
                     {"ate_rmse", value(t.ate_rmse)},
                     {"odom_ate_rmse", value(t.odom_ate_rmse)}};
  const auto& p = m.pgo;
  j["pgo"] = {{"t_pgo_s", value(p.t_pgo_s)},           {"n_optimisations", value(p.n_optimisations)},
              {"n_variables", value(p.n_variables)},   {"n_factors", value(p.n_factors)},
              {"t_pgo_mean_s", value(p.t_pgo_mean_s)}, {"t_pgo_p95_s", value(p.t_pgo_p95_s)}};
  const auto& r = m.rooms_gt;
  j["rooms_gt"] = {{"precision", value(r.precision)},
                   {"recall", value(r.recall)},
                   {"f1", value(r.f1)},
                   {"mean_iou", value(r.mean_iou)},
                   {"under_segmented", value(r.under_segmented)},
                   {"over_segmented", value(r.over_segmented)},
                   {"n_rooms_final", value(r.n_rooms_final)},
                   {"n_truth", value(r.n_truth)},
                   {"n_truth_visited", value(r.n_truth_visited)},
                   {"unsupported", value(r.unsupported)},
                   {"unsupported_fraction_max", value(r.unsupported_fraction_max)},
                   {"ipa_precision_micro", value(r.ipa_precision_micro)},
                   {"ipa_recall_micro", value(r.ipa_recall_micro)},
                   {"ipa_precision_macro", value(r.ipa_precision_macro)},
                   {"ipa_recall_macro", value(r.ipa_recall_macro)}};
  j["ground"] = {{"precision", value(m.ground.precision)},
                 {"recall", value(m.ground.recall)},
                 {"f1", value(m.ground.f1)}};
  const auto& w = m.walls;
  j["walls"] = {
      {"mean_dist_err", value(w.mean_dist_err)}, {"mean_angle_err_deg", value(w.mean_angle_err_deg)},
      {"max_dist_err", value(w.max_dist_err)},   {"max_angle_err_deg", value(w.max_angle_err_deg)},
      {"n_faces_seen", value(w.n_faces_seen)},   {"n_faces_mapped", value(w.n_faces_mapped)},
      {"n_duplicates", value(w.n_duplicates)}};
  const auto& s = m.speed;
  j["speed"] = {{"rtf", value(s.rtf)},
                {"frontend_ms_mean", value(s.frontend_ms_mean)},
                {"frontend_ms_p95", value(s.frontend_ms_p95)},
                {"peak_rss_mb", value(s.peak_rss_mb)}};
  const auto& l = m.loops;
  j["loops"] = {{"n_loops", value(l.n_loops)},
                {"n_loops_correct", value(l.n_loops_correct)},
                {"n_loops_room", value(l.n_loops_room)},
                {"n_loops_room_correct", value(l.n_loops_room_correct)},
                {"max_loop_err_m", value(l.max_loop_err_m)},
                {"max_loop_err_deg", value(l.max_loop_err_deg)}};
  return j.dump(1) + "\n";
}

std::string metrics_table(const Metrics& m) {
  std::string out;
  const auto row = [&](const char* name, const std::string& v) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "  %-28s %s\n", name, v.c_str());
    out += buf;
  };
  out += "trajectory\n";
  row("ATE_loop (m)", cell(m.trajectory.ate_loop, "%.3f"));
  row("ATE_rmse (m)", cell(m.trajectory.ate_rmse, "%.3f"));
  row("odometry ATE_rmse (m)", cell(m.trajectory.odom_ate_rmse, "%.3f"));
  row("loops (correct / found)",
      m.loops.n_loops ? cell(m.loops.n_loops_correct, "%.0f") + " / " + cell(m.loops.n_loops, "%.0f") : "-");
  out += "back-end\n";
  row("T_PGO total (s)", cell(m.pgo.t_pgo_s, "%.3f"));
  row("optimisations", cell(m.pgo.n_optimisations, "%.0f"));
  row("T_PGO mean / p95 (ms)",
      cell(m.pgo.t_pgo_mean_s ? Figure(*m.pgo.t_pgo_mean_s * 1e3) : Figure{}, "%.1f") + " / " +
          cell(m.pgo.t_pgo_p95_s ? Figure(*m.pgo.t_pgo_p95_s * 1e3) : Figure{}, "%.1f"));
  row("variables / factors (last)", cell(m.pgo.n_variables, "%.0f") + " / " + cell(m.pgo.n_factors, "%.0f"));
  out += "rooms\n";
  row("N1st / N2nd / N_re", cell(m.consistency.N1st, "%.0f") + " / " + cell(m.consistency.N2nd, "%.0f") +
                                " / " + cell(m.consistency.N_re, "%.0f"));
  row("f_re / DCS / d_center (m)", cell(m.consistency.f_re, "%.2f") + " / " +
                                       cell(m.consistency.dcs, "%.2f") + " / " +
                                       cell(m.consistency.d_center, "%.2f"));
  row("vs truth P / R / F1", cell(m.rooms_gt.precision, "%.2f") + " / " + cell(m.rooms_gt.recall, "%.2f") +
                                 " / " + cell(m.rooms_gt.f1, "%.2f"));
  row("mean IoU, under / over-seg.", cell(m.rooms_gt.mean_iou, "%.2f") + ", " +
                                         cell(m.rooms_gt.under_segmented, "%.0f") + " / " +
                                         cell(m.rooms_gt.over_segmented, "%.0f"));
  row("final rooms", cell(m.rooms_gt.n_rooms_final, "%.0f"));
  row("truth rooms visited / all",
      cell(m.rooms_gt.n_truth_visited, "%.0f") + " / " + cell(m.rooms_gt.n_truth, "%.0f"));
  row("unsupported (max share)",
      cell(m.rooms_gt.unsupported, "%.0f") + " (" + cell(m.rooms_gt.unsupported_fraction_max, "%.2f") + ")");
  row("IPA P / R micro",
      cell(m.rooms_gt.ipa_precision_micro, "%.3f") + " / " + cell(m.rooms_gt.ipa_recall_micro, "%.3f"));
  row("IPA P / R macro",
      cell(m.rooms_gt.ipa_precision_macro, "%.3f") + " / " + cell(m.rooms_gt.ipa_recall_macro, "%.3f"));
  out += "ground\n";
  row("precision / recall / F1", cell(m.ground.precision, "%.3f") + " / " + cell(m.ground.recall, "%.3f") +
                                     " / " + cell(m.ground.f1, "%.3f"));
  out += "walls\n";
  row("faces seen / mapped",
      cell(m.walls.n_faces_seen, "%.0f") + " / " + cell(m.walls.n_faces_mapped, "%.0f"));
  row("distance err mean / max (m)",
      cell(m.walls.mean_dist_err, "%.4f") + " / " + cell(m.walls.max_dist_err, "%.4f"));
  row("angle err mean / max (deg)",
      cell(m.walls.mean_angle_err_deg, "%.3f") + " / " + cell(m.walls.max_angle_err_deg, "%.3f"));
  row("duplicate planes", cell(m.walls.n_duplicates, "%.0f"));
  out += "speed\n";
  row("real-time factor", cell(m.speed.rtf, "%.1f"));
  row("front-end mean / p95 (ms)",
      cell(m.speed.frontend_ms_mean, "%.2f") + " / " + cell(m.speed.frontend_ms_p95, "%.2f"));
  row("peak RSS (MB)", cell(m.speed.peak_rss_mb, "%.0f"));
  return out;
}

}  // namespace tsgraphs::eval
