#pragma once
/// Methods side by side over seeds: the paper's Table 1 layout (N1st, N2nd, N_re, f_re, DCS,
/// d_center, ATE, T_PGO) and the figures beyond the paper (rooms against ground truth, ground
/// F1, speed), each cell the mean over seeds with the sample standard deviation as the spread.
#include <functional>
#include <string>
#include <vector>

#include "tsgraphs/eval/metrics.hpp"

namespace tsgraphs::eval {

/// One method on one scene: the metrics of each seed's run.
struct MethodResult {
  std::string scene;
  std::string method;
  std::vector<Metrics> seeds;
};

/// A column: its header, its CSV key, the decimals shown and the figure it reads.
struct TableColumn {
  std::string header;
  std::string key;
  int decimals = 2;
  std::function<Figure(const Metrics&)> figure;
};

/// The paper's Table 1: N1st, N2nd, N_re, f_re, DCS, d_center, ATE (ATE_loop, the paper's), T_PGO.
std::vector<TableColumn> table1_columns();
/// Beyond the paper: rooms P / R / F1 and under / over-segmentation against ground truth,
/// ATE_rmse, ground F1, real-time factor, front-end ms per scan.
std::vector<TableColumn> truth_columns();

/// Mean and sample standard deviation of a column over the seeds that have the figure.
struct Spread {
  int n = 0;  ///< seeds with the figure
  double mean = 0.0;
  double sd = 0.0;  ///< 0 for fewer than two seeds
};
Spread spread(const MethodResult& result, const TableColumn& column);

/// A cell as shown: "0.95", "0.95 ± 0.02" with two or more seeds, "-" without the figure.
std::string cell_text(const Spread& s, int decimals);

/// Markdown table: scene, method, then one cell per column.
std::string markdown_table(const std::vector<MethodResult>& results, const std::vector<TableColumn>& columns);
/// CSV: scene, method, seeds, then <key>_mean and <key>_sd per column (empty when missing).
std::string csv_table(const std::vector<MethodResult>& results, const std::vector<TableColumn>& columns);

}  // namespace tsgraphs::eval
