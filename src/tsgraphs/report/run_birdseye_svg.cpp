// The bird's-eye of one level of a run (birdseye_svg): the scene, the map and the
// trajectories seen from above, labelled, with a scale bar and a legend.
#include "tsgraphs/report/run_svg.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/report/run_svg_drawing.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::report {
namespace {

using namespace run_drawing;

// Layout (pixels unless the name says metres)
constexpr double kPlanPxPerMetre = 24.0;  // lowered for runs kilometres long (svg::drawing_scale)
constexpr double kPlanPaddingM = 0.8;     // around what is drawn
constexpr int kScaleBarMetres = 5;
constexpr double kScaleBarGap = 12.0;     // between the plan and the scale bar
constexpr double kScaleBarHeight = 34.0;  // the bar and its numbers
constexpr double kScaleBarThickness = 6.0;
constexpr double kScaleTextGap = 12.0;
constexpr double kScaleTextShift = 3.0;
constexpr double kStartRadius = 5.0;  // the estimated trajectory's first pose
constexpr double kSwatchTall = 12.0;  // heights of the legend's samples: areas,

// Dots
constexpr double kFreeSpaceCellM = 0.2;  // one free-space dot per cell (the ESDF's grid): a tint
constexpr double kFreeSpaceDotPx = 3.4;

// Labels
constexpr double kLabelCharWidth = 6.6;  // rough width of a label character (11 px bold)
constexpr double kLabelHeight = 14.0;
constexpr int kLabelMaxShifts = 8;           // tries to move a label off the ones already placed
constexpr double kTruthNameInset = 4.0;      // a ground-truth room's name, from its top left corner
constexpr double kTruthNameBaseline = 11.0;  // within its label box

// Colours
constexpr const char* kSceneSlab = "#f4f4f4";
constexpr const char* kSceneSlabStroke = "#dddddd";
constexpr const char* kSceneWall = "#c6c6c6";
constexpr const char* kMappedWall = "#1b1b1b";
constexpr const char* kTruthRoom = "#555555";

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
    std::size_t n_rooms = 0;
    for (const RunView::Room* r : rooms_) n_rooms += is_corridor(*r) ? 0 : 1;
    out_ = open_svg(page_w_, page_h_, "tsg-birdseye",
                    run_.label + " \xE2\x80\x94 level " + std::to_string(level_), style());
    out_ += headings(
        run_.label + " \xE2\x80\x94 level " + std::to_string(level_) + ", floor at " + num(floor_z) + " m",
        std::to_string(n_rooms) + " rooms, " + std::to_string(rooms_.size() - n_rooms) + " corridors, " +
            std::to_string(walls_.size()) + " wall planes on this level; " + short_num(frame_.scale) +
            " px per metre, y up");
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

}  // namespace

std::string birdseye_svg(const RunView& run, int level) { return BirdseyeDrawer(run, level).draw(); }

}  // namespace tsgraphs::report
