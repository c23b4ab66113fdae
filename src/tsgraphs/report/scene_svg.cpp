// Bird's-eye SVG of a scene (tsgraphs draw-scene): one panel per level, in a common metric
// scale with y up, drawn in layers from the floor up: slab, voids, rooms, ramps, voxel maps,
// boxes, walls with their openings, railings, the first lap of the path, and the labels.
//
// Every element a reader (or a test) may want to count carries a class: "wall full",
// "wall header" (the wall above an opening), "wall sill" (below a window), "door", "door leaf"
// (a leaf the scene has, a box labelled door), "window",
// "railing solid", "railing bars", "railing glass", "box", "void", "room", "ramp", "voxels", "path",
// "arrow", "start", "end", "panel", "panel-title". Numbers are printed with two decimals
// whatever the locale, so the same scene always gives the same bytes.
#include "tsgraphs/report/scene_svg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/report/svg_writer.hpp"
#include "tsgraphs/scene/door_leaves.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"

namespace tsgraphs::report {
namespace {

using scene::Scene;

// ---------------------------------------------------------------------------------------
// Layout (pixels unless the name says metres or seconds)

constexpr double kPxPerMetre = 40.0;     // common scale of every panel (svg::drawing_scale may lower it)
constexpr double kWorldPaddingM = 0.6;   // free space around the scene's extent
constexpr double kPageMargin = 20.0;     // around the whole picture
constexpr double kTitleHeight = 56.0;    // scene name and subtitle
constexpr double kTitleBaseline = 22.0;  // of the scene name, below the page margin
constexpr double kSubtitleBaseline = 42.0;
constexpr double kPanelGap = 24.0;          // between panels, and panels to legend
constexpr double kPanelPadding = 12.0;      // inside a panel's border, around the plan
constexpr double kPanelTitleHeight = 26.0;  // level name and elevation above the plan
constexpr double kPanelTitleBaseline = 14.0;
constexpr double kScaleBarHeight = 36.0;  // below the plan
constexpr double kMinPlanWidth = 280.0;   // so the title and scale bar always fit
constexpr double kScaleBarMetres = 5.0;   // with a tick every metre
constexpr double kScaleBarThickness = 6.0;
constexpr double kScaleBarGap = 14.0;    // between the plan and the scale bar
constexpr double kScaleTextGap = 12.0;   // between the bar and its numbers' baseline
constexpr double kScaleTextShift = 3.0;  // numbers start this far left of their tick
constexpr double kLegendWidth = 220.0;
constexpr double kLegendRow = 20.0;
constexpr double kLegendSwatch = 34.0;    // width of the sample drawn before each entry
constexpr double kLegendInset = 10.0;     // inside the legend's border
constexpr double kLegendTitleRows = 1.5;  // the heading takes this many rows
constexpr int kLegendFixedRows = 15;      // entries always shown (voxel maps add one)
constexpr double kSwatchTall = 12.0;      // heights of the legend's samples: areas,
constexpr double kSwatchThin = 6.0;       // walls,
constexpr double kSwatchLine = 5.0;       // the path's colour bar
constexpr double kSwatchInset = 4.0;      // the ramp arrow inside its sample
constexpr double kLegendDoorRadius = 14.0;

// Path
constexpr double kSampleStepS = 0.1;    // the path is sampled this often
constexpr double kPathChunkS = 1.0;     // one colour per second of travel
constexpr double kArrowSpacingM = 3.0;  // an arrowhead every this many metres
constexpr double kArrowLength = 12.0;
constexpr double kArrowHalfWidth = 5.5;
constexpr double kStartRadius = 6.5;
constexpr double kEndHalfSize = 5.0;
constexpr double kEndMinDistanceM = 0.5;  // closer to the start than this: no end marker

// Labels
constexpr double kLabelBaseline = 4.0;   // text baseline below the labelled point
constexpr double kLabelCharWidth = 7.5;  // rough width of a label character
constexpr double kLabelLineHeight = 14.0;
constexpr double kLabelMarkerShift = 18.0;  // a label over the start marker moves down this much

// Strokes and sizes
constexpr double kMinRailingWidth = 2.5;
constexpr double kBarsDotSize = 4.5;        // bars: a dotted line (a symbol: real posts are
constexpr double kBarsDotSpacing = 8.0;     // 0.12 m apart, too close to show one by one)
constexpr double kBarsRailWidth = 1.0;      // the top rail under the dots
constexpr double kRampArrowFraction = 0.7;  // of the ramp's length along its axis
constexpr double kRampArrowHead = 9.0;
constexpr double kRampLabelGapM = 0.35;     // the ramp's label sits this far before its entry
constexpr double kRoomHueStartDeg = 205.0;  // room colours: golden-angle hues from here
constexpr double kGoldenAngleDeg = 137.50776;
constexpr double kRoomSaturation = 0.62;
constexpr double kRoomLightness = 0.48;
constexpr double kHatchSpacing = 8.0;  // void hatching: line spacing and width
constexpr double kHatchWidth = 3.0;
constexpr double kEps = 1e-9;

// Colours
constexpr const char* kBackground = "#ffffff";
constexpr const char* kInk = "#222222";
constexpr const char* kMutedInk = "#666666";
constexpr const char* kPanelBorder = "#c8c8c8";
constexpr const char* kSlabFill = "#e9e9e9";
constexpr const char* kSlabStroke = "#9a9a9a";
constexpr const char* kVoidFill = "#7a7a7a";
constexpr const char* kVoidHatch = "#3c3c3c";
constexpr const char* kWallFill = "#2f2f2f";
constexpr const char* kDoorColour = "#d2561e";
constexpr const char* kWindowColour = "#2a86d6";
constexpr const char* kWindowSillFill = "#b9dcf7";
constexpr const char* kRailingColour = "#1d4fb8";
constexpr const char* kPersonColour = "#c2185b";
constexpr const char* kGlassColour = "#37b6d6";  // glass railings: lighter, the LiDAR sees through them
constexpr const char* kBoxFill = "#b9834f";
constexpr const char* kBoxStroke = "#6b4523";
constexpr const char* kRampLow = "#fbf0cf";
constexpr const char* kRampHigh = "#d6a53a";
constexpr const char* kRampArrow = "#7a5510";
constexpr const char* kVoxelFill = "#5d6d7e";
constexpr const char* kPathCasing = "#ffffff";
constexpr const char* kHalo = "#ffffff";
constexpr const char* kFont = "DejaVu Sans, Helvetica, Arial, sans-serif";

// The path's colour along time: start (dark blue) to end (red), through teal and yellow.
struct ColourStop {
  double at;
  double r, g, b;
};
constexpr std::array<ColourStop, 5> kPathRamp = {{{0.00, 0x2b, 0x3a, 0x9e},
                                                  {0.30, 0x14, 0x9c, 0x9a},
                                                  {0.55, 0x7f, 0xbf, 0x3f},
                                                  {0.78, 0xf2, 0xb1, 0x1c},
                                                  {1.00, 0xd7, 0x26, 0x2b}}};

// ---------------------------------------------------------------------------------------
// Text and numbers (svg_writer.hpp)

using svg::hex_colour;
using svg::num;
using svg::short_num;
using svg::xml_escape;

/// Colour of the path at fraction u in [0, 1] of the lap.
std::string path_colour(double u) {
  u = std::clamp(u, 0.0, 1.0);
  for (std::size_t i = 1; i < kPathRamp.size(); ++i) {
    const ColourStop& a = kPathRamp[i - 1];
    const ColourStop& b = kPathRamp[i];
    if (u <= b.at || i + 1 == kPathRamp.size()) {
      const double f = std::clamp((u - a.at) / (b.at - a.at), 0.0, 1.0);
      return hex_colour(a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b));
    }
  }
  return hex_colour(kPathRamp.back().r, kPathRamp.back().g, kPathRamp.back().b);
}

/// Distinct colour of the i-th room: hues a golden angle apart.
std::string room_colour(std::size_t i) {
  return svg::hsl_colour(kRoomHueStartDeg + kGoldenAngleDeg * static_cast<double>(i), kRoomSaturation,
                         kRoomLightness);
}

// ---------------------------------------------------------------------------------------
// Geometry helpers

using svg::Extent;

/// World metres to the pixels of one panel, y up.
struct Frame {
  double min_x = 0.0, max_y = 0.0;  // world corner drawn at (left, top)
  double left = 0.0, top = 0.0;     // pixel position of that corner
  double scale = kPxPerMetre;       // px per metre
  Vec2 px(const Vec2& p) const { return {left + (p.x() - min_x) * scale, top + (max_y - p.y()) * scale}; }
};

std::string xy(const Vec2& p) { return num(p.x()) + "," + num(p.y()); }

std::string points_attr(const Frame& f, const Polygon2& poly) {
  std::string s;
  for (const Vec2& p : poly) s += (s.empty() ? "" : " ") + xy(f.px(p));
  return s;
}

Vec2 rotate(const Vec2& v, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

Vec2 left_normal(const Vec2& d) { return {-d.y(), d.x()}; }

/// The rectangle [s0, s1] along the segment a -> b, `thickness` wide about it.
Polygon2 strip(const Vec2& a, const Vec2& b, double s0, double s1, double thickness) {
  const Vec2 d = (b - a).normalized();
  const Vec2 n = 0.5 * thickness * left_normal(d);
  return {a + s0 * d - n, a + s1 * d - n, a + s1 * d + n, a + s0 * d + n};
}

Polygon2 box_corners(const scene::Box& box) {
  const Vec2 c = 0.5 * (box.min.head<2>() + box.max.head<2>());
  const Vec2 h = 0.5 * (box.max.head<2>() - box.min.head<2>());
  const double yaw = box.yaw_deg * M_PI / 180.0;
  return {c + rotate({-h.x(), -h.y()}, yaw), c + rotate({h.x(), -h.y()}, yaw),
          c + rotate({h.x(), h.y()}, yaw), c + rotate({-h.x(), h.y()}, yaw)};
}

/// A point inside `poly` to put its name at: the area centroid, or for shapes that do not
/// contain it (an L, a U) the centroid of the polygon's largest triangle.
Vec2 label_point(const Polygon2& poly) {
  const double a = signed_area(poly);
  Vec2 c = Vec2::Zero();
  if (std::abs(a) > kEps) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2& p = poly[i];
      const Vec2& q = poly[(i + 1) % poly.size()];
      const double cross = p.x() * q.y() - q.x() * p.y();
      c += (p + q) * cross;
    }
    c /= 6.0 * a;
    if (contains(poly, c)) return c;
  }
  double best = -1.0;
  for (const Triangle2& t : triangulate_region({poly})) {
    const double ta = std::abs((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x());
    if (ta > best) best = ta, c = (t[0] + t[1] + t[2]) / 3.0;
  }
  if (best < 0.0 && !poly.empty()) {
    c = Vec2::Zero();
    for (const Vec2& p : poly) c += p;
    c /= static_cast<double>(poly.size());
  }
  return c;
}

/// Direction in which a ramp climbs (its axis points up from `from_level` to `to_level`;
/// if `from_level` is the higher one the surface falls along the axis instead).
Vec2 ramp_uphill(const Scene& scene, const scene::Ramp& ramp) {
  const double rise = scene.levels[ramp.to_level].elevation - scene.levels[ramp.from_level].elevation;
  return rise >= 0.0 ? ramp.axis : Vec2(-ramp.axis);
}

// ---------------------------------------------------------------------------------------
// The path

struct PathSample {
  Vec2 xy;
  double yaw;
  double t;   // s since the start
  double s;   // m travelled
  int level;  // panel it is drawn on
};

/// The level whose elevation is closest to the walkable surface under the sensor; among
/// levels at the same elevation, the first whose slab holds the point.
int level_at(const Scene& scene, double floor_z, const Vec2& p) {
  int best = 0;
  double best_gap = std::numeric_limits<double>::infinity();
  bool best_holds = false;
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    const double gap = std::abs(scene.levels[i].elevation - floor_z);
    const bool holds = contains(scene.levels[i].slab, p);
    if (gap < best_gap - kEps || (std::abs(gap - best_gap) <= kEps && holds && !best_holds)) {
      best = static_cast<int>(i), best_gap = gap, best_holds = holds;
    }
  }
  return best;
}

/// The first lap, sampled every kSampleStepS seconds (and at its end).
std::vector<PathSample> sample_first_lap(const Scene& scene, const scene::Trajectory& trajectory) {
  const std::vector<double>& laps = trajectory.lap_starts();
  const double end = laps.size() > 1 ? laps[1] : trajectory.duration();
  const auto steps = static_cast<long>(std::floor(end / kSampleStepS + kEps));
  std::vector<PathSample> out;
  for (long k = 0; k <= steps + 1; ++k) {
    const double t = std::min(static_cast<double>(k) * kSampleStepS, end);
    if (!out.empty() && t <= out.back().t) break;
    const Pose3 pose = trajectory.body_pose(t);
    const Vec2 p = pose.translation().head<2>();
    const double floor_z = pose.translation().z() - scene.sensor.mount_height;
    out.push_back({p, yaw_of(pose), t, trajectory.distance_at(t), level_at(scene, floor_z, p)});
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Voxel maps: the occupied cells seen from above (floor and ceiling cubes left out)

struct VoxelFootprint {
  int level = 0;
  double cell = 0.1;
  std::set<std::pair<long, long>> cells;  // ordered: deterministic output
};

VoxelFootprint voxel_footprint(const Scene& scene, const scene::VoxelMap& vm) {
  VoxelFootprint fp;
  fp.level = vm.level;
  fp.cell = vm.voxel_size;
  const PointCloud cloud = io::read_pcd(vm.file);
  const double c = std::cos(vm.yaw_deg * M_PI / 180.0), s = std::sin(vm.yaw_deg * M_PI / 180.0);
  const double ceiling = scene.levels[vm.level].ceiling;
  for (const Eigen::Vector3f& pf : cloud.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double z = p.z() + vm.offset.z();
    if (vm.label == scene::VoxelLabel::kAuto &&
        (std::abs(z) <= vm.voxel_size || std::abs(z - ceiling) <= vm.voxel_size)) {
      continue;
    }
    const double x = c * p.x() - s * p.y() + vm.offset.x(), y = s * p.x() + c * p.y() + vm.offset.y();
    fp.cells.emplace(std::lround(y / fp.cell), std::lround(x / fp.cell));  // row-major: rows merge into runs
  }
  return fp;
}

// ---------------------------------------------------------------------------------------
// Drawing

struct Label {
  Vec2 at;           // world
  std::string text;  // raw, escaped when written
  std::string cls;
};

struct Panel {
  int level = 0;
  Frame frame;
  double x = 0.0, y = 0.0, width = 0.0, height = 0.0;  // the panel's box on the page
};

class SceneDrawer {
 public:
  SceneDrawer(const Scene& scene, const scene::Trajectory& trajectory)
      : scene_(scene), path_(sample_first_lap(scene, trajectory)) {
    for (const scene::VoxelMap& vm : scene.voxel_maps) voxels_.push_back(voxel_footprint(scene, vm));
  }

  std::string draw() {
    layout();
    open_document();
    for (const Panel& p : panels_) draw_panel(p);
    draw_legend();
    out_ += "</svg>\n";
    return out_;
  }

 private:
  // --- page layout ----------------------------------------------------------------------

  Extent world_extent() const {
    Extent e;
    for (const scene::Level& l : scene_.levels) {
      e.add(l.slab);
      for (const Polygon2& v : l.voids) e.add(v);
    }
    for (const scene::Wall& w : scene_.walls) {
      for (const scene::WallPiece& p : scene::wall_pieces(w))
        e.add(strip(w.from, w.to, p.s0, p.s1, w.thickness));
    }
    for (const scene::Railing& r : scene_.railings) e.add(r.from), e.add(r.to);
    for (const scene::Box& b : scene_.boxes) e.add(box_corners(b));
    for (const scene::Ramp& r : scene_.ramps) e.add(r.polygon);
    for (const scene::Room& r : scene_.rooms) e.add(r.polygon);
    for (const scene::Person& p : scene_.people)
      for (const Vec2& q : p.path) e.add(q);
    for (const PathSample& s : path_) e.add(s.xy);
    for (const VoxelFootprint& v : voxels_) {
      for (const auto& [row, col] : v.cells) e.add(Vec2(col * v.cell, row * v.cell));
    }
    if (e.empty()) e.add(Vec2::Zero());
    e.min_x -= kWorldPaddingM, e.min_y -= kWorldPaddingM;
    e.max_x += kWorldPaddingM, e.max_y += kWorldPaddingM;
    return e;
  }

  /// Panels side by side, or stacked when that makes the page closer to square.
  void layout() {
    const Extent e = world_extent();
    scale_ = svg::drawing_scale(e, kPxPerMetre);
    const double plan_w = std::max((e.max_x - e.min_x) * scale_, kMinPlanWidth);
    const double plan_h = (e.max_y - e.min_y) * scale_;
    const double panel_w = plan_w + 2.0 * kPanelPadding;
    const double panel_h = kPanelTitleHeight + plan_h + kScaleBarHeight + 2.0 * kPanelPadding;
    const auto n = static_cast<double>(std::max<std::size_t>(scene_.levels.size(), 1));
    auto page = [&](bool stacked) {
      const double w = (stacked ? panel_w : n * panel_w + (n - 1.0) * kPanelGap) + kPanelGap + kLegendWidth;
      const double h =
          kTitleHeight + std::max(stacked ? n * panel_h + (n - 1.0) * kPanelGap : panel_h, legend_height());
      return std::make_pair(w + 2.0 * kPageMargin, h + 2.0 * kPageMargin);
    };
    const auto [wide_w, wide_h] = page(false);
    const auto [tall_w, tall_h] = page(true);
    const bool stacked =
        std::max(tall_w / tall_h, tall_h / tall_w) < std::max(wide_w / wide_h, wide_h / wide_w);
    std::tie(page_w_, page_h_) = stacked ? std::make_pair(tall_w, tall_h) : std::make_pair(wide_w, wide_h);

    // Lowest level first (left or top).
    std::vector<int> order(scene_.levels.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return scene_.levels[a].elevation < scene_.levels[b].elevation; });
    for (std::size_t k = 0; k < order.size(); ++k) {
      Panel p;
      p.level = order[k];
      p.width = panel_w;
      p.height = panel_h;
      p.x = kPageMargin + (stacked ? 0.0 : static_cast<double>(k) * (panel_w + kPanelGap));
      p.y = kPageMargin + kTitleHeight + (stacked ? static_cast<double>(k) * (panel_h + kPanelGap) : 0.0);
      p.frame.min_x = e.min_x;
      p.frame.max_y = e.max_y;
      p.frame.left = kPanelPadding;  // panel-local pixels (the panel group is translated)
      p.frame.top = kPanelPadding + kPanelTitleHeight;
      p.frame.scale = scale_;
      panels_.push_back(p);
    }
    legend_x_ = kPageMargin + (stacked ? panel_w : n * panel_w + (n - 1.0) * kPanelGap) + kPanelGap;
    plan_h_ = plan_h;
  }

  double legend_height() const { return (legend_rows() + kLegendTitleRows) * kLegendRow; }
  int legend_rows() const {
    return kLegendFixedRows + (voxels_.empty() ? 0 : 1) + (scene_.people.empty() ? 0 : 1);
  }

  void open_document() {
    out_ += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(page_w_) + "\" height=\"" +
            num(page_h_) + "\" viewBox=\"0 0 " + num(page_w_) + " " + num(page_h_) + "\">\n";
    out_ += "<title>" + xml_escape(scene_.name) + "</title>\n";
    write_defs();
    out_ += "<rect class=\"background\" x=\"0\" y=\"0\" width=\"" + num(page_w_) + "\" height=\"" +
            num(page_h_) + "\" fill=\"" + kBackground + "\"/>\n";
    out_ += text(kPageMargin, kPageMargin + kTitleBaseline, "scene-title", scene_.name);
    const double lap_s = path_.empty() ? 0.0 : path_.back().t;
    const double lap_m = path_.empty() ? 0.0 : path_.back().s;
    out_ += text(kPageMargin, kPageMargin + kSubtitleBaseline, "subtitle",
                 std::to_string(scene_.levels.size()) + (scene_.levels.size() == 1 ? " level" : " levels") +
                     "; first lap of the path: " + num(lap_m) + " m in " + num(lap_s) + " s; " +
                     short_num(scale_) + " px per metre, y up");
  }

  void write_defs() {
    out_ += "<style>\n";
    out_ += std::string("text { font-family: ") + kFont + "; fill: " + kInk + "; }\n";
    out_ += ".scene-title { font-size: 20px; font-weight: bold; }\n";
    out_ += std::string(".subtitle { font-size: 12px; fill: ") + kMutedInk + "; }\n";
    out_ += ".panel-title { font-size: 14px; font-weight: bold; }\n";
    out_ += std::string(".panel-border { fill: none; stroke: ") + kPanelBorder + "; stroke-width: 1; }\n";
    out_ += std::string(".slab { fill: ") + kSlabFill + "; stroke: " + kSlabStroke + "; stroke-width: 1; }\n";
    out_ += std::string(".void { fill: url(#void-hatch); stroke: ") + kVoidHatch + "; stroke-width: 1; }\n";
    out_ += ".room { stroke-width: 1.5; fill-opacity: 0.22; stroke-opacity: 0.85; }\n";
    out_ += std::string(".ramp { stroke: ") + kRampArrow + "; stroke-width: 1; }\n";
    out_ += std::string(".ramp-arrow { fill: none; stroke: ") + kRampArrow +
            "; stroke-width: 2; stroke-linecap: round; stroke-linejoin: round; }\n";
    out_ += std::string(".voxels { fill: ") + kVoxelFill + "; stroke: none; }\n";
    out_ += std::string(".box { fill: ") + kBoxFill + "; fill-opacity: 0.85; stroke: " + kBoxStroke +
            "; stroke-width: 1; }\n";
    out_ += std::string(".wall.full { fill: ") + kWallFill + "; stroke: " + kWallFill +
            "; stroke-width: 0.5; }\n";
    out_ += std::string(".wall.header { fill: none; stroke: ") + kWallFill +
            "; stroke-width: 0.8; stroke-dasharray: 3 2; }\n";
    out_ += std::string(".wall.sill { fill: ") + kWindowSillFill + "; stroke: " + kWindowColour +
            "; stroke-width: 0.8; }\n";
    out_ += std::string(".door { fill: none; stroke: ") + kDoorColour + "; stroke-width: 1.2; }\n";
    out_ += std::string(".door.leaf { fill: ") + kDoorColour + "; }\n";
    out_ += std::string(".window { stroke: ") + kWindowColour + "; stroke-width: 2; }\n";
    out_ += std::string(".railing.solid { stroke: ") + kRailingColour + "; stroke-linecap: butt; }\n";
    out_ += std::string(".railing.bars line { stroke: ") + kRailingColour + "; }\n";
    out_ += std::string(".railing.glass { stroke: ") + kGlassColour + "; stroke-linecap: butt; }\n";
    out_ += std::string(".person { fill: none; stroke: ") + kPersonColour +
            "; stroke-width: 1.5; stroke-dasharray: 4 3; }\n";
    out_ += std::string(".person-start { fill: ") + kPersonColour +
            "; fill-opacity: 0.5; stroke: " + kPersonColour + "; stroke-width: 1; }\n";
    out_ += std::string(".path-casing { fill: none; stroke: ") + kPathCasing +
            "; stroke-width: 6; stroke-linejoin: round; stroke-linecap: round; }\n";
    out_ += ".path { fill: none; stroke-width: 3; stroke-linejoin: round; stroke-linecap: round; }\n";
    out_ += std::string(".arrow { stroke: ") + kPathCasing + "; stroke-width: 0.8; }\n";
    out_ += std::string(".start { fill: ") + kPathCasing + "; stroke-width: 2.5; }\n";
    out_ += std::string(".end { fill: ") + kPathCasing + "; stroke-width: 2.5; }\n";
    out_ += std::string(".label { stroke: ") + kHalo +
            "; stroke-width: 3px; stroke-linejoin: round; paint-order: stroke; text-anchor: middle; }\n";
    out_ += ".room-name { font-size: 13px; font-weight: bold; }\n";
    out_ += ".void-name { font-size: 12px; font-style: italic; }\n";
    out_ += ".box-name { font-size: 9px; }\n";
    out_ += std::string(".ramp-name { font-size: 11px; fill: ") + kRampArrow + "; }\n";
    out_ += ".scale-text { font-size: 10px; }\n";
    out_ += ".legend-title { font-size: 13px; font-weight: bold; }\n";
    out_ += ".legend-text { font-size: 11px; }\n";
    out_ += "</style>\n<defs>\n";
    const std::string h = num(kHatchSpacing);
    out_ += "<pattern id=\"void-hatch\" patternUnits=\"userSpaceOnUse\" width=\"" + h + "\" height=\"" + h +
            "\" patternTransform=\"rotate(45)\"><rect width=\"" + h + "\" height=\"" + h + "\" fill=\"" +
            kVoidFill + "\"/><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"" + h + "\" stroke=\"" + kVoidHatch +
            "\" stroke-width=\"" + num(kHatchWidth) + "\"/></pattern>\n";
    out_ += "<linearGradient id=\"path-ramp\">";
    for (const ColourStop& c : kPathRamp) {
      out_ += "<stop offset=\"" + num(c.at) + "\" stop-color=\"" + hex_colour(c.r, c.g, c.b) + "\"/>";
    }
    out_ += "</linearGradient>\n";
    out_ += std::string("<linearGradient id=\"ramp-legend\"><stop offset=\"0.00\" stop-color=\"") + kRampLow +
            "\"/><stop offset=\"1.00\" stop-color=\"" + kRampHigh + "\"/></linearGradient>\n";
    out_ += "</defs>\n";
  }

  // --- one panel -------------------------------------------------------------------------

  void draw_panel(const Panel& p) {
    const scene::Level& level = scene_.levels[p.level];
    labels_.clear();
    out_ += "<g class=\"panel\" transform=\"translate(" + num(p.x) + "," + num(p.y) + ")\">\n";
    out_ += "<rect class=\"panel-border\" x=\"0\" y=\"0\" width=\"" + num(p.width) + "\" height=\"" +
            num(p.height) + "\"/>\n";
    out_ += text(kPanelPadding, kPanelPadding + kPanelTitleBaseline, "panel-title",
                 level.name + " \xE2\x80\x94 elevation " + num(level.elevation) + " m");
    const Frame& f = p.frame;
    draw_slab(f, p.level);
    draw_rooms(f, p.level);
    draw_ramps(f, p.level);
    draw_voxels(f, p.level);
    draw_boxes(f, p.level);
    draw_walls(f, p.level);
    draw_railings(f, p.level);
    draw_people(f, p.level);
    draw_path(f, p.level);
    draw_labels(f, p.level);
    draw_path_ends(f, p.level);  // last: never hidden under a room's name
    draw_scale_bar(kPanelPadding, kPanelPadding + kPanelTitleHeight + plan_h_ + kScaleBarGap);
    out_ += "</g>\n";
  }

  /// The slab, and its voids hatched; a void's label is left out where a ramp (drawn over
  /// it) already says what the hole is for.
  void draw_slab(const Frame& f, int level) {
    const scene::Level& l = scene_.levels[level];
    out_ += "<g class=\"layer-slab\">\n";
    out_ += "<polygon class=\"slab\" points=\"" + points_attr(f, l.slab) + "\"/>\n";
    for (const Polygon2& v : l.voids) {
      out_ += "<polygon class=\"void\" points=\"" + points_attr(f, v) + "\"/>\n";
      const Vec2 at = label_point(v);
      const bool under_ramp =
          std::any_of(scene_.ramps.begin(), scene_.ramps.end(), [&](const scene::Ramp& r) {
            return (r.from_level == level || r.to_level == level) && contains(r.polygon, at);
          });
      if (!under_ramp) labels_.push_back({at, "void", "void-name"});
    }
    out_ += "</g>\n";
  }

  void draw_rooms(const Frame& f, int level) {
    out_ += "<g class=\"layer-rooms\">\n";
    for (std::size_t i = 0; i < scene_.rooms.size(); ++i) {
      const scene::Room& r = scene_.rooms[i];
      if (r.level != level) continue;
      const std::string colour = room_colour(i);
      out_ += "<polygon class=\"room\" fill=\"" + colour + "\" stroke=\"" + colour + "\" points=\"" +
              points_attr(f, r.polygon) + "\"/>\n";
      labels_.push_back({label_point(r.polygon), r.name, "room-name"});
    }
    out_ += "</g>\n";
  }

  /// Ramps touching this level: a gradient rising along the ascent, an arrow pointing uphill
  /// and the level at the other end.
  void draw_ramps(const Frame& f, int level) {
    out_ += "<g class=\"layer-ramps\">\n";
    for (std::size_t i = 0; i < scene_.ramps.size(); ++i) {
      const scene::Ramp& r = scene_.ramps[i];
      if (r.from_level != level && r.to_level != level) continue;
      const Vec2 up = ramp_uphill(scene_, r);
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Vec2& q : r.polygon) lo = std::min(lo, q.dot(up)), hi = std::max(hi, q.dot(up));
      const Vec2 c = label_point(r.polygon);
      const Vec2 across = c - c.dot(up) * up;  // the centre line's offset from the origin
      const Vec2 low = across + lo * up, high = across + hi * up;
      const std::string id = "ramp-" + std::to_string(i) + "-on-" + std::to_string(level);
      out_ += "<linearGradient id=\"" + id + "\" gradientUnits=\"userSpaceOnUse\" x1=\"" +
              num(f.px(low).x()) + "\" y1=\"" + num(f.px(low).y()) + "\" x2=\"" + num(f.px(high).x()) +
              "\" y2=\"" + num(f.px(high).y()) + "\"><stop offset=\"0.00\" stop-color=\"" + kRampLow +
              "\"/><stop offset=\"1.00\" stop-color=\"" + kRampHigh + "\"/></linearGradient>\n";
      out_ += "<polygon class=\"ramp\" fill=\"url(#" + id + ")\" points=\"" + points_attr(f, r.polygon) +
              "\"/>\n";
      const double half = 0.5 * kRampArrowFraction * (hi - lo);
      out_ +=
          "<path class=\"ramp-arrow\" d=\"" + arrow_path(f.px(c - half * up), f.px(c + half * up)) + "\"/>\n";
      // The label stands where one steps onto the ramp from this level.
      const int other = r.from_level == level ? r.to_level : r.from_level;
      const bool here_low = scene_.levels[level].elevation <= scene_.levels[other].elevation;
      const Vec2 entry = here_low ? Vec2(low - kRampLabelGapM * up) : Vec2(high + kRampLabelGapM * up);
      labels_.push_back(
          {entry, "ramp to " + scene_.levels[other].name + (here_low ? " (up)" : " (down)"), "ramp-name"});
    }
    out_ += "</g>\n";
  }

  /// A line from a to b (pixels) with an open arrowhead at b.
  static std::string arrow_path(const Vec2& a, const Vec2& b) {
    const Vec2 d = (b - a).norm() > kEps ? Vec2((b - a).normalized()) : Vec2(1.0, 0.0);
    const Vec2 n = left_normal(d);
    const Vec2 h1 = b - kRampArrowHead * d + 0.6 * kRampArrowHead * n;
    const Vec2 h2 = b - kRampArrowHead * d - 0.6 * kRampArrowHead * n;
    return "M" + xy(a) + " L" + xy(b) + " M" + xy(h1) + " L" + xy(b) + " L" + xy(h2);
  }

  /// Occupied voxel columns as merged runs along x, one path per map.
  void draw_voxels(const Frame& f, int level) {
    out_ += "<g class=\"layer-voxels\">\n";
    for (const VoxelFootprint& v : voxels_) {
      if (v.level != level || v.cells.empty()) continue;
      std::string d;
      for (auto it = v.cells.begin(); it != v.cells.end();) {
        const long row = it->first, first = it->second;
        long last = first;
        for (++it; it != v.cells.end() && it->first == row && it->second == last + 1; ++it) ++last;
        const Vec2 a = f.px(Vec2((first - 0.5) * v.cell, (row + 0.5) * v.cell));
        const Vec2 b = f.px(Vec2((last + 0.5) * v.cell, (row - 0.5) * v.cell));
        d += "M" + xy(a) + "h" + num(b.x() - a.x()) + "v" + num(b.y() - a.y()) + "h" + num(a.x() - b.x()) +
             "z";
      }
      out_ += "<path class=\"voxels\" d=\"" + d + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  void draw_boxes(const Frame& f, int level) {
    out_ += "<g class=\"layer-boxes\">\n";
    for (const scene::Box& b : scene_.boxes) {
      if (b.level != level) continue;
      if (b.label == scene::kDoorLeafLabel) {  // a door's own leaf, drawn as the door symbol is
        out_ += "<polygon class=\"door leaf\" points=\"" + points_attr(f, box_corners(b)) + "\"/>\n";
        continue;
      }
      out_ += "<polygon class=\"box\" points=\"" + points_attr(f, box_corners(b)) + "\"/>\n";
      if (!b.label.empty())
        labels_.push_back({0.5 * (b.min.head<2>() + b.max.head<2>()), b.label, "box-name"});
    }
    out_ += "</g>\n";
  }

  /// Each person's walk (there and back) dashed, and a disc of their size where it starts.
  void draw_people(const Frame& f, int level) {
    out_ += "<g class=\"layer-people\">\n";
    for (const scene::Person& p : scene_.people) {
      if (p.level != level) continue;
      out_ += "<polyline class=\"person\" points=\"" + points_attr(f, p.path) + "\"/>\n";
      const Vec2 c = f.px(p.path.front());
      out_ += "<circle class=\"person-start\" cx=\"" + num(c.x()) + "\" cy=\"" + num(c.y()) + "\" r=\"" +
              num(p.radius * scale_) + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  /// Each solid piece of a wall as a rectangle: full height dark, above an opening as a
  /// dashed outline, below a window light blue; then a swing arc in each door and a blue
  /// line along each window.
  void draw_walls(const Frame& f, int level) {
    out_ += "<g class=\"layer-walls\">\n";
    for (const char* kind : {"header", "sill", "full"}) {
      for (const scene::Wall& w : scene_.walls) {
        if (w.level != level) continue;
        for (const scene::WallPiece& piece : scene::wall_pieces(w)) {
          if (piece_kind(w, piece) != kind) continue;
          out_ += std::string("<polygon class=\"wall ") + kind + "\" points=\"" +
                  points_attr(f, strip(w.from, w.to, piece.s0, piece.s1, w.thickness)) + "\"/>\n";
        }
      }
    }
    for (const scene::Wall& w : scene_.walls) {
      if (w.level != level) continue;
      for (const scene::Opening& o : w.openings) {
        if (o.sill > 0.0)
          out_ += window(f, w, o);
        else if (!has_leaf(w, o))
          out_ += door(f, w, o);  // a door whose leaf is in the scene shows that
      }
    }
    out_ += "</g>\n";
  }

  /// True when a door leaf (a box labelled as one) stands at the door's opening.
  bool has_leaf(const scene::Wall& w, const scene::Opening& o) const {
    const Vec2 c = w.from + o.at * (w.to - w.from).normalized();
    for (const scene::Box& b : scene_.boxes) {
      if (b.level != w.level || b.label != scene::kDoorLeafLabel) continue;
      for (const Vec2& p : box_corners(b)) {
        if ((p - c).norm() <= 0.5 * o.width + w.thickness) return true;  // its hinge is at a jamb
      }
    }
    return false;
  }

  static std::string piece_kind(const scene::Wall& w, const scene::WallPiece& p) {
    if (p.z0 > kEps) return "header";
    return p.z1 < w.height - kEps ? "sill" : "full";
  }

  /// The door leaf, open at right angles to the wall's left, and the arc its edge sweeps.
  static std::string door(const Frame& f, const scene::Wall& w, const scene::Opening& o) {
    const Vec2 d = (w.to - w.from).normalized();
    const Vec2 hinge = w.from + (o.at - 0.5 * o.width) * d;
    const Vec2 open = f.px(hinge + o.width * left_normal(d));
    const Vec2 jamb = f.px(w.from + (o.at + 0.5 * o.width) * d);
    const Vec2 h = f.px(hinge);
    const Vec2 a = open - h, b = jamb - h;
    const int sweep = a.x() * b.y() - a.y() * b.x() > 0.0 ? 1 : 0;  // turning direction on the page
    const std::string r = num(o.width * f.scale);
    return "<path class=\"door\" d=\"M" + xy(h) + " L" + xy(open) + " A" + r + "," + r + " 0 0," +
           std::to_string(sweep) + " " + xy(jamb) + "\"/>\n";
  }

  static std::string window(const Frame& f, const scene::Wall& w, const scene::Opening& o) {
    const Vec2 d = (w.to - w.from).normalized();
    const Vec2 a = f.px(w.from + (o.at - 0.5 * o.width) * d), b = f.px(w.from + (o.at + 0.5 * o.width) * d);
    return "<line class=\"window\" x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) +
           "\" y2=\"" + num(b.y()) + "\"/>\n";
  }

  /// Solid railings as a line of the panel's thickness (at least kMinRailingWidth); bars
  /// as a thin top rail with a dotted line over it.
  void draw_railings(const Frame& f, int level) {
    out_ += "<g class=\"layer-railings\">\n";
    for (const scene::Railing& r : scene_.railings) {
      if (r.level != level) continue;
      const Vec2 a = f.px(r.from), b = f.px(r.to);
      const std::string ends = "x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) +
                               "\" y2=\"" + num(b.y()) + "\"";
      if (r.style != scene::RailingStyle::kBars) {
        const double width = std::max(scene::RailingGeometry::kSolidThickness * scale_, kMinRailingWidth);
        const char* cls = r.style == scene::RailingStyle::kGlass ? "railing glass" : "railing solid";
        out_ +=
            std::string("<line class=\"") + cls + "\" " + ends + " stroke-width=\"" + num(width) + "\"/>\n";
      } else {
        out_ += "<g class=\"railing bars\">" + bars_lines(ends) + "</g>\n";
      }
    }
    out_ += "</g>\n";
  }

  /// The two lines of a bars railing between the given x1..y2 attributes.
  static std::string bars_lines(const std::string& ends) {
    return "<line " + ends + " stroke-width=\"" + num(kBarsRailWidth) + "\"/><line " + ends +
           " stroke-width=\"" + num(kBarsDotSize) + "\" stroke-linecap=\"round\" stroke-dasharray=\"0.01 " +
           num(kBarsDotSpacing) + "\"/>";
  }

  /// The part of the first lap on this level: a white casing, then one polyline per second
  /// coloured by time, and arrowheads every kArrowSpacingM metres.
  void draw_path(const Frame& f, int level) {
    if (path_.empty()) return;
    out_ += "<g class=\"layer-path\">\n";
    const double duration = std::max(path_.back().t, kEps);
    // Runs of consecutive samples on this level (a path that changes level leaves one run
    // and starts another on the other panel).
    std::vector<std::pair<std::size_t, std::size_t>> runs;  // [first, last]
    for (std::size_t i = 0; i < path_.size(); ++i) {
      if (path_[i].level != level) continue;
      if (!runs.empty() && runs.back().second + 1 == i) {
        runs.back().second = i;
      } else {
        runs.emplace_back(i, i);
      }
    }
    for (const auto& [first, last] : runs) {
      out_ += "<polyline class=\"path-casing\" points=\"" + path_points(f, first, last) + "\"/>\n";
    }
    auto chunk_of = [&](std::size_t i) {
      return static_cast<long>(std::floor(path_[i].t / kPathChunkS + kEps));
    };
    for (const auto& [first, last] : runs) {
      if (first == last) {
        out_ += "<polyline class=\"path\" stroke=\"" + path_colour(path_[first].t / duration) +
                "\" points=\"" + path_points(f, first, last) + "\"/>\n";
        continue;
      }
      // One polyline per chunk, ending on the next chunk's first sample so they join.
      for (std::size_t i = first; i < last;) {
        std::size_t j = i + 1;
        while (j < last && chunk_of(j) == chunk_of(i)) ++j;
        const double mid = 0.5 * (path_[i].t + path_[j].t);
        out_ += "<polyline class=\"path\" stroke=\"" + path_colour(mid / duration) + "\" points=\"" +
                path_points(f, i, j) + "\"/>\n";
        i = j;
      }
    }
    draw_arrows(f, level, duration);
    out_ += "</g>\n";
  }

  /// The start (circle) and, when the lap does not return to it, the end (square).
  void draw_path_ends(const Frame& f, int level) {
    if (path_.empty()) return;
    out_ += "<g class=\"layer-path-ends\">\n";
    const PathSample& s0 = path_.front();
    const PathSample& s1 = path_.back();
    if (s1.level == level && (s1.xy - s0.xy).norm() >= kEndMinDistanceM) {
      const Vec2 c = f.px(s1.xy);
      out_ += "<rect class=\"end\" stroke=\"" + path_colour(1.0) + "\" x=\"" + num(c.x() - kEndHalfSize) +
              "\" y=\"" + num(c.y() - kEndHalfSize) + "\" width=\"" + num(2.0 * kEndHalfSize) +
              "\" height=\"" + num(2.0 * kEndHalfSize) + "\"/>\n";
    }
    if (s0.level == level) {
      const Vec2 c = f.px(s0.xy);
      out_ += "<circle class=\"start\" stroke=\"" + path_colour(0.0) + "\" cx=\"" + num(c.x()) + "\" cy=\"" +
              num(c.y()) + "\" r=\"" + num(kStartRadius) + "\"/>\n";
    }
    out_ += "</g>\n";
  }

  std::string path_points(const Frame& f, std::size_t first, std::size_t last) const {
    std::string s;
    for (std::size_t i = first; i <= last; ++i) {
      if (i > first && (path_[i].xy - path_[i - 1].xy).norm() < kEps) continue;  // turning in place
      s += (s.empty() ? "" : " ") + xy(f.px(path_[i].xy));
    }
    if (s.find(' ') == std::string::npos) s += " " + s;  // a single point still draws a dot
    return s;
  }

  /// A filled arrowhead centred on `c` (pixels) pointing along the unit `d`.
  static std::string arrowhead_points(const Vec2& c, const Vec2& d) {
    const Vec2 n = left_normal(d);
    const Vec2 tip = c + 0.5 * kArrowLength * d, back = c - 0.5 * kArrowLength * d;
    return xy(tip) + " " + xy(back + kArrowHalfWidth * n) + " " + xy(back - kArrowHalfWidth * n);
  }

  /// Arrowheads at kArrowSpacingM / 2, 3/2 kArrowSpacingM, ... metres from the start.
  void draw_arrows(const Frame& f, int level, double duration) {
    std::size_t i = 0;
    for (double at = 0.5 * kArrowSpacingM; at < path_.back().s; at += kArrowSpacingM) {
      while (i + 1 < path_.size() && path_[i].s < at) ++i;
      const PathSample& p = path_[i];
      if (p.level != level) continue;
      const Vec2 d(std::cos(p.yaw), -std::sin(p.yaw));  // page y points down
      out_ += "<polygon class=\"arrow\" fill=\"" + path_colour(p.t / duration) + "\" points=\"" +
              arrowhead_points(f.px(p.xy), d) + "\"/>\n";
    }
  }

  /// Names centred on their points; one that would cover the start marker moves below it.
  void draw_labels(const Frame& f, int level) {
    out_ += "<g class=\"layer-labels\">\n";
    const bool start_here = !path_.empty() && path_.front().level == level;
    const Vec2 start = start_here ? f.px(path_.front().xy) : Vec2::Zero();
    for (const Label& l : labels_) {
      Vec2 p = f.px(l.at);
      const double half_width = 0.5 * kLabelCharWidth * static_cast<double>(l.text.size()) + kStartRadius;
      if (start_here && std::abs(p.x() - start.x()) < half_width &&
          std::abs(p.y() - start.y()) < 0.5 * kLabelLineHeight + kStartRadius) {
        p.y() = start.y() + kLabelMarkerShift;
      }
      out_ += "<text class=\"label " + l.cls + "\" x=\"" + num(p.x()) + "\" y=\"" +
              num(p.y() + kLabelBaseline) + "\">" + xml_escape(l.text) + "</text>\n";
    }
    out_ += "</g>\n";
  }

  /// kScaleBarMetres long, alternating dark and light metres, labelled 0, 1 and the length.
  void draw_scale_bar(double x, double y) {
    svg::ScaleBarStyle style;
    style.px_per_metre = scale_;
    style.metres = static_cast<int>(kScaleBarMetres);
    style.thickness = kScaleBarThickness;
    style.text_gap = kScaleTextGap;
    style.text_shift = kScaleTextShift;
    style.ink = kInk;
    style.paper = kBackground;
    out_ += svg::scale_bar(x, y, style);
  }

  // --- legend ----------------------------------------------------------------------------

  /// One row per kind of mark: a sample drawn with the same classes as in the panels, and
  /// what it means.
  void draw_legend() {
    const double x = legend_x_;
    double y = kPageMargin + kTitleHeight;
    out_ += "<g class=\"legend\">\n";
    out_ += "<rect class=\"panel-border\" x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" +
            num(kLegendWidth) + "\" height=\"" + num(legend_height()) + "\"/>\n";
    out_ += text(x + kLegendInset, y + kLegendRow - kLabelBaseline, "legend-title", "Legend");
    y += kLegendTitleRows * kLegendRow;
    const double sx = x + kLegendInset, sw = kLegendSwatch;
    auto row = [&](const std::string& swatch, const std::string& what) {
      out_ += swatch;
      out_ += text(sx + sw + kLegendInset, y + kLabelBaseline, "legend-text", what);
      y += kLegendRow;
    };
    auto rect = [&](const std::string& attrs, double h) {
      return "<rect " + attrs + " x=\"" + num(sx) + "\" y=\"" + num(y - 0.5 * h) + "\" width=\"" + num(sw) +
             "\" height=\"" + num(h) + "\"/>\n";
    };
    auto ends = [&]() {
      return "x1=\"" + num(sx) + "\" y1=\"" + num(y) + "\" x2=\"" + num(sx + sw) + "\" y2=\"" + num(y) + "\"";
    };
    const Vec2 mid(sx + 0.5 * sw, 0.0);
    row(rect("class=\"slab\"", kSwatchTall), "floor slab");
    row(rect("class=\"void\"", kSwatchTall), "void (open below)");
    row(rect("class=\"wall full\"", kSwatchThin), "wall");
    row(rect("class=\"wall header\"", kSwatchThin), "wall above an opening");
    {
      const double r = kLegendDoorRadius;
      const Vec2 hinge(sx + kLegendInset, y + 0.5 * kSwatchTall), open = hinge - Vec2(0.0, r),
                                                                  jamb = hinge + Vec2(r, 0.0);
      row("<path class=\"door\" d=\"M" + xy(hinge) + " L" + xy(open) + " A" + num(r) + "," + num(r) +
              " 0 0,1 " + xy(jamb) + "\"/>\n",
          "door (leaf and swing)");
    }
    row(rect("class=\"wall sill\"", kSwatchThin) + "<line class=\"window\" " + ends() + "/>\n", "window");
    row("<line class=\"railing solid\" " + ends() + " stroke-width=\"" + num(kMinRailingWidth) + "\"/>\n",
        "railing, solid");
    row("<g class=\"railing bars\">" + bars_lines(ends()) + "</g>\n", "railing, bars");
    row("<line class=\"railing glass\" " + ends() + " stroke-width=\"" + num(kMinRailingWidth) + "\"/>\n",
        "railing, glass");
    row(rect("class=\"box\"", kSwatchTall), "box (with its label)");
    row(rect("class=\"ramp\" fill=\"url(#ramp-legend)\"", kSwatchTall) + "<path class=\"ramp-arrow\" d=\"" +
            arrow_path({sx + kSwatchInset, y}, {sx + sw - kSwatchInset, y}) + "\"/>\n",
        "ramp, arrow uphill");
    if (!voxels_.empty()) row(rect("class=\"voxels\"", kSwatchTall), "voxel map (walls, objects)");
    if (!scene_.people.empty()) row("<line class=\"person\" " + ends() + "/>\n", "a person's walk");
    row(rect("class=\"room\" fill=\"" + room_colour(0) + "\" stroke=\"" + room_colour(0) + "\"", kSwatchTall),
        "ground-truth room");
    row(rect("fill=\"url(#path-ramp)\"", kSwatchLine), "first lap, start to end");
    row("<polygon class=\"arrow\" fill=\"" + path_colour(0.5) + "\" points=\"" +
            arrowhead_points(Vec2(mid.x(), y), Vec2(1.0, 0.0)) + "\"/>\n",
        "direction, every " + short_num(kArrowSpacingM) + " m");
    row("<circle class=\"start\" stroke=\"" + path_colour(0.0) + "\" cx=\"" + num(mid.x()) + "\" cy=\"" +
            num(y) + "\" r=\"" + num(kStartRadius) + "\"/>\n",
        "start (square: end)");
    out_ += "</g>\n";
  }

  static std::string text(double x, double y, const std::string& cls, const std::string& what) {
    return svg::text(x, y, cls, what);
  }

  const Scene& scene_;
  std::vector<PathSample> path_;
  std::vector<VoxelFootprint> voxels_;
  std::vector<Panel> panels_;
  std::vector<Label> labels_;
  double page_w_ = 0.0, page_h_ = 0.0, legend_x_ = 0.0, plan_h_ = 0.0;
  double scale_ = kPxPerMetre;  // px per metre of every panel (layout)
  std::string out_;
};

}  // namespace

std::string scene_svg(const scene::Scene& scene, const scene::Trajectory& trajectory) {
  return SceneDrawer(scene, trajectory).draw();
}

}  // namespace tsgraphs::report
