#include "tsgraphs/eval/method_table.hpp"

#include "tsgraphs/eval/table_text.hpp"
#include <cmath>
#include <cstdio>

namespace tsgraphs::eval {

namespace {}  // namespace

std::vector<TableColumn> table1_columns() {
  return {
      {"N1st", "N1st", 1, [](const Metrics& m) { return m.consistency.N1st; }},
      {"N2nd", "N2nd", 1, [](const Metrics& m) { return m.consistency.N2nd; }},
      {"N_re", "N_re", 1, [](const Metrics& m) { return m.consistency.N_re; }},
      {"f_re", "f_re", 2, [](const Metrics& m) { return m.consistency.f_re; }},
      {"DCS", "dcs", 2, [](const Metrics& m) { return m.consistency.dcs; }},
      {"d_center (m)", "d_center", 2, [](const Metrics& m) { return m.consistency.d_center; }},
      {"ATE (m)", "ate_loop", 3, [](const Metrics& m) { return m.trajectory.ate_loop; }},
      {"T_PGO (s)", "t_pgo_s", 3, [](const Metrics& m) { return m.pgo.t_pgo_s; }},
  };
}

std::vector<TableColumn> truth_columns() {
  return {
      {"rooms P", "rooms_precision", 2, [](const Metrics& m) { return m.rooms_gt.precision; }},
      {"rooms R", "rooms_recall", 2, [](const Metrics& m) { return m.rooms_gt.recall; }},
      {"rooms F1", "rooms_f1", 2, [](const Metrics& m) { return m.rooms_gt.f1; }},
      {"under-seg.", "under_segmented", 1, [](const Metrics& m) { return m.rooms_gt.under_segmented; }},
      {"over-seg.", "over_segmented", 1, [](const Metrics& m) { return m.rooms_gt.over_segmented; }},
      {"ATE_rmse (m)", "ate_rmse", 3, [](const Metrics& m) { return m.trajectory.ate_rmse; }},
      {"ground F1", "ground_f1", 3, [](const Metrics& m) { return m.ground.f1; }},
      {"RTF", "rtf", 1, [](const Metrics& m) { return m.speed.rtf; }},
      {"front-end ms", "frontend_ms_mean", 1, [](const Metrics& m) { return m.speed.frontend_ms_mean; }},
  };
}

Spread spread(const MethodResult& result, const TableColumn& column) {
  Spread s;
  double sum = 0.0;
  for (const Metrics& m : result.seeds) {
    if (const Figure f = column.figure(m)) {
      sum += *f;
      ++s.n;
    }
  }
  if (s.n == 0) return s;
  s.mean = sum / s.n;
  if (s.n < 2) return s;
  double sq = 0.0;
  for (const Metrics& m : result.seeds)
    if (const Figure f = column.figure(m)) sq += (*f - s.mean) * (*f - s.mean);
  s.sd = std::sqrt(sq / (s.n - 1));
  return s;
}

std::string cell_text(const Spread& s, int decimals) {
  if (s.n == 0) return "-";
  if (s.n < 2) return fixed_text(s.mean, decimals);
  return fixed_text(s.mean, decimals) + " ± " + fixed_text(s.sd, decimals);
}

std::string markdown_table(const std::vector<MethodResult>& results,
                           const std::vector<TableColumn>& columns) {
  std::string out = "| scene | method |";
  std::string rule = "|---|---|";
  for (const TableColumn& c : columns) {
    out += " " + c.header + " |";
    rule += "---|";
  }
  out += "\n" + rule + "\n";
  for (const MethodResult& r : results) {
    out += "| " + r.scene + " | " + r.method + " |";
    for (const TableColumn& c : columns) out += " " + cell_text(spread(r, c), c.decimals) + " |";
    out += "\n";
  }
  return out;
}

std::string csv_table(const std::vector<MethodResult>& results, const std::vector<TableColumn>& columns) {
  std::string out = "scene,method,seeds";
  for (const TableColumn& c : columns) out += "," + c.key + "_mean," + c.key + "_sd";
  out += "\n";
  for (const MethodResult& r : results) {
    out += csv_field(r.scene) + "," + csv_field(r.method) + "," + std::to_string(r.seeds.size());
    for (const TableColumn& c : columns) {
      const Spread s = spread(r, c);
      out += s.n == 0 ? std::string(",,")
                      : "," + fixed_text(s.mean, 6) + "," + (s.n < 2 ? std::string() : fixed_text(s.sd, 6));
    }
    out += "\n";
  }
  return out;
}

}  // namespace tsgraphs::eval
