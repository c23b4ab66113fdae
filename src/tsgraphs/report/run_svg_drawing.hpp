#pragma once
/// Internal to the report module: what the pictures of a run (run_svg.hpp) share: the page's
/// layout and palette, the world-to-page frame, merged dots, the <svg> opening with its scoped
/// style, the legend and the axis ticks. Each picture is drawn in its own file
/// (run_birdseye_svg.cpp, run_side_view_svg.cpp, run_timing_svg.cpp) over these.
#include <cmath>
#include <cstddef>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/report/run_view.hpp"
#include "tsgraphs/report/svg_writer.hpp"

namespace tsgraphs::report::run_drawing {

using svg::Extent;
using svg::num;
using svg::short_num;
using svg::text;
using svg::xml_escape;

// ---------------------------------------------------------------------------------------
// Layout shared by the pictures (pixels unless the name says metres)

constexpr double kPageMargin = 16.0;
constexpr double kTitleBaseline = 18.0;  // below the page margin
constexpr double kSubtitleBaseline = 35.0;
constexpr double kTitleHeight = 48.0;  // title and subtitle
constexpr double kLegendRow = 18.0;
constexpr double kLegendSwatch = 28.0;  // width of the sample before each entry
constexpr double kLegendGap = 8.0;      // between sample and text, and above the legend
constexpr double kLegendColumnWidth = 250.0;
constexpr double kTextBaselineShift = 4.0;  // a row's text baseline below the row's middle
constexpr double kMinPlanWidth = 2.0 * kLegendColumnWidth;

// Dots
constexpr double kNodeCellPx = 2.0;        // one node dot per cell of this size (no visible loss)
constexpr double kNodeDotPx = 2.2;         // diameters of the dots
constexpr double kTrajectoryStepM = 0.15;  // trajectory vertices at least this far apart

// Axes (side view and time plot)
constexpr double kAxisLeft = 44.0;    // room for the z tick labels
constexpr double kAxisBottom = 34.0;  // room for the x tick labels and title
constexpr double kTickLength = 4.0;
constexpr double kTickLabelGap = 14.0;  // tick to the baseline of its number (x axis)
constexpr double kTickLabelPad = 2.0;   // tick to the end of its number (value axis)
constexpr double kAxisTitleGap = 30.0;  // below the x axis
constexpr double kLevelNameGap = 4.0;   // a level's name above its line / slab
constexpr double kEps = 1e-9;           // relative slack when counting ticks

// Colours
constexpr const char* kBackground = "#ffffff";
constexpr const char* kInk = "#222222";
constexpr const char* kMutedInk = "#666666";
constexpr const char* kFrameStroke = "#bbbbbb";
constexpr const char* kGrid = "#eeeeee";
constexpr const char* kNode = "#d020c8";  // magenta, as in map.ply
constexpr const char* kEstimated = "#1f3fbf";
constexpr const char* kTrue = "#2ca02c";

bool is_corridor(const RunView::Room& r);

/// A room's colour: rooms cyan-ish, corridors orange-ish (as in map.ply).
std::string room_colour(const RunView::Room& r);

std::string xy(const Vec2& p);

/// World metres to page pixels, y up.
struct Frame {
  double min_x = 0.0, max_y = 0.0;  // world corner drawn at (left, top)
  double left = 0.0, top = 0.0;
  double scale = 1.0;  // px per metre
  Vec2 px(const Vec2& p) const { return {left + (p.x() - min_x) * scale, top + (max_y - p.y()) * scale}; }
};

std::string points_attr(const Frame& f, const std::vector<Vec2>& pts);

/// Dots merged into one path: one per cell of `cell` px. The path is written in cell units
/// under a scale transform, each dot a zero-length subpath moved to relative to the one
/// before in its row ("m3 0h0"): about 7 bytes a dot instead of 17, which keeps a page of
/// large maps small. Rows in order, so the bytes are deterministic.
class Dots {
 public:
  Dots(double cell, double dot_px) : cell_(cell), dot_px_(dot_px) {}
  void add(const Vec2& px) {
    cells_.emplace(std::lround(px.y() / cell_), std::lround(px.x() / cell_));
    ++count_;
  }
  /// The <path> of class `cls` (with `attrs`), or "" without dots.
  std::string path(const std::string& cls, const std::string& attrs = "") const {
    if (cells_.empty()) return "";
    std::string d;
    long row = 0, col = 0;
    bool first = true;
    for (const auto& [r, c] : cells_) {
      if (first || r != row) {
        d += "M" + std::to_string(c) + " " + std::to_string(r) + "h0";
      } else {
        d += "m" + std::to_string(c - col) + " 0h0";
      }
      row = r, col = c, first = false;
    }
    return "<path class=\"" + cls + "\"" + attrs + " data-count=\"" + std::to_string(count_) +
           "\" transform=\"scale(" + num(cell_) + ")\" stroke-width=\"" + num(dot_px_ / cell_) + "\" d=\"" +
           d + "\"/>\n";
  }

 private:
  double cell_, dot_px_;
  std::set<std::pair<long, long>> cells_;
  std::size_t count_ = 0;
};

/// Keeps a vertex only `step` or more from the last one kept (and always the last).
std::vector<Vec2> thinned(const std::vector<Vec2>& pts, double step);

/// "<svg ...>", its <title> and a <style> whose rules are prefixed with the root class.
/// The legends' samples use "key-" classes styled like what they stand for, so that
/// counting an element class counts what the picture shows, not its legend.
std::string open_svg(double w, double h, const std::string& root, const std::string& title,
                     const std::vector<std::pair<std::string, std::string>>& rules);

/// A legend: entries (a sample drawn centred on (x + swatch/2, y) and its text) laid out in
/// columns of kLegendColumnWidth, row by row.
struct LegendEntry {
  std::string swatch;  // SVG, drawn with {X0} {X1} {XM} {Y} replaced
  std::string what;
};

double legend_height(std::size_t entries, double width);

std::string draw_legend(const std::vector<LegendEntry>& entries, double x, double y, double width);

/// A horizontal sample line of class `cls` for the legend.
std::string key_line(const std::string& cls, const std::string& attrs = "");

/// A sample dot (zero-length path) of class `cls`.
std::string key_dot(const std::string& cls, const std::string& attrs = "");

/// The style rules of a plot's frame, grid, ticks, tick labels and axis titles; the tick labels
/// of the value axis (class `value`) end at their ticks, those along the other (`along`) are centred.
std::vector<std::pair<std::string, std::string>> axes_style(const std::string& value,
                                                            const std::string& along);

/// The picture's title and, under it, its subtitle, at the top of the page.
std::string headings(const std::string& title, const std::string& subtitle);

/// A vertical grid line at x from `top` to `bottom`, and its tick below `bottom`.
std::string x_grid_line(double x, double top, double bottom);

/// A horizontal grid line at y from `left` to `right`, and its tick left of `left`.
std::string y_grid_line(double y, double left, double right);

/// A step of 1, 2 or 5 times a power of ten giving about `ticks` ticks over `range`.
double nice_step(double range, int ticks);

/// Multiples of `step` within [lo, hi] (to rounding).
std::vector<double> ticks_between(double lo, double hi, double step);

}  // namespace tsgraphs::report::run_drawing
