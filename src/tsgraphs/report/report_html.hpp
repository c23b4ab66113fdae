#pragma once
/// HTML pages of runs: one self-contained page (inline CSS and SVG, no script, no external
/// URL, UTF-8) per run, and the demo's page comparing runs scene by scene.
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/eval/method_table.hpp"
#include "tsgraphs/report/run_view.hpp"

namespace tsgraphs::report {

/// The report of one run: `title`, the table of its metrics (run.metrics_json; "-" for a
/// figure that is null or absent), a bird's-eye per visited level, the side view when the
/// scene has more than one level, and the time plot.
std::string run_report_html(const RunView& run, const std::string& title);

/// One scene of the demo page: its runs (e.g. TS-graphs and S-Graphs+) drawn side by side.
struct DemoSection {
  std::string title;
  std::vector<RunView> runs;
};

/// The demo's page: `title`, `intro_html` and `table_html` (HTML, inserted as given), then
/// per section a bird's-eye of each run's main level side by side, captioned with the run's
/// label, the side view of its first run when the scene has more than one level, and the
/// first run's time plot.
std::string demo_report_html(const std::string& title, const std::string& intro_html,
                             const std::string& table_html, const std::vector<DemoSection>& sections);

/// `text` with &, <, > and " escaped, for HTML text and attributes.
std::string html_escape(const std::string& text);

/// The cells of eval::markdown_table as an HTML <table class="metrics">.
std::string method_table_html(const std::vector<eval::MethodResult>& results,
                              const std::vector<eval::TableColumn>& columns);

/// The names of a run's report files in its folder.
inline constexpr const char* kBirdseyeFile = "birdseye.svg";
inline constexpr const char* kReportFile = "report.html";

/// The two files of a run's report, as text.
struct RunReportFiles {
  std::string birdseye_svg;  ///< the main level
  std::string report_html;
};

/// The report write_run_report writes, made but written nowhere. `metrics_json`, when given,
/// stands for RUN/metrics.json (an earlier one is not read): eval makes the report of the
/// metrics it has yet to write.
RunReportFiles run_report_files(const std::string& run_dir, const std::string& seq_dir,
                                const std::string& title,
                                const std::optional<std::string>& metrics_json = std::nullopt);

/// Writes RUN_DIR/report.html (run_report_html) and RUN_DIR/birdseye.svg (the main level)
/// from the run's files and, when `seq_dir` is not empty, the sequence's ground truth; `title`
/// names the run in both. Each file appears whole or not at all.
void write_run_report(const std::string& run_dir, const std::string& seq_dir, const std::string& title);

}  // namespace tsgraphs::report
