// Pictures of one run: the bird's-eye of a level, the x-z side view and the time plot.
//
// Each is one <svg> whose root has a class (tsg-birdseye, tsg-side-view, tsg-timing) and
// whose <style> rules are scoped to it, with no ids, so that any number of them can be
// inlined in one HTML page. Thousands of points (traversable nodes, free space) are drawn
// as zero-length subpaths with round caps merged into one <path> per colour, thinned to
// one dot per small cell so that a page of eight pictures of a large map stays a few MB;
// the path's data-count says how many points it stands for.
#include "tsgraphs/report/run_svg.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/report/svg_writer.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::report {
namespace {

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
constexpr double kSwatchTall = 12.0;        // heights of the legend's samples: areas,
constexpr double kSwatchThin = 6.0;         // floors seen from the side
constexpr double kTextBaselineShift = 4.0;  // a row's text baseline below the row's middle

// Bird's-eye
constexpr double kPlanPxPerMetre = 24.0;  // lowered for runs kilometres long (svg::drawing_scale)
constexpr double kPlanPaddingM = 0.8;     // around what is drawn
constexpr double kMinPlanWidth = 2.0 * kLegendColumnWidth;
constexpr int kScaleBarMetres = 5;
constexpr double kScaleBarGap = 12.0;     // between the plan and the scale bar
constexpr double kScaleBarHeight = 34.0;  // the bar and its numbers
constexpr double kScaleBarThickness = 6.0;
constexpr double kScaleTextGap = 12.0;
constexpr double kScaleTextShift = 3.0;
constexpr double kStartRadius = 5.0;  // the estimated trajectory's first pose

// Dots
constexpr double kNodeCellPx = 2.0;      // one node dot per cell of this size (no visible loss)
constexpr double kFreeSpaceCellM = 0.2;  // one free-space dot per cell (the ESDF's grid): a tint
constexpr double kNodeDotPx = 2.2;       // diameters of the dots
constexpr double kFreeSpaceDotPx = 3.4;
constexpr double kSideFreeSpaceDotPx = 3.0;
constexpr double kTrajectoryStepM = 0.15;  // trajectory vertices at least this far apart

// Labels
constexpr double kLabelCharWidth = 6.6;  // rough width of a label character (11 px bold)
constexpr double kLabelHeight = 14.0;
constexpr int kLabelMaxShifts = 8;           // tries to move a label off the ones already placed
constexpr double kTruthNameInset = 4.0;      // a ground-truth room's name, from its top left corner
constexpr double kTruthNameBaseline = 11.0;  // within its label box

// Side view
constexpr double kSidePxPerMetre = 28.0;
constexpr double kSidePaddingM = 0.6;
constexpr double kSlabThicknessM = 0.25;  // drawn under each scene floor
constexpr double kAxisLeft = 44.0;        // room for the z tick labels
constexpr double kAxisBottom = 34.0;      // room for the x tick labels and title
constexpr double kTickLength = 4.0;
constexpr double kTickLabelGap = 14.0;    // tick to the baseline of its number (x axis)
constexpr double kTickLabelPad = 2.0;     // tick to the end of its number (value axis)
constexpr double kAxisTitleGap = 30.0;    // below the x axis
constexpr double kAxisTitleInset = 10.0;  // the z axis title's baseline from the page margin
constexpr int kSideTicksX = 10;           // about this many ticks along x
constexpr int kSideTicksZ = 5;
constexpr double kLevelNameGap = 4.0;  // a level's name above its line / slab

// Timing
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
constexpr double kEps = 1e-9;  // relative slack when counting ticks

// Colours
constexpr const char* kBackground = "#ffffff";
constexpr const char* kInk = "#222222";
constexpr const char* kMutedInk = "#666666";
constexpr const char* kFrameStroke = "#bbbbbb";
constexpr const char* kGrid = "#eeeeee";
constexpr const char* kSceneSlab = "#f4f4f4";
constexpr const char* kSceneSlabStroke = "#dddddd";
constexpr const char* kSceneWall = "#c6c6c6";
constexpr const char* kSideSlab = "#b8b8b8";
constexpr const char* kMappedWall = "#1b1b1b";
constexpr const char* kNode = "#d020c8";  // magenta, as in map.ply
constexpr const char* kTruthRoom = "#555555";
constexpr const char* kEstimated = "#1f3fbf";
constexpr const char* kTrue = "#2ca02c";
constexpr const char* kFrontend = "#1f77b4";
constexpr const char* kSolveLocal = "#1f77b4";
constexpr const char* kSolveFull = "#d62728";
constexpr const char* kHalo = "#ffffff";
constexpr const char* kFont = "DejaVu Sans, Helvetica, Arial, sans-serif";

// Room colours: rooms cyan-ish, corridors orange-ish (as in map.ply), each room's hue moved
// within its band by the golden ratio of its id so that neighbours differ.
constexpr double kRoomHueDeg = 188.0;
constexpr double kCorridorHueDeg = 30.0;
constexpr double kRoomHueSpreadDeg = 36.0;
constexpr double kCorridorHueSpreadDeg = 22.0;
constexpr double kGoldenRatio = 0.6180339887498949;
constexpr double kRoomSaturation = 0.78;
constexpr double kRoomLightness = 0.44;

// ---------------------------------------------------------------------------------------
// Helpers

bool is_corridor(const RunView::Room& r) { return r.kind == "corridor"; }

std::string room_colour(const RunView::Room& r) {
  const double spread = std::fmod(std::abs(static_cast<double>(r.id)) * kGoldenRatio, 1.0) - 0.5;
  const double hue = is_corridor(r) ? kCorridorHueDeg + kCorridorHueSpreadDeg * spread
                                    : kRoomHueDeg + kRoomHueSpreadDeg * spread;
  return svg::hsl_colour(hue, kRoomSaturation, kRoomLightness);
}

std::string xy(const Vec2& p) { return num(p.x()) + "," + num(p.y()); }

/// World metres to page pixels, y up.
struct Frame {
  double min_x = 0.0, max_y = 0.0;  // world corner drawn at (left, top)
  double left = 0.0, top = 0.0;
  double scale = 1.0;  // px per metre
  Vec2 px(const Vec2& p) const { return {left + (p.x() - min_x) * scale, top + (max_y - p.y()) * scale}; }
};

std::string points_attr(const Frame& f, const std::vector<Vec2>& pts) {
  std::string s;
  for (const Vec2& p : pts) s += (s.empty() ? "" : " ") + xy(f.px(p));
  return s;
}

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
std::vector<Vec2> thinned(const std::vector<Vec2>& pts, double step) {
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (out.empty() || (pts[i] - out.back()).norm() >= step || i + 1 == pts.size()) out.push_back(pts[i]);
  }
  return out;
}

/// "<svg ...>", its <title> and a <style> whose rules are prefixed with the root class.
/// The legends' samples use "key-" classes styled like what they stand for, so that
/// counting an element class counts what the picture shows, not its legend.
std::string open_svg(double w, double h, const std::string& root, const std::string& title,
                     const std::vector<std::pair<std::string, std::string>>& rules) {
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"" + root + "\" width=\"" + num(w) +
                    "\" height=\"" + num(h) + "\" viewBox=\"0 0 " + num(w) + " " + num(h) + "\">\n";
  out += "<title>" + xml_escape(title) + "</title>\n<style>\n";
  const std::vector<std::pair<std::string, std::string>> common = {
      {"text", std::string("font-family: ") + kFont + "; fill: " + kInk + ";"},
      {".title", "font-size: 15px; font-weight: bold;"},
      {".subtitle", std::string("font-size: 11px; fill: ") + kMutedInk + ";"},
      {".legend-text", "font-size: 11px;"},
      {".scale-text", "font-size: 10px;"},
      {".halo",
       std::string("stroke: ") + kHalo + "; stroke-width: 3px; stroke-linejoin: round; paint-order: stroke;"},
  };
  for (const auto* list : {&common, &rules}) {
    for (const auto& [selectors, declarations] : *list) {
      // Each selector of a list ("a, b") scoped to the root.
      std::string scoped;
      for (std::size_t at = 0; at < selectors.size();) {
        std::size_t end = selectors.find(',', at);
        if (end == std::string::npos) end = selectors.size();
        const std::size_t first = selectors.find_first_not_of(' ', at);
        scoped += (scoped.empty() ? "." : ", .") + root + " " + selectors.substr(first, end - first);
        at = end + 1;
      }
      out += scoped + " { " + declarations + " }\n";
    }
  }
  out += "</style>\n";
  out += "<rect class=\"background\" x=\"0\" y=\"0\" width=\"" + num(w) + "\" height=\"" + num(h) +
         "\" fill=\"" + kBackground + "\"/>\n";
  return out;
}

/// A legend: entries (a sample drawn centred on (x + swatch/2, y) and its text) laid out in
/// columns of kLegendColumnWidth, row by row.
struct LegendEntry {
  std::string swatch;  // SVG, drawn with {X0} {X1} {XM} {Y} replaced
  std::string what;
};

std::size_t legend_columns(double width) {
  return static_cast<std::size_t>(std::max(1.0, std::floor(width / kLegendColumnWidth)));
}

double legend_height(std::size_t entries, double width) {
  const std::size_t columns = legend_columns(width);
  return static_cast<double>((entries + columns - 1) / columns) * kLegendRow;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
  return s;
}

std::string draw_legend(const std::vector<LegendEntry>& entries, double x, double y, double width) {
  const std::size_t columns = legend_columns(width);
  std::string out = "<g class=\"legend\">\n";
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double ex = x + static_cast<double>(i % columns) * kLegendColumnWidth;
    const double ey = y + (static_cast<double>(i / columns) + 0.5) * kLegendRow;
    std::string s = entries[i].swatch;
    s = replace_all(s, "{X0}", num(ex));
    s = replace_all(s, "{X1}", num(ex + kLegendSwatch));
    s = replace_all(s, "{XM}", num(ex + 0.5 * kLegendSwatch));
    s = replace_all(s, "{Y}", num(ey));
    out += s + "\n";
    out += text(ex + kLegendSwatch + kLegendGap, ey + kTextBaselineShift, "legend-text", entries[i].what);
  }
  out += "</g>\n";
  return out;
}

/// A horizontal sample line of class `cls` for the legend.
std::string key_line(const std::string& cls, const std::string& attrs = "") {
  return "<line class=\"" + cls + "\"" + attrs + " x1=\"{X0}\" y1=\"{Y}\" x2=\"{X1}\" y2=\"{Y}\"/>";
}

/// A sample dot (zero-length path) of class `cls`.
std::string key_dot(const std::string& cls, const std::string& attrs = "") {
  return "<path class=\"" + cls + "\"" + attrs + " d=\"M{XM},{Y}h0\"/>";
}

/// A step of 1, 2 or 5 times a power of ten giving about `ticks` ticks over `range`.
double nice_step(double range, int ticks) {
  const double raw = range / std::max(ticks, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / magnitude;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * magnitude;
}

/// Multiples of `step` within [lo, hi] (to rounding).
std::vector<double> ticks_between(double lo, double hi, double step) {
  std::vector<double> out;
  for (long k = std::lround(std::ceil(lo / step - kEps)); static_cast<double>(k) * step <= hi + kEps * step;
       ++k) {
    out.push_back(static_cast<double>(k) * step);
  }
  return out;
}

/// Pieces of a trajectory whose poses lie on `level`, thinned.
std::vector<std::vector<Vec2>> runs_on_level(const RunView& run, const std::vector<RunView::Stamped>& traj,
                                             int level) {
  std::vector<std::vector<Vec2>> runs;
  bool open = false;
  for (const RunView::Stamped& s : traj) {
    const bool on = level_of_height(run, s.p.z()) == level;
    if (on && !open) runs.emplace_back();
    if (on) runs.back().push_back(s.p.head<2>());
    open = on;
  }
  for (auto& r : runs) r = thinned(r, kTrajectoryStepM);
  return runs;
}

/// The rectangle [s0, s1] along the segment a -> b, `thickness` wide about it.
Polygon2 strip(const Vec2& a, const Vec2& b, double s0, double s1, double thickness) {
  const Vec2 d = (b - a).normalized();
  const Vec2 n = 0.5 * thickness * Vec2(-d.y(), d.x());
  return {a + s0 * d - n, a + s1 * d - n, a + s1 * d + n, a + s0 * d + n};
}

// ---------------------------------------------------------------------------------------
// Bird's-eye

class BirdseyeDrawer {
 public:
  BirdseyeDrawer(const RunView& run, int level) : run_(run), level_(level) {
    const std::size_t n = std::max<std::size_t>(run.levels.size(), 1);
    if (level < 0 || static_cast<std::size_t>(level) >= n) {
      throw std::invalid_argument("birdseye_svg: the run has no level " + std::to_string(level));
    }
    if (run.scene) {
      for (std::size_t i = 0; i < run.scene->levels.size(); ++i) {
        if (level_of_height(run, run.scene->levels[i].elevation) == level)
          scene_levels_.push_back(static_cast<int>(i));
      }
    }
    for (const RunView::Wall& w : run.walls) {
      if (level_of_height(run, w.z0) == level) walls_.push_back(&w);
    }
    for (const RunView::Room& r : run.rooms) {
      if (r.level == level) rooms_.push_back(&r);
    }
    for (const io::RoomTruth& t : run.truth_rooms) {
      if (level_of_height(run, t.elevation) == level) truth_rooms_.push_back(&t);
    }
    estimated_ = runs_on_level(run, run.estimated, level);
    truth_ = runs_on_level(run, run.truth, level);
  }

  std::string draw() {
    layout();
    const double floor_z = run_.levels.empty() ? 0.0 : run_.levels[level_];
    out_ = open_svg(page_w_, page_h_, "tsg-birdseye",
                    run_.label + " \xE2\x80\x94 level " + std::to_string(level_), style());
    out_ += text(
        kPageMargin, kPageMargin + kTitleBaseline, "title",
        run_.label + " \xE2\x80\x94 level " + std::to_string(level_) + ", floor at " + num(floor_z) + " m");
    std::size_t n_rooms = 0;
    for (const RunView::Room* r : rooms_) n_rooms += is_corridor(*r) ? 0 : 1;
    out_ += text(kPageMargin, kPageMargin + kSubtitleBaseline, "subtitle",
                 std::to_string(n_rooms) + " rooms, " + std::to_string(rooms_.size() - n_rooms) +
                     " corridors, " + std::to_string(walls_.size()) + " wall planes on this level; " +
                     short_num(frame_.scale) + " px per metre, y up");
    out_ += "<g class=\"plan\">\n";
    draw_scene();
    draw_nodes();
    draw_free_space();
    draw_rooms();
    draw_truth_rooms();
    draw_walls();
    draw_trajectories();
    draw_labels();
    out_ += "</g>\n";
    svg::ScaleBarStyle bar;
    bar.px_per_metre = frame_.scale;
    bar.metres = kScaleBarMetres;
    bar.thickness = kScaleBarThickness;
    bar.text_gap = kScaleTextGap;
    bar.text_shift = kScaleTextShift;
    bar.ink = kInk;
    bar.paper = kBackground;
    out_ += svg::scale_bar(kPageMargin, frame_.top + plan_h_ + kScaleBarGap, bar);
    out_ +=
        draw_legend(legend(), kPageMargin, frame_.top + plan_h_ + kScaleBarGap + kScaleBarHeight, plan_w_);
    out_ += "</svg>\n";
    return out_;
  }

 private:
  bool on_level(const Eigen::Vector3d& p) const { return level_of_height(run_, p.z()) == level_; }
  bool on_scene_level(int scene_level) const {
    return std::find(scene_levels_.begin(), scene_levels_.end(), scene_level) != scene_levels_.end();
  }

  void layout() {
    Extent e;
    for (int l : scene_levels_) e.add(run_.scene->levels[l].slab);
    if (run_.scene) {
      for (const scene::Wall& w : run_.scene->walls) {
        if (on_scene_level(w.level)) e.add(w.from), e.add(w.to);
      }
    }
    for (const RunView::Wall* w : walls_) e.add(w->a), e.add(w->b);
    for (const RunView::Node& n : run_.nodes) {
      if (on_level(n.p)) e.add(Vec2(n.p.head<2>()));
    }
    for (const RunView::Room* r : rooms_) {
      e.add(r->footprint());
      for (const Eigen::Vector3d& p : r->free_space) e.add(Vec2(p.head<2>()));
    }
    for (const io::RoomTruth* t : truth_rooms_) e.add(t->polygon);
    for (const auto* runs : {&estimated_, &truth_}) {
      for (const auto& r : *runs) e.add(r);
    }
    if (e.empty()) e.add(Vec2::Zero());
    e.min_x -= kPlanPaddingM, e.min_y -= kPlanPaddingM;
    e.max_x += kPlanPaddingM, e.max_y += kPlanPaddingM;
    const double scale = svg::drawing_scale(e, kPlanPxPerMetre);
    plan_w_ = std::max((e.max_x - e.min_x) * scale, kMinPlanWidth);
    plan_h_ = (e.max_y - e.min_y) * scale;
    frame_.min_x = e.min_x - 0.5 * (plan_w_ / scale - (e.max_x - e.min_x));  // centred when widened
    frame_.max_y = e.max_y;
    frame_.left = kPageMargin;
    frame_.top = kPageMargin + kTitleHeight;
    frame_.scale = scale;
    page_w_ = plan_w_ + 2.0 * kPageMargin;
    page_h_ = frame_.top + plan_h_ + kScaleBarGap + kScaleBarHeight +
              legend_height(legend().size(), plan_w_) + kPageMargin;
  }

  std::vector<std::pair<std::string, std::string>> style() const {
    return {
        {".scene-slab",
         std::string("fill: ") + kSceneSlab + "; stroke: " + kSceneSlabStroke + "; stroke-width: 1;"},
        {".scene-void", std::string("fill: ") + kBackground + "; stroke: " + kSceneSlabStroke +
                            "; stroke-width: 1; stroke-dasharray: 4 3;"},
        {".scene-wall, .key-scene-wall", std::string("fill: ") + kSceneWall + "; stroke: none;"},
        {".scene-railing", std::string("stroke: ") + kSceneWall + "; stroke-width: 2.5;"},
        {".scene-railing.bars", "stroke-dasharray: 2 3;"},
        // Dots: widths are attributes (in the path's scaled units); the keys' are in px.
        {".node", std::string("fill: none; stroke: ") + kNode + "; stroke-linecap: round;"},
        {".free-space", "fill: none; stroke-linecap: round; stroke-opacity: 0.5;"},
        {".key-node", std::string("fill: none; stroke: ") + kNode +
                          "; stroke-linecap: round; stroke-width: " + num(kNodeDotPx) + ";"},
        {".key-free-space", "fill: none; stroke-linecap: round; stroke-opacity: 0.5; stroke-width: " +
                                num(kFreeSpaceDotPx) + ";"},
        {".room, .corridor, .key-room, .key-corridor",
         "fill-opacity: 0.14; stroke-width: 2; stroke-opacity: 0.9;"},
        {".truth-room, .key-truth-room",
         std::string("fill: none; stroke: ") + kTruthRoom + "; stroke-width: 1.2; stroke-dasharray: 6 4;"},
        {".wall, .key-wall",
         std::string("stroke: ") + kMappedWall + "; stroke-width: 3; stroke-linecap: round;"},
        {".trajectory-true, .key-trajectory-true",
         std::string("fill: none; stroke: ") + kTrue +
             "; stroke-width: 4.5; stroke-opacity: 0.45; stroke-linejoin: round;"},
        {".trajectory-estimated, .key-trajectory-estimated",
         std::string("fill: none; stroke: ") + kEstimated + "; stroke-width: 1.4; stroke-linejoin: round;"},
        {".start", std::string("fill: ") + kBackground + "; stroke: " + kEstimated + "; stroke-width: 2;"},
        {".room-label, .key-room-label", "font-size: 11px; font-weight: bold; text-anchor: middle;"},
        {".truth-name", std::string("font-size: 10px; font-style: italic; fill: ") + kTruthRoom + ";"},
    };
  }

  std::vector<LegendEntry> legend() const {
    RunView::Room room, corridor;
    corridor.kind = "corridor";
    const std::string rc = room_colour(room), cc = room_colour(corridor);
    const std::string box = " x=\"{X0}\" y=\"{Y}\" transform=\"translate(0," + num(-0.5 * kSwatchTall) +
                            ")\" width=\"" + num(kLegendSwatch) + "\" height=\"" + num(kSwatchTall) + "\"";
    return {
        {"<rect class=\"key-scene-wall\"" + box + "/>", "scene walls and railings (truth)"},
        {key_line("key-wall"), "mapped wall plane"},
        {key_dot("key-node"), "traversable node"},
        {key_dot("key-free-space", " stroke=\"" + rc + "\""), "free space of a room (its colour)"},
        {"<rect class=\"key-room\" fill=\"" + rc + "\" stroke=\"" + rc + "\"" + box + "/>", "room (cyan)"},
        {"<rect class=\"key-corridor\" fill=\"" + cc + "\" stroke=\"" + cc + "\"" + box + "/>",
         "corridor (orange)"},
        {"<rect class=\"key-truth-room\"" + box + "/>", "ground-truth room and its name"},
        {key_line("key-trajectory-true"), "true trajectory"},
        {key_line("key-trajectory-estimated"), "estimated trajectory (circle: start)"},
        {"<text class=\"key-room-label halo\" x=\"{XM}\" y=\"{Y}\" dy=\"" + num(kTextBaselineShift) +
             "\">3</text>",
         "room id \xC2\xB7 lap of its first extraction"},
    };
  }

  void draw_scene() {
    if (scene_levels_.empty()) return;
    const scene::Scene& scene = *run_.scene;
    out_ += "<g class=\"layer-scene\">\n";
    for (int l : scene_levels_) {
      out_ +=
          "<polygon class=\"scene-slab\" points=\"" + points_attr(frame_, scene.levels[l].slab) + "\"/>\n";
      for (const Polygon2& v : scene.levels[l].voids) {
        out_ += "<polygon class=\"scene-void\" points=\"" + points_attr(frame_, v) + "\"/>\n";
      }
    }
    for (const scene::Wall& w : scene.walls) {
      if (!on_scene_level(w.level)) continue;
      // The pieces standing on the floor: doors are gaps, windows are not.
      for (const scene::WallPiece& piece : scene::wall_pieces(w)) {
        if (piece.z0 > 0.0) continue;
        out_ += "<polygon class=\"scene-wall\" points=\"" +
                points_attr(frame_, strip(w.from, w.to, piece.s0, piece.s1, w.thickness)) + "\"/>\n";
      }
    }
    for (const scene::Railing& r : scene.railings) {
      if (!on_scene_level(r.level)) continue;
      const Vec2 a = frame_.px(r.from), b = frame_.px(r.to);
      out_ += std::string("<line class=\"scene-railing") +
              (r.style == scene::RailingStyle::kBars    ? " bars"
               : r.style == scene::RailingStyle::kGlass ? " glass"
                                                        : "") +
              "\" x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) + "\" y2=\"" +
              num(b.y()) + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  void draw_nodes() {
    Dots dots(kNodeCellPx, kNodeDotPx);
    for (const RunView::Node& n : run_.nodes) {
      if (on_level(n.p)) dots.add(frame_.px(n.p.head<2>()));
    }
    out_ += dots.path("node");
  }

  void draw_free_space() {
    out_ += "<g class=\"layer-free-space\">\n";
    for (const RunView::Room* r : rooms_) {
      Dots dots(kFreeSpaceCellM * frame_.scale, kFreeSpaceDotPx);
      for (const Eigen::Vector3d& p : r->free_space) dots.add(frame_.px(p.head<2>()));
      out_ += dots.path("free-space",
                        " data-room=\"" + std::to_string(r->id) + "\" stroke=\"" + room_colour(*r) + "\"");
    }
    out_ += "</g>\n";
  }

  void draw_rooms() {
    out_ += "<g class=\"layer-rooms\">\n";
    for (const RunView::Room* r : rooms_) {
      const std::string colour = room_colour(*r);
      out_ += std::string("<polygon class=\"") + (is_corridor(*r) ? "corridor" : "room") + "\" data-id=\"" +
              std::to_string(r->id) + "\" fill=\"" + colour + "\" stroke=\"" + colour + "\" points=\"" +
              points_attr(frame_, r->footprint()) + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  void draw_truth_rooms() {
    out_ += "<g class=\"layer-truth-rooms\">\n";
    for (const io::RoomTruth* t : truth_rooms_) {
      out_ += "<polygon class=\"truth-room\" points=\"" + points_attr(frame_, t->polygon) + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  void draw_walls() {
    out_ += "<g class=\"layer-walls\">\n";
    for (const RunView::Wall* w : walls_) {
      const Vec2 a = frame_.px(w->a), b = frame_.px(w->b);
      out_ += "<line class=\"wall\" data-id=\"" + std::to_string(w->id) + "\" x1=\"" + num(a.x()) +
              "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) + "\" y2=\"" + num(b.y()) + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  void draw_trajectories() {
    out_ += "<g class=\"layer-trajectories\">\n";
    for (const auto& r : truth_) {
      out_ += "<polyline class=\"trajectory-true\" points=\"" + points_attr(frame_, r) + "\"/>\n";
    }
    for (const auto& r : estimated_) {
      out_ += "<polyline class=\"trajectory-estimated\" points=\"" + points_attr(frame_, r) + "\"/>\n";
    }
    if (!run_.estimated.empty() && on_level(run_.estimated.front().p)) {
      const Vec2 c = frame_.px(run_.estimated.front().p.head<2>());
      out_ += "<circle class=\"start\" cx=\"" + num(c.x()) + "\" cy=\"" + num(c.y()) + "\" r=\"" +
              num(kStartRadius) + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  struct Box {
    double x0, y0, x1, y1;
    bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  };

  /// Where a label of this box goes: as asked, or moved up or down by whole label heights
  /// until it clears the labels already placed (as asked when nothing clears).
  Box place(const Box& wanted) {
    for (int k = 0; k <= kLabelMaxShifts; ++k) {
      const double shift = (k % 2 == 1 ? 1.0 : -1.0) * std::ceil(0.5 * k) * kLabelHeight;
      const Box b{wanted.x0, wanted.y0 + shift, wanted.x1, wanted.y1 + shift};
      if (std::none_of(placed_.begin(), placed_.end(), [&](const Box& p) { return p.overlaps(b); })) {
        placed_.push_back(b);
        return b;
      }
    }
    placed_.push_back(wanted);
    return wanted;
  }

  /// Ground-truth names at the top left corner inside their rooms, then the detected rooms'
  /// labels at their centres, moved off each other, off the names and off the start marker.
  void draw_labels() {
    out_ += "<g class=\"layer-labels\">\n";
    if (!run_.estimated.empty() && on_level(run_.estimated.front().p)) {  // keep the start marker visible
      const Vec2 c = frame_.px(run_.estimated.front().p.head<2>());
      placed_.push_back(
          {c.x() - kStartRadius, c.y() - kStartRadius, c.x() + kStartRadius, c.y() + kStartRadius});
    }
    for (const io::RoomTruth* t : truth_rooms_) {
      Extent e;
      e.add(t->polygon);
      const Vec2 corner = frame_.px(Vec2(e.min_x, e.max_y));
      const double w = kLabelCharWidth * static_cast<double>(t->name.size());
      const Box b = place({corner.x() + kTruthNameInset, corner.y() + kTruthNameInset,
                           corner.x() + kTruthNameInset + w, corner.y() + kTruthNameInset + kLabelHeight});
      out_ += text(b.x0, b.y0 + kTruthNameBaseline, "truth-name halo", t->name);
    }
    for (const RunView::Room* r : rooms_) {
      const std::string label =
          std::to_string(r->id) + " \xC2\xB7 " +
          (r->first_lap > 0 ? "lap " + std::to_string(r->first_lap) : std::string("no event"));
      const Vec2 c = frame_.px(r->center());
      const double half =
          0.5 * kLabelCharWidth * static_cast<double>(label.size() - 1);  // the dot is 2 bytes
      const Box b =
          place({c.x() - half, c.y() - 0.5 * kLabelHeight, c.x() + half, c.y() + 0.5 * kLabelHeight});
      out_ += text(0.5 * (b.x0 + b.x1), 0.5 * (b.y0 + b.y1) + kTextBaselineShift, "room-label halo", label);
    }
    out_ += "</g>\n";
  }

  const RunView& run_;
  int level_;
  std::vector<int> scene_levels_;
  std::vector<const RunView::Wall*> walls_;
  std::vector<const RunView::Room*> rooms_;
  std::vector<const io::RoomTruth*> truth_rooms_;
  std::vector<std::vector<Vec2>> estimated_, truth_;
  std::vector<Box> placed_;
  Frame frame_;
  double plan_w_ = 0.0, plan_h_ = 0.0, page_w_ = 0.0, page_h_ = 0.0;
  std::string out_;
};

// ---------------------------------------------------------------------------------------
// Side view

/// Pieces of [lo, hi] left after removing the intervals `cut`.
std::vector<std::pair<double, double>> subtract(double lo, double hi,
                                                std::vector<std::pair<double, double>> cut) {
  std::sort(cut.begin(), cut.end());
  std::vector<std::pair<double, double>> out;
  double at = lo;
  for (const auto& [a, b] : cut) {
    if (b <= at) continue;
    if (a >= hi) break;
    if (a > at) out.emplace_back(at, a);
    at = std::max(at, b);
  }
  if (at < hi) out.emplace_back(at, hi);
  return out;
}

class SideViewDrawer {
 public:
  explicit SideViewDrawer(const RunView& run) : run_(run) {}

  std::string draw() {
    layout();
    out_ = open_svg(page_w_, page_h_, "tsg-side-view", run_.label + " \xE2\x80\x94 side view", style());
    out_ += text(kPageMargin, kPageMargin + kTitleBaseline, "title",
                 run_.label + " \xE2\x80\x94 side view (x\xE2\x80\x93z, every y projected)");
    out_ += text(kPageMargin, kPageMargin + kSubtitleBaseline, "subtitle",
                 "grey bars: the scene's floors, gaps where a void opens; dashed: the run's levels; " +
                     short_num(frame_.scale) + " px per metre in x and z");
    draw_axes();
    draw_slabs();
    draw_levels();
    draw_points();
    draw_trajectories();
    out_ += draw_legend(legend(), kPageMargin, plot_bottom() + kAxisBottom + kLegendGap,
                        page_w_ - 2.0 * kPageMargin);
    out_ += "</svg>\n";
    return out_;
  }

 private:
  Vec2 xz(const Eigen::Vector3d& p) const { return {p.x(), p.z()}; }

  void layout() {
    Extent e;
    for (const RunView::Node& n : run_.nodes) e.add(xz(n.p));
    for (const RunView::Room& r : run_.rooms) {
      for (const Eigen::Vector3d& p : r.free_space) e.add(xz(p));
    }
    for (const auto* traj : {&run_.estimated, &run_.truth}) {
      for (const RunView::Stamped& s : *traj) e.add(xz(s.p));
    }
    if (run_.scene) {
      for (const scene::Level& l : run_.scene->levels) {
        Extent s;
        s.add(l.slab);
        e.add(Vec2(s.min_x, l.elevation - kSlabThicknessM));
        e.add(Vec2(s.max_x, l.elevation));
      }
    }
    for (double z : run_.levels) {
      if (!e.empty()) e.add(Vec2(e.min_x, z));
    }
    if (e.empty()) e.add(Vec2::Zero());
    e.min_x -= kSidePaddingM, e.max_x += kSidePaddingM;
    e.min_y -= kSidePaddingM, e.max_y += kSidePaddingM;
    extent_ = e;
    const double scale = svg::drawing_scale(e, kSidePxPerMetre);
    plot_w_ = (e.max_x - e.min_x) * scale;
    plot_h_ = (e.max_y - e.min_y) * scale;
    frame_.min_x = e.min_x;
    frame_.max_y = e.max_y;
    frame_.left = kPageMargin + kAxisLeft;
    frame_.top = kPageMargin + kTitleHeight;
    frame_.scale = scale;
    page_w_ = std::max(frame_.left + plot_w_, kPageMargin + kMinPlanWidth) + kPageMargin;
    page_h_ = plot_bottom() + kAxisBottom + kLegendGap +
              legend_height(legend().size(), page_w_ - 2.0 * kPageMargin) + kPageMargin;
  }

  double plot_bottom() const { return frame_.top + plot_h_; }

  std::vector<std::pair<std::string, std::string>> style() const {
    return {
        {".frame", std::string("fill: none; stroke: ") + kFrameStroke + "; stroke-width: 1;"},
        {".grid", std::string("stroke: ") + kGrid + "; stroke-width: 1;"},
        {".tick", std::string("stroke: ") + kInk + "; stroke-width: 1;"},
        {".tick-label", "font-size: 10px;"},
        {".tick-label.z", "text-anchor: end;"},
        {".tick-label.x", "text-anchor: middle;"},
        {".axis-title", "font-size: 11px;"},
        {".axis-title.z", "text-anchor: middle;"},
        {".scene-slab, .key-scene-slab", std::string("fill: ") + kSideSlab + "; stroke: none;"},
        {".slab-name", std::string("font-size: 10px; fill: ") + kMutedInk + ";"},
        {".level-line, .key-level-line",
         std::string("stroke: ") + kMutedInk + "; stroke-width: 1; stroke-dasharray: 5 4;"},
        {".level-name", std::string("font-size: 10px; text-anchor: end; fill: ") + kMutedInk + ";"},
        {".node", std::string("fill: none; stroke: ") + kNode + "; stroke-linecap: round;"},
        {".free-space", "fill: none; stroke-linecap: round; stroke-opacity: 0.6;"},
        {".key-node", std::string("fill: none; stroke: ") + kNode +
                          "; stroke-linecap: round; stroke-width: " + num(kNodeDotPx) + ";"},
        {".key-free-space", "fill: none; stroke-linecap: round; stroke-opacity: 0.6; stroke-width: " +
                                num(kSideFreeSpaceDotPx) + ";"},
        {".trajectory-true, .key-trajectory-true",
         std::string("fill: none; stroke: ") + kTrue +
             "; stroke-width: 4; stroke-opacity: 0.45; stroke-linejoin: round;"},
        {".trajectory-estimated, .key-trajectory-estimated",
         std::string("fill: none; stroke: ") + kEstimated + "; stroke-width: 1.2; stroke-linejoin: round;"},
    };
  }

  std::vector<LegendEntry> legend() const {
    RunView::Room room;
    return {
        {"<rect class=\"key-scene-slab\" x=\"{X0}\" y=\"{Y}\" transform=\"translate(0," +
             num(-0.5 * kSwatchThin) + ")\" width=\"" + num(kLegendSwatch) + "\" height=\"" +
             num(kSwatchThin) + "\"/>",
         "scene floor (truth)"},
        {key_line("key-level-line"), "floor of a run level"},
        {key_dot("key-node"), "traversable node"},
        {key_dot("key-free-space", " stroke=\"" + room_colour(room) + "\""),
         "free space of a room (its colour)"},
        {key_line("key-trajectory-true"), "true sensor height"},
        {key_line("key-trajectory-estimated"), "estimated sensor height"},
    };
  }

  void draw_axes() {
    const double left = frame_.left, right = frame_.left + plot_w_, top = frame_.top, bottom = plot_bottom();
    out_ += "<g class=\"axes\">\n";
    const double sx = nice_step(extent_.max_x - extent_.min_x, kSideTicksX);
    for (double x : ticks_between(extent_.min_x, extent_.max_x, sx)) {
      const double px = frame_.px(Vec2(x, 0.0)).x();
      out_ += "<line class=\"grid\" x1=\"" + num(px) + "\" y1=\"" + num(top) + "\" x2=\"" + num(px) +
              "\" y2=\"" + num(bottom) + "\"/>\n";
      out_ += "<line class=\"tick\" x1=\"" + num(px) + "\" y1=\"" + num(bottom) + "\" x2=\"" + num(px) +
              "\" y2=\"" + num(bottom + kTickLength) + "\"/>\n";
      out_ += text(px, bottom + kTickLabelGap, "tick-label x", short_num(x));
    }
    const double sz = nice_step(extent_.max_y - extent_.min_y, kSideTicksZ);
    for (double z : ticks_between(extent_.min_y, extent_.max_y, sz)) {
      const double py = frame_.px(Vec2(0.0, z)).y();
      out_ += "<line class=\"grid\" x1=\"" + num(left) + "\" y1=\"" + num(py) + "\" x2=\"" + num(right) +
              "\" y2=\"" + num(py) + "\"/>\n";
      out_ += "<line class=\"tick\" x1=\"" + num(left - kTickLength) + "\" y1=\"" + num(py) + "\" x2=\"" +
              num(left) + "\" y2=\"" + num(py) + "\"/>\n";
      out_ += text(left - kTickLength - kTickLabelPad, py + kTextBaselineShift, "tick-label z", short_num(z));
    }
    out_ += "<rect class=\"frame\" x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(plot_w_) +
            "\" height=\"" + num(plot_h_) + "\"/>\n";
    out_ += text(right - 2.0 * kLegendSwatch, bottom + kAxisTitleGap, "axis-title", "x (m)");
    // Rotated along the z axis, clear of the tick numbers.
    const double zx = kPageMargin + kAxisTitleInset, zy = 0.5 * (top + bottom);
    out_ += "<text class=\"axis-title z\" x=\"" + num(zx) + "\" y=\"" + num(zy) +
            "\" transform=\"rotate(-90 " + num(zx) + " " + num(zy) + ")\">z (m)</text>\n";
    out_ += "</g>\n";
  }

  void draw_slabs() {
    if (!run_.scene) return;
    out_ += "<g class=\"layer-scene\">\n";
    for (const scene::Level& l : run_.scene->levels) {
      Extent slab;
      slab.add(l.slab);
      std::vector<std::pair<double, double>> voids;
      for (const Polygon2& v : l.voids) {
        Extent ve;
        ve.add(v);
        voids.emplace_back(ve.min_x, ve.max_x);
      }
      const auto pieces = subtract(slab.min_x, slab.max_x, voids);
      for (const auto& [x0, x1] : pieces) {
        const Vec2 a = frame_.px(Vec2(x0, l.elevation)),
                   b = frame_.px(Vec2(x1, l.elevation - kSlabThicknessM));
        out_ += "<rect class=\"scene-slab\" x=\"" + num(a.x()) + "\" y=\"" + num(a.y()) + "\" width=\"" +
                num(b.x() - a.x()) + "\" height=\"" + num(b.y() - a.y()) + "\"/>\n";
      }
      if (!pieces.empty()) {
        const Vec2 at = frame_.px(Vec2(pieces.front().first, l.elevation - kSlabThicknessM));
        out_ += text(at.x(), at.y() + kTickLabelGap, "slab-name", l.name + " (scene)");
      }
    }
    out_ += "</g>\n";
  }

  void draw_levels() {
    out_ += "<g class=\"layer-levels\">\n";
    const double left = frame_.left, right = frame_.left + plot_w_;
    for (std::size_t i = 0; i < run_.levels.size(); ++i) {
      const double py = frame_.px(Vec2(0.0, run_.levels[i])).y();
      out_ += "<line class=\"level-line\" x1=\"" + num(left) + "\" y1=\"" + num(py) + "\" x2=\"" +
              num(right) + "\" y2=\"" + num(py) + "\"/>\n";
      out_ += text(right - kLevelNameGap, py - kLevelNameGap, "level-name halo",
                   "run level " + std::to_string(i) + ", z " + num(run_.levels[i]) + " m");
    }
    out_ += "</g>\n";
  }

  void draw_points() {
    Dots nodes(kNodeCellPx, kNodeDotPx);
    for (const RunView::Node& n : run_.nodes) nodes.add(frame_.px(xz(n.p)));
    out_ += nodes.path("node");
    out_ += "<g class=\"layer-free-space\">\n";
    for (const RunView::Room& r : run_.rooms) {
      Dots dots(kNodeCellPx, kSideFreeSpaceDotPx);
      for (const Eigen::Vector3d& p : r.free_space) dots.add(frame_.px(xz(p)));
      out_ += dots.path("free-space",
                        " data-room=\"" + std::to_string(r.id) + "\" stroke=\"" + room_colour(r) + "\"");
    }
    out_ += "</g>\n";
  }

  void draw_trajectories() {
    out_ += "<g class=\"layer-trajectories\">\n";
    for (const auto& [traj, cls] : {std::make_pair(&run_.truth, "trajectory-true"),
                                    std::make_pair(&run_.estimated, "trajectory-estimated")}) {
      std::vector<Vec2> pts;
      for (const RunView::Stamped& s : *traj) pts.push_back(xz(s.p));
      pts = thinned(pts, kTrajectoryStepM);
      if (pts.empty()) continue;
      out_ += std::string("<polyline class=\"") + cls + "\" points=\"" + points_attr(frame_, pts) + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  const RunView& run_;
  Extent extent_;
  Frame frame_;
  double plot_w_ = 0.0, plot_h_ = 0.0, page_w_ = 0.0, page_h_ = 0.0;
  std::string out_;
};

// ---------------------------------------------------------------------------------------
// Time plot

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
    out_ = open_svg(page_w_, page_h_, "tsg-timing", run_.label + " \xE2\x80\x94 timing", style());
    out_ += text(kPageMargin, kPageMargin + kTitleBaseline, "title",
                 run_.label + " \xE2\x80\x94 time per scan and per solve");
    double pgo_s = 0.0;
    std::size_t full = 0;
    for (const RunView::Solve& s : run_.solves) pgo_s += s.seconds, full += s.full ? 1 : 0;
    out_ += text(kPageMargin, kPageMargin + kSubtitleBaseline, "subtitle",
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
    return {
        {".frame", std::string("fill: none; stroke: ") + kFrameStroke + "; stroke-width: 1;"},
        {".grid", std::string("stroke: ") + kGrid + "; stroke-width: 1;"},
        {".tick", std::string("stroke: ") + kInk + "; stroke-width: 1;"},
        {".tick-label", "font-size: 10px;"},
        {".tick-label.v", "text-anchor: end;"},
        {".tick-label.t", "text-anchor: middle;"},
        {".axis-title", "font-size: 11px;"},
        {".panel-title", "font-size: 12px; font-weight: bold;"},
        {".frontend",
         std::string("fill: none; stroke: ") + kFrontend + "; stroke-width: 1; stroke-linejoin: round;"},
        {".solve.local, .key-local",
         std::string("fill: ") + kBackground + "; stroke: " + kSolveLocal + "; stroke-width: 1.3;"},
        {".solve.full, .key-full", std::string("fill: ") + kSolveFull + "; stroke: none;"},

    };
  }

  void draw_panel(const TimePanel& p, const std::string& title) {
    const double right = left_ + kTimingPlotWidth, bottom = p.top + p.height;
    out_ += "<g class=\"panel\">\n";
    out_ += text(left_, p.top - kLevelNameGap - kTextBaselineShift, "panel-title", title);
    const double st = nice_step(t_max_, kTimingTicksX);
    for (double t : ticks_between(0.0, t_max_, st)) {
      const double x = px_t(t);
      out_ += "<line class=\"grid\" x1=\"" + num(x) + "\" y1=\"" + num(p.top) + "\" x2=\"" + num(x) +
              "\" y2=\"" + num(bottom) + "\"/>\n";
      out_ += "<line class=\"tick\" x1=\"" + num(x) + "\" y1=\"" + num(bottom) + "\" x2=\"" + num(x) +
              "\" y2=\"" + num(bottom + kTickLength) + "\"/>\n";
    }
    for (double v : ticks_between(0.0, p.max_value, p.step)) {
      const double y = px_v(p, v);
      out_ += "<line class=\"grid\" x1=\"" + num(left_) + "\" y1=\"" + num(y) + "\" x2=\"" + num(right) +
              "\" y2=\"" + num(y) + "\"/>\n";
      out_ += "<line class=\"tick\" x1=\"" + num(left_ - kTickLength) + "\" y1=\"" + num(y) + "\" x2=\"" +
              num(left_) + "\" y2=\"" + num(y) + "\"/>\n";
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

std::string birdseye_svg(const RunView& run, int level) { return BirdseyeDrawer(run, level).draw(); }

std::string side_view_svg(const RunView& run) { return SideViewDrawer(run).draw(); }

std::string timing_svg(const RunView& run) { return TimingDrawer(run).draw(); }

}  // namespace tsgraphs::report
