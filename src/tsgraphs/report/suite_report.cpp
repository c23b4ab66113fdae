// The suite page: the tables, then one row of bird's-eyes per case, the worst case first.
// The pictures are the run folders' own birdseye.svg, inlined (their styles are scoped to
// their root class), so the page needs neither the sequences nor a network.
#include "tsgraphs/report/suite_report.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/report/report_html.hpp"
#include "tsgraphs/report/svg_writer.hpp"

namespace tsgraphs::report {
namespace {

using svg::xml_escape;

constexpr const char* kCss =
    "body { font-family: DejaVu Sans, Helvetica, Arial, sans-serif; color: #222222; margin: 24px; "
    "max-width: 1800px; }\n"
    "h1 { font-size: 22px; margin: 0 0 8px 0; }\n"
    "h2 { font-size: 17px; margin: 28px 0 10px 0; border-bottom: 1px solid #dddddd; padding-bottom: 4px; }\n"
    "h3 { font-size: 14px; margin: 18px 0 6px 0; }\n"
    "p.note { color: #666666; font-size: 13px; }\n"
    "p.failed { color: #b00020; font-size: 13px; }\n"
    "table { border-collapse: collapse; font-size: 13px; margin-bottom: 12px; }\n"
    "th, td { border: 1px solid #cccccc; padding: 3px 9px; text-align: left; }\n"
    "th { background: #f2f2f2; }\n"
    "td.value { text-align: right; font-variant-numeric: tabular-nums; }\n"
    "figure { margin: 0; }\n"
    "figcaption { font-size: 12px; color: #555555; margin-top: 4px; }\n"
    ".runs { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; }\n"
    ".runs figure { flex: 0 1 440px; min-width: 260px; }\n"
    "svg { max-width: 100%; height: auto; display: block; }\n";

std::string value_text(const eval::CaseMethod& run, const char* key) {
  return eval::case_figure_text(run, key);
}

std::string run_caption(const eval::CaseMethod& run) {
  return run.method.name + ": rooms F1 " + value_text(run, "rooms_gt.f1") + ", f_re " +
         value_text(run, "consistency.f_re") + ", DCS " + value_text(run, "consistency.dcs") + ", d_center " +
         value_text(run, "consistency.d_center") + " m, unsupported " +
         value_text(run, "rooms_gt.unsupported") + ", ATE " + value_text(run, "trajectory.ate_rmse") + " m";
}

/// What the case ran on: "office, seed 3, platform handheld, vlp-16 at 1.50 m".
std::string case_subtitle(const eval::CaseRecord& c) {
  std::string s;
  const auto add = [&](const std::string& text) { s += (s.empty() ? "" : ", ") + text; };
  if (const std::string v = c.info_value("style"); !v.empty()) add(v);
  if (const std::string v = c.info_value("source"); !v.empty()) add(v);
  if (const std::string v = c.info_value("seed"); !v.empty()) add("seed " + v);
  if (const std::string v = c.info_value("platform"); !v.empty() && v != "default") add("platform " + v);
  const std::string preset = c.info_value("preset"), mount = c.info_value("mount_height");
  if (!preset.empty() || !mount.empty())
    add((preset.empty() ? std::string("sensor") : preset) + (mount.empty() ? "" : " at " + mount + " m"));
  return s;
}

std::string summary_table(const eval::MethodSummary& s) {
  std::string out =
      "<table class=\"suite\">\n<thead><tr><th>figure</th><th>better (worst decile)</th><th>median</th>"
      "<th>worst decile</th><th>worst</th><th>worst case</th><th>cases</th></tr></thead>\n<tbody>\n";
  for (std::size_t k = 0; k < eval::suite_figures().size(); ++k) {
    const eval::SuiteFigure& f = eval::suite_figures()[k];
    const eval::FigureStats& st = s.stats[k];
    out += "<tr><td>" + xml_escape(f.header) + "</td><td>" + xml_escape(eval::better_text(f.better)) +
           "</td><td class=\"value\">" + eval::figure_text(st.median, f.decimals) +
           "</td><td class=\"value\">" + eval::figure_text(st.worst_decile, f.decimals) +
           "</td><td class=\"value\">" + eval::figure_text(st.worst, f.decimals) + "</td><td>" +
           xml_escape(st.worst_case.empty() ? "-" : st.worst_case) + "</td><td class=\"value\">" +
           std::to_string(st.n) + "</td></tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

/// An SVG file's text as an inline element: without an XML declaration or a doctype.
std::string inline_svg(std::string text) {
  const std::size_t at = text.find("<svg");
  return at == std::string::npos ? std::string() : text.substr(at);
}

}  // namespace

std::string suite_report_html(const eval::SuiteResults& results, const BirdseyeSource& birdseye) {
  const std::string title = "tsgraphs suite: " + results.name;
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
                    xml_escape(title) + "</title>\n<style>\n" + kCss + "</style>\n</head>\n<body>\n<h1>" +
                    xml_escape(title) + "</h1>\n";
  int done = 0, failed = 0;
  for (const eval::CaseRecord& c : results.cases) (c.done() ? done : failed) += 1;
  std::string methods;
  for (const eval::SuiteMethod& m : results.methods) methods += (methods.empty() ? "" : ", ") + m.name;
  out += "<p>" + eval::cases_text(results.cases.size() + results.pending.size()) + ": " +
         std::to_string(done) + " counted, " + std::to_string(failed) + " failed, " +
         std::to_string(results.pending.size()) + " not run yet. Methods: " + xml_escape(methods) + ".</p>\n";
  out +=
      "<p class=\"note\">Per method and figure, over the counted cases that have the figure: the median, the "
      "worst decile (the 10th percentile where higher is better, the 90th where lower is better), the worst "
      "value "
      "and the first case with it. DCS, d_center and mean IoU exist only where rooms were paired or matched; "
      "rooms F1 is 0 where a run has no final room.</p>\n";
  for (const eval::MethodSummary& s : eval::summarise(results)) {
    out += "<section class=\"method\">\n<h2>" + xml_escape(s.method.name) + "</h2>\n<p>" +
           eval::cases_text(s.counted) + " counted, " + std::to_string(s.failed) + " failed.</p>\n" +
           summary_table(s) + "</section>\n";
  }

  const std::string key = eval::key_method(results);
  out += "<h2>Cases, worst first</h2>\n<p class=\"note\">Sorted by the " + xml_escape(key) +
         " run's rooms F1, then its f_re; failed cases first. True rooms are dashed, each found room is "
         "labelled "
         "with its id and the lap of its first extraction.</p>\n";
  for (const eval::CaseRecord* c : eval::worst_first(results)) {
    out += "<section class=\"case\">\n<h3>" + xml_escape(c->id) + "</h3>\n";
    if (const std::string sub = case_subtitle(*c); !sub.empty())
      out += "<p class=\"note\">" + xml_escape(sub) + "</p>\n";
    if (!c->done()) {
      out += "<p class=\"failed\">failed: " + xml_escape(c->message) + "</p>\n</section>\n";
      continue;
    }
    out += "<div class=\"runs\">\n";
    for (const eval::CaseMethod& run : c->methods) {
      const std::string picture = inline_svg(birdseye(*c, run.method.slug));
      out += "<figure>\n" +
             (picture.empty() ? "<p class=\"note\">no bird's-eye in the run folder</p>\n" : picture + "\n") +
             "<figcaption>" + xml_escape(c->id + ", " + run_caption(run)) + "</figcaption>\n</figure>\n";
    }
    out += "</div>\n</section>\n";
  }
  return out + "</body>\n</html>\n";
}

std::string read_birdseye(const std::string& run_dir) {
  std::ifstream in(std::filesystem::path(run_dir) / kBirdseyeFile, std::ios::binary);
  if (!in) return "";
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_suite_report(const std::string& path, const std::string& suite_dir,
                        const eval::SuiteResults& results) {
  const std::filesystem::path cases = std::filesystem::path(suite_dir) / eval::suite_files::kCases;
  io::write_file_atomic(path,
                        suite_report_html(results, [&](const eval::CaseRecord& c, const std::string& slug) {
                          return read_birdseye((cases / c.id / slug).string());
                        }));
}

}  // namespace tsgraphs::report
