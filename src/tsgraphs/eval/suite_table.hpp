#pragma once
/// A suite's figures over its cases (docs/suite.md, docs/metrics.md "Suites"): per method the
/// median, the worst decile and the worst case of each figure, with the direction in which it
/// is better; suite.csv (every figure of every case and method) and suite.md.
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/eval/suite_folder.hpp"

namespace tsgraphs::eval {

/// Which way a figure is better, which says which tail is its worst decile.
enum class Better { kHigher, kLower };

/// A figure of the suite's tables.
struct SuiteFigure {
  std::string key;     ///< metrics.json "group.key"
  std::string header;  ///< as the tables name it
  Better better;
  int decimals;  ///< shown in suite.md and report.html
  /// When not empty: a null figure counts as 0 where this figure exists (rooms F1 without a
  /// final room: recall is 0 then, so F1 is 0, and a method that finds nothing must not drop
  /// out of the statistics).
  std::string zero_when_null_with;
  bool whole = false;  ///< a count: one case's value is shown without decimals
};

/// The value the tables take for `figure` in a run: the figure, or 0 under zero_when_null_with.
Figure suite_value(const CaseMethod& run, const SuiteFigure& figure);

/// f_re, DCS, d_center, rooms P / R / F1 at IoU 0.5, mean IoU, under- / over-segmented,
/// unsupported rooms, IPA precision / recall micro and macro, ATE_rmse, T_PGO, RTF.
const std::vector<SuiteFigure>& suite_figures();

/// The `p`-th percentile (0..100) of `values` (not empty), linearly interpolated between the
/// closest ranks (Hyndman and Fan's type 7, numpy's and R's default): rank p/100 (n-1).
double percentile(std::vector<double> values, double p);

/// The worst decile's edge: the 10th percentile of a figure where higher is better, the 90th
/// where lower is better.
double worst_decile(const std::vector<double>& values, Better better);
/// The percentile worst_decile takes: 10 or 90.
int worst_decile_percentile(Better better);

/// One figure of one method over the cases that have it.
struct FigureStats {
  int n = 0;  ///< cases with the figure (a null figure, e.g. DCS with no room found again, is left out)
  Figure median, worst_decile, worst;
  std::string worst_case;  ///< the first case (in plan order) with the worst value
};

/// `values`: (case id, figure) in plan order.
FigureStats figure_stats(const std::vector<std::pair<std::string, double>>& values, Better better);

/// A suite's cases as far as they got.
struct SuiteResults {
  std::string name;
  std::vector<SuiteMethod> methods;  ///< in the suite's order
  std::vector<CaseRecord> cases;     ///< done and failed, in plan order
  std::vector<std::string> pending;  ///< cases without a case.json yet
  std::vector<CaseGroup> groups;     ///< the suite file's entries (suite.json); empty for an older folder
};

/// The results of one group's cases alone (its own figures: e.g. a suite's original cases
/// without a group added later).
SuiteResults group_results(const SuiteResults& results, const CaseGroup& group);

/// One method over the suite.
struct MethodSummary {
  SuiteMethod method;
  int counted = 0;                 ///< done cases with this method's run
  int failed = 0;                  ///< failed cases
  std::vector<FigureStats> stats;  ///< one per suite_figures()
};

std::vector<MethodSummary> summarise(const SuiteResults& results);

/// The method that orders the cases and leads each case's line: ts-graphs when the suite
/// runs it, else its first method ("" without methods).
std::string key_method(const SuiteResults& results);

/// Per done case with both runs' T_PGO (the other's > 0): the key method's T_PGO over
/// method `other`'s, by case id, in plan order. The paper's claim is that rooms make PGO cheaper.
std::vector<std::pair<std::string, double>> pgo_ratios(const SuiteResults& results, const std::string& other);

/// Loop closures of one method summed over the done cases: found and correct (within eval's
/// tolerance of the truth), all of them and those a room re-detection proposed.
struct LoopTotals {
  int cases = 0;  ///< cases with the loop figures
  double found = 0, correct = 0, room_found = 0, room_correct = 0;
};
LoopTotals loop_totals(const SuiteResults& results, const std::string& method);

/// The cases worst first: failed ones, then by the key method's rooms F1 (a case without it
/// first), then its f_re, then plan order.
std::vector<const CaseRecord*> worst_first(const SuiteResults& results);

/// A figure as the tables show it; "-" without one.
std::string figure_text(const Figure& f, int decimals);
/// One run's value of `figure` as the tables show it (suite_value; counts without decimals).
std::string case_figure_text(const CaseMethod& run, const SuiteFigure& figure);
/// The same for the figure at `key` (a key of suite_figures()).
std::string case_figure_text(const CaseMethod& run, const std::string& key);
/// "1 case", "3 cases".
std::string cases_text(std::size_t n);
/// "higher (p10)" or "lower (p90)".
std::string better_text(Better better);

/// A case's key figures in one line: "office-s3: TS-graphs F1 0.50, f_re 0.67, DCS 0.91,
/// d_center 0.30 m; S-Graphs+ F1 0.40; 63 s" (the key method's F1, f_re, DCS and d_center,
/// every other method's F1, the wall time), or "office-s3: failed: <message>".
std::string case_line(const CaseRecord& c, const SuiteResults& results);

/// suite.csv: a header, then one row per case and method (failed cases: one row per suite
/// method with the status and message, no figures): case, status, message, kind, the case
/// info (case_info_keys()), method, wall_s, then every metrics.json figure (metrics_keys()),
/// empty when null.
std::string suite_csv(const SuiteResults& results);

/// suite.md: counts, per method a table of every suite figure (direction, median, worst
/// decile, worst, worst case, cases with it), the same tables per case group when the suite
/// has more than one, the cases worst first, the failed cases.
std::string suite_markdown(const SuiteResults& results);

}  // namespace tsgraphs::eval
