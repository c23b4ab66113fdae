// The side view of a run (side_view_svg): x horizontal, z up, every y projected; the scene's
// floors, the run's levels, its nodes, free space and trajectories' heights.
#include "tsgraphs/report/run_svg.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/report/run_svg_drawing.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::report {
namespace {

using namespace run_drawing;

// Layout (pixels unless the name says metres)
constexpr double kSidePxPerMetre = 28.0;
constexpr double kSidePaddingM = 0.6;
constexpr double kSlabThicknessM = 0.25;  // drawn under each scene floor
constexpr double kAxisTitleInset = 10.0;  // the z axis title's baseline from the page margin
constexpr int kSideTicksX = 10;           // about this many ticks along x
constexpr int kSideTicksZ = 5;
constexpr double kSwatchThin = 6.0;  // floors seen from the side
constexpr double kSideFreeSpaceDotPx = 3.0;

// Colours
constexpr const char* kSideSlab = "#b8b8b8";

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
    out_ += headings(run_.label + " \xE2\x80\x94 side view (x\xE2\x80\x93z, every y projected)",
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
    std::vector<std::pair<std::string, std::string>> rules = axes_style("z", "x");
    rules.insert(
        rules.end(),
        {
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
             std::string("fill: none; stroke: ") + kEstimated +
                 "; stroke-width: 1.2; stroke-linejoin: round;"},
        });
    return rules;
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
      out_ += x_grid_line(px, top, bottom);
      out_ += text(px, bottom + kTickLabelGap, "tick-label x", short_num(x));
    }
    const double sz = nice_step(extent_.max_y - extent_.min_y, kSideTicksZ);
    for (double z : ticks_between(extent_.min_y, extent_.max_y, sz)) {
      const double py = frame_.px(Vec2(0.0, z)).y();
      out_ += y_grid_line(py, left, right);
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

}  // namespace

std::string side_view_svg(const RunView& run) { return SideViewDrawer(run).draw(); }

}  // namespace tsgraphs::report
