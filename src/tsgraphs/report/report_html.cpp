// The HTML pages: pictures inlined as SVG (their styles are scoped to their root class, see
// run_svg.hpp), CSS in the head, no script and no URL, so a page opens anywhere on its own.
#include "tsgraphs/report/report_html.hpp"

#include <charconv>
#include <filesystem>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tsgraphs/eval/table_text.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/report/run_svg.hpp"
#include "tsgraphs/report/svg_writer.hpp"

namespace tsgraphs::report {
namespace {

using svg::xml_escape;

constexpr const char* kMissing = "-";

constexpr const char* kCss =
    "body { font-family: DejaVu Sans, Helvetica, Arial, sans-serif; color: #222222; margin: 24px; "
    "max-width: 1600px; }\n"
    "h1 { font-size: 22px; margin: 0 0 8px 0; }\n"
    "h2 { font-size: 17px; margin: 28px 0 10px 0; border-bottom: 1px solid #dddddd; padding-bottom: 4px; }\n"
    "h3 { font-size: 14px; margin: 16px 0 6px 0; }\n"
    "p.note { color: #666666; font-size: 13px; }\n"
    "table { border-collapse: collapse; font-size: 13px; }\n"
    "th, td { border: 1px solid #cccccc; padding: 3px 9px; text-align: left; }\n"
    "th { background: #f2f2f2; }\n"
    "td.value { text-align: right; font-variant-numeric: tabular-nums; }\n"
    "tr.group td { background: #fafafa; font-weight: bold; }\n"
    "figure { margin: 8px 0 16px 0; }\n"
    "figcaption { font-size: 13px; color: #555555; margin-top: 4px; }\n"
    ".runs { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }\n"
    ".runs figure { flex: 1 1 520px; min-width: 320px; margin: 0; }\n"
    "svg { max-width: 100%; height: auto; display: block; }\n";

/// One row of the metrics table: metrics.json group and key, what it is, decimals shown.
struct MetricRow {
  const char* group;
  const char* key;
  const char* meaning;
  int decimals;
};

// docs/metrics.md: the Table 1 figures first, then the ground-truth and cost figures.
constexpr MetricRow kMetricRows[] = {
    {"consistency", "N1st", "rooms extracted in lap 1", 0},
    {"consistency", "N2nd", "rooms extracted in lap 2", 0},
    {"consistency", "N_re", "rooms of lap 1 found again in lap 2", 0},
    {"consistency", "f_re", "N_re / N1st", 3},
    {"consistency", "dcs", "mean Dice of the re-found rooms", 3},
    {"consistency", "d_center", "mean distance of their centres, m", 3},
    {"trajectory", "ate_rmse", "position RMSE against ground truth, m", 4},
    {"pgo", "t_pgo_s", "total optimisation wall time, s", 3},
    {"rooms_gt", "precision", "final rooms matching a true room", 3},
    {"rooms_gt", "recall", "visited true rooms matched", 3},
    {"rooms_gt", "f1", "", 3},
    {"rooms_gt", "under_segmented", "detections covering two true rooms", 0},
    {"rooms_gt", "over_segmented", "true rooms split over two detections", 0},
    {"ground", "f1", "ground label against the scans' labels", 3},
    {"speed", "rtf", "real-time factor (sequence time / wall time)", 2},
};

std::string metrics_table(const std::string& metrics_json) {
  if (metrics_json.empty()) {
    return "<p class=\"note\">No metrics.json in the run folder: run <code>tsgraphs eval RUN_DIR --seq "
           "SEQ_DIR</code> "
           "to compute the figures.</p>\n";
  }
  nlohmann::json m;
  try {
    m = nlohmann::json::parse(metrics_json);
  } catch (const nlohmann::json::exception&) {
    return "<p class=\"note\">metrics.json is not valid JSON.</p>\n";
  }
  std::string out = "<table class=\"metrics\">\n<tr><th>figure</th><th>value</th><th>meaning</th></tr>\n";
  std::string group;
  for (const MetricRow& row : kMetricRows) {
    if (group != row.group) {
      group = row.group;
      out += "<tr class=\"group\"><td colspan=\"3\">" + xml_escape(group) + "</td></tr>\n";
    }
    std::string value = kMissing;
    if (m.is_object() && m.contains(row.group) && m[row.group].is_object() &&
        m[row.group].contains(row.key) && m[row.group][row.key].is_number()) {
      const double v = m[row.group][row.key].get<double>();
      if (std::isfinite(v)) value = eval::fixed_text(v, row.decimals);
    }
    out += "<tr><td>" + xml_escape(row.key) + "</td><td class=\"value\">" + value + "</td><td>" +
           xml_escape(row.meaning) + "</td></tr>\n";
  }
  return out + "</table>\n";
}

std::string page_head(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
         xml_escape(title) + "</title>\n<style>\n" + kCss + "</style>\n</head>\n<body>\n<h1>" +
         xml_escape(title) + "</h1>\n";
}

constexpr const char* kPageTail = "</body>\n</html>\n";

std::string figure(const std::string& svg, const std::string& caption) {
  return "<figure>\n" + svg + "<figcaption>" + xml_escape(caption) + "</figcaption>\n</figure>\n";
}

bool multi_level_scene(const RunView& run) { return run.scene && run.scene->levels.size() > 1; }

std::string level_caption(const RunView& run, int level) {
  std::string s = run.label + ", level " + std::to_string(level);
  if (static_cast<std::size_t>(level) < run.levels.size())
    s += " (floor at " + svg::num(run.levels[level]) + " m)";
  return s;
}

constexpr const char* kSideViewCaption =
    "Side view: which heights hold traversable nodes and free space. Points on a storey the run "
    "did not walk (seen through a void) should not be there.";

}  // namespace

std::string run_report_html(const RunView& run, const std::string& title) {
  std::string out = page_head(title);
  out += "<p class=\"note\">Run: " + xml_escape(run.label) + "; " + std::to_string(run.estimated.size()) +
         " poses, " + std::to_string(run.rooms.size()) + " rooms and corridors, " +
         std::to_string(run.walls.size()) + " wall planes, " + std::to_string(run.nodes.size()) +
         " traversable nodes.</p>\n";
  out += "<section class=\"metrics\">\n<h2>Metrics</h2>\n" + metrics_table(run.metrics_json) + "</section>\n";
  out += "<section class=\"birdseye\">\n<h2>Bird's-eye view</h2>\n";
  for (int level : visited_levels(run)) out += figure(birdseye_svg(run, level), level_caption(run, level));
  out += "</section>\n";
  if (multi_level_scene(run)) {
    out += "<section class=\"side-view\">\n<h2>Side view</h2>\n" +
           figure(side_view_svg(run), kSideViewCaption) + "</section>\n";
  }
  out += "<section class=\"timing\">\n<h2>Timing</h2>\n" +
         figure(timing_svg(run), "Front-end time per scan and wall time of each optimisation.") +
         "</section>\n";
  return out + kPageTail;
}

std::string demo_report_html(const std::string& title, const std::string& intro_html,
                             const std::string& table_html, const std::vector<DemoSection>& sections) {
  std::string out = page_head(title);
  out += "<section class=\"intro\">\n" + intro_html + "\n</section>\n";
  out += "<section class=\"table\">\n" + table_html + "\n</section>\n";
  for (const DemoSection& s : sections) {
    out += "<section class=\"scene\">\n<h2>" + xml_escape(s.title) + "</h2>\n<div class=\"runs\">\n";
    for (const RunView& run : s.runs) {
      const int level = main_level(run);
      out += figure(birdseye_svg(run, level), level_caption(run, level));
    }
    out += "</div>\n";
    if (!s.runs.empty()) {
      const RunView& first = s.runs.front();
      if (multi_level_scene(first)) {
        out += "<h3>Side view: " + xml_escape(first.label) + "</h3>\n" +
               figure(side_view_svg(first), kSideViewCaption);
      }
      out += "<h3>Timing: " + xml_escape(first.label) + "</h3>\n" +
             figure(timing_svg(first), "Front-end time per scan and wall time of each optimisation.");
    }
    out += "</section>\n";
  }
  return out + kPageTail;
}

std::string html_escape(const std::string& text) { return xml_escape(text); }

std::string method_table_html(const std::vector<eval::MethodResult>& results,
                              const std::vector<eval::TableColumn>& columns) {
  std::string out = "<table class=\"metrics\">\n<thead><tr><th>scene</th><th>method</th>";
  for (const eval::TableColumn& c : columns) out += "<th>" + xml_escape(c.header) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const eval::MethodResult& r : results) {
    out += "<tr><td>" + xml_escape(r.scene) + "</td><td>" + xml_escape(r.method) + "</td>";
    for (const eval::TableColumn& c : columns)
      out += "<td class=\"value\">" + xml_escape(eval::cell_text(eval::spread(r, c), c.decimals)) + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

RunReportFiles run_report_files(const std::string& run_dir, const std::string& seq_dir,
                                const std::string& title, const std::optional<std::string>& metrics_json) {
  RunView run = read_run_view(run_dir, seq_dir, !metrics_json.has_value());
  if (metrics_json) run.metrics_json = *metrics_json;
  run.label = title;
  return {birdseye_svg(run, main_level(run)), run_report_html(run, title)};
}

void write_run_report(const std::string& run_dir, const std::string& seq_dir, const std::string& title) {
  const RunReportFiles files = run_report_files(run_dir, seq_dir, title);
  const std::filesystem::path dir(run_dir);
  io::write_file_atomic((dir / kBirdseyeFile).string(), files.birdseye_svg);
  io::write_file_atomic((dir / kReportFile).string(), files.report_html);
}

}  // namespace tsgraphs::report
