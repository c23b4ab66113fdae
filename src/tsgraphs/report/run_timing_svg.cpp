// The time plot of a run (timing_svg): the front-end's time per scan over each optimisation's
// wall time, on a shared time axis.
#include "tsgraphs/report/run_svg.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/report/run_svg_drawing.hpp"

namespace tsgraphs::report {
namespace {

using namespace run_drawing;

// Layout (pixels unless the name says seconds)
constexpr double kTimingPlotWidth = 760.0;
constexpr double kTimingTopHeight = 170.0;  // front-end panel
constexpr double kTimingBottomHeight = 140.0;
constexpr double kTimingPanelTitle = 22.0;  // above each panel
constexpr double kTimingPanelGap = 26.0;    // under the top panel's plot
constexpr int kTimingTicksX = 10;
constexpr int kTimingTicksY = 4;
constexpr double kMinTimeRangeS = 1.0;
constexpr double kMinMsRange = 0.1;      // so that tick steps stay >= 0.01 (two decimals)
constexpr double kValueHeadroom = 1.05;  // the highest value stays clear of the panel's top
constexpr double kSolveRadius = 3.2;     // local solve: a ring
constexpr double kSolveHalfSize = 3.4;   // full solve: a square
constexpr double kKeyWidth = 80.0;       // one marker entry of the bottom panel's key
constexpr double kMsPerSecond = 1000.0;

// Colours
constexpr const char* kFrontend = "#1f77b4";
constexpr const char* kSolveLocal = "#1f77b4";
constexpr const char* kSolveFull = "#d62728";

/// One panel of the time plot: value axis from 0, shared time axis.
struct TimePanel {
  double top = 0.0, height = 0.0;  // of the plot area, page pixels
  double max_value = 1.0, step = 1.0;
};

class TimingDrawer {
 public:
  explicit TimingDrawer(const RunView& run) : run_(run) {}

  std::string draw() {
    layout();
    double pgo_s = 0.0;
    std::size_t full = 0;
    for (const RunView::Solve& s : run_.solves) pgo_s += s.seconds, full += s.full ? 1 : 0;
    out_ = open_svg(page_w_, page_h_, "tsg-timing", run_.label + " \xE2\x80\x94 timing", style());
    out_ += headings(run_.label + " \xE2\x80\x94 time per scan and per solve",
                     std::to_string(run_.scans.size()) + " scans; " + std::to_string(run_.solves.size()) +
                         " optimisations (" + std::to_string(full) + " full), T_PGO " + num(pgo_s) + " s");
    draw_panel(top_, "front-end time per scan (ms)");
    draw_frontend();
    draw_panel(bottom_, "optimisation wall time (ms)");
    draw_solves();
    draw_time_axis();
    out_ += "</svg>\n";
    return out_;
  }

 private:
  void layout() {
    t_max_ = kMinTimeRangeS;
    double frontend_max = 0.0, solve_max = 0.0;
    for (const RunView::ScanTime& s : run_.scans) {
      t_max_ = std::max(t_max_, s.t);
      frontend_max = std::max(frontend_max, s.frontend_ms);
    }
    for (const RunView::Solve& s : run_.solves) {
      t_max_ = std::max(t_max_, s.t);
      solve_max = std::max(solve_max, kMsPerSecond * s.seconds);
    }
    left_ = kPageMargin + kAxisLeft;
    top_.top = kPageMargin + kTitleHeight + kTimingPanelTitle;
    top_.height = kTimingTopHeight;
    bottom_.top = top_.top + top_.height + kTimingPanelGap + kTimingPanelTitle;
    bottom_.height = kTimingBottomHeight;
    for (auto [panel, max] : {std::make_pair(&top_, frontend_max), std::make_pair(&bottom_, solve_max)}) {
      max = std::max(kValueHeadroom * max, kMinMsRange);
      panel->step = nice_step(max, kTimingTicksY);
      panel->max_value = std::ceil(max / panel->step - kEps) * panel->step;
    }
    page_w_ = left_ + kTimingPlotWidth + kPageMargin;
    page_h_ = bottom_.top + bottom_.height + kAxisBottom + kPageMargin;
  }

  double px_t(double t) const { return left_ + t / t_max_ * kTimingPlotWidth; }
  static double px_v(const TimePanel& p, double v) { return p.top + p.height * (1.0 - v / p.max_value); }

  std::vector<std::pair<std::string, std::string>> style() const {
    std::vector<std::pair<std::string, std::string>> rules = axes_style("v", "t");
    rules.insert(rules.end(),
                 {
                     {".panel-title", "font-size: 12px; font-weight: bold;"},
                     {".frontend", std::string("fill: none; stroke: ") + kFrontend +
                                       "; stroke-width: 1; stroke-linejoin: round;"},
                     {".solve.local, .key-local", std::string("fill: ") + kBackground +
                                                      "; stroke: " + kSolveLocal + "; stroke-width: 1.3;"},
                     {".solve.full, .key-full", std::string("fill: ") + kSolveFull + "; stroke: none;"},
                 });
    return rules;
  }

  void draw_panel(const TimePanel& p, const std::string& title) {
    const double right = left_ + kTimingPlotWidth, bottom = p.top + p.height;
    out_ += "<g class=\"panel\">\n";
    out_ += text(left_, p.top - kLevelNameGap - kTextBaselineShift, "panel-title", title);
    const double st = nice_step(t_max_, kTimingTicksX);
    for (double t : ticks_between(0.0, t_max_, st)) out_ += x_grid_line(px_t(t), p.top, bottom);
    for (double v : ticks_between(0.0, p.max_value, p.step)) {
      const double y = px_v(p, v);
      out_ += y_grid_line(y, left_, right);
      out_ += text(left_ - kTickLength - kTickLabelPad, y + kTextBaselineShift, "tick-label v", short_num(v));
    }
    out_ += "<rect class=\"frame\" x=\"" + num(left_) + "\" y=\"" + num(p.top) + "\" width=\"" +
            num(kTimingPlotWidth) + "\" height=\"" + num(p.height) + "\"/>\n";
    out_ += "</g>\n";
  }

  void draw_frontend() {
    if (run_.scans.empty()) return;
    std::string pts;
    for (const RunView::ScanTime& s : run_.scans) {
      pts += (pts.empty() ? "" : " ") + num(px_t(s.t)) + "," + num(px_v(top_, s.frontend_ms));
    }
    out_ += "<polyline class=\"frontend\" data-count=\"" + std::to_string(run_.scans.size()) +
            "\" points=\"" + pts + "\"/>\n";
  }

  static std::string square(const std::string& cls, double x, double y) {
    return "<rect class=\"" + cls + "\" x=\"" + num(x - kSolveHalfSize) + "\" y=\"" +
           num(y - kSolveHalfSize) + "\" width=\"" + num(2.0 * kSolveHalfSize) + "\" height=\"" +
           num(2.0 * kSolveHalfSize) + "\"/>\n";
  }
  static std::string ring(const std::string& cls, double x, double y) {
    return "<circle class=\"" + cls + "\" cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" +
           num(kSolveRadius) + "\"/>\n";
  }

  /// Local solves first, full ones over them: the few full solves stay visible.
  void draw_solves() {
    out_ += "<g class=\"layer-solves\">\n";
    for (const bool full : {false, true}) {
      for (const RunView::Solve& s : run_.solves) {
        if (s.full != full) continue;
        const double x = px_t(s.t), y = px_v(bottom_, kMsPerSecond * s.seconds);
        out_ += full ? square("solve full", x, y) : ring("solve local", x, y);
      }
    }
    // The key, right-aligned in the panel's title row.
    const double y = bottom_.top - kLevelNameGap - kTextBaselineShift - kTextBaselineShift;
    const double x_full = left_ + kTimingPlotWidth - kKeyWidth, x_local = x_full - kKeyWidth;
    out_ += ring("key-local", x_local, y) +
            text(x_local + kLegendGap, y + kTextBaselineShift, "legend-text", "local");
    out_ += square("key-full", x_full, y) +
            text(x_full + kLegendGap, y + kTextBaselineShift, "legend-text", "full");
    out_ += "</g>\n";
  }

  void draw_time_axis() {
    const double bottom = bottom_.top + bottom_.height;
    out_ += "<g class=\"time-axis\">\n";
    for (double t : ticks_between(0.0, t_max_, nice_step(t_max_, kTimingTicksX))) {
      out_ += text(px_t(t), bottom + kTickLabelGap, "tick-label t", short_num(t));
    }
    out_ += text(left_ + kTimingPlotWidth - kKeyWidth, bottom + kAxisTitleGap, "axis-title", "time (s)");
    out_ += "</g>\n";
  }

  const RunView& run_;
  TimePanel top_, bottom_;
  double t_max_ = kMinTimeRangeS, left_ = 0.0, page_w_ = 0.0, page_h_ = 0.0;
  std::string out_;
};

}  // namespace

std::string timing_svg(const RunView& run) { return TimingDrawer(run).draw(); }

}  // namespace tsgraphs::report
