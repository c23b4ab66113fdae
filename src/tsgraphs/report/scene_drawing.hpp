#pragma once
/// Internal to the report module: the scene picture's (scene_svg.hpp) layout and palette, the
/// helpers its parts share (world-to-panel frame, geometry, the sampled first lap, voxel maps
/// seen from above) and its drawer, whose parts are drawn in scene_svg.cpp (the page),
/// scene_svg_building.cpp (what stands on a level) and scene_svg_path.cpp (path and names).
#include <array>
#include <cstddef>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/report/svg_writer.hpp"
#include "tsgraphs/scene/scene.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/trajectory.hpp"

namespace tsgraphs::report::scene_drawing {

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
std::string path_colour(double u);

/// Distinct colour of the i-th room: hues a golden angle apart.
std::string room_colour(std::size_t i);

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

std::string xy(const Vec2& p);

std::string points_attr(const Frame& f, const Polygon2& poly);

Vec2 rotate(const Vec2& v, double yaw);

Vec2 left_normal(const Vec2& d);

/// The rectangle [s0, s1] along the segment a -> b, `thickness` wide about it.
Polygon2 strip(const Vec2& a, const Vec2& b, double s0, double s1, double thickness);

Polygon2 box_corners(const scene::Box& box);

/// A point inside `poly` to put its name at: the area centroid, or for shapes that do not
/// contain it (an L, a U) the centroid of the polygon's largest triangle.
Vec2 label_point(const Polygon2& poly);

/// Direction in which a ramp climbs (its axis points up from `from_level` to `to_level`;
/// if `from_level` is the higher one the surface falls along the axis instead).
Vec2 ramp_uphill(const Scene& scene, const scene::Ramp& ramp);

// ---------------------------------------------------------------------------------------
// The path

struct PathSample {
  Vec2 xy;
  double yaw;
  double t;   // s since the start
  double s;   // m travelled
  int level;  // panel it is drawn on
};

/// The first lap, sampled every kSampleStepS seconds (and at its end).
std::vector<PathSample> sample_first_lap(const Scene& scene, const scene::Trajectory& trajectory);

// ---------------------------------------------------------------------------------------
// Voxel maps: the occupied cells seen from above (floor and ceiling cubes left out)

struct VoxelFootprint {
  int level = 0;
  double cell = 0.1;
  std::set<std::pair<long, long>> cells;  // ordered: deterministic output
};

VoxelFootprint voxel_footprint(const Scene& scene, const scene::VoxelMap& vm);

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

/// The picture of a scene (scene_svg): its page (layout, style, legend) in scene_svg.cpp, what
/// stands on each level in scene_svg_building.cpp, the path and the names in scene_svg_path.cpp.
class SceneDrawer {
 public:
  SceneDrawer(const Scene& scene, const scene::Trajectory& trajectory);

  std::string draw();

 private:
  // --- page layout (scene_svg.cpp) -----------------------------------------------------------

  Extent world_extent() const;

  /// Panels side by side, or stacked when that makes the page closer to square.
  void layout();

  double legend_height() const;

  int legend_rows() const;

  void open_document();

  void write_defs();

  // --- one panel ---------------------------------------------------------------------------

  void draw_panel(const Panel& p);

  /// kScaleBarMetres long, alternating dark and light metres, labelled 0, 1 and the length.
  void draw_scale_bar(double x, double y);

  // --- what stands on a level (scene_svg_building.cpp) ------------------------------------

  /// The slab, and its voids hatched; a void's label is left out where a ramp (drawn over
  /// it) already says what the hole is for.
  void draw_slab(const Frame& f, int level);

  void draw_rooms(const Frame& f, int level);

  /// Ramps touching this level: a gradient rising along the ascent, an arrow pointing uphill
  /// and the level at the other end.
  void draw_ramps(const Frame& f, int level);

  /// A line from a to b (pixels) with an open arrowhead at b.
  static std::string arrow_path(const Vec2& a, const Vec2& b);

  /// Occupied voxel columns as merged runs along x, one path per map.
  void draw_voxels(const Frame& f, int level);

  void draw_boxes(const Frame& f, int level);

  /// Each person's walk (there and back) dashed, and a disc of their size where it starts.
  void draw_people(const Frame& f, int level);

  /// Each solid piece of a wall as a rectangle: full height dark, above an opening as a
  /// dashed outline, below a window light blue; then a swing arc in each door and a blue
  /// line along each window.
  void draw_walls(const Frame& f, int level);

  /// True when a door leaf (a box labelled as one) stands at the door's opening.
  bool has_leaf(const scene::Wall& w, const scene::Opening& o) const;

  static std::string piece_kind(const scene::Wall& w, const scene::WallPiece& p);

  /// The door leaf, open at right angles to the wall's left, and the arc its edge sweeps.
  static std::string door(const Frame& f, const scene::Wall& w, const scene::Opening& o);

  static std::string window(const Frame& f, const scene::Wall& w, const scene::Opening& o);

  /// Solid railings as a line of the panel's thickness (at least kMinRailingWidth); bars
  /// as a thin top rail with a dotted line over it.
  void draw_railings(const Frame& f, int level);

  /// The two lines of a bars railing between the given x1..y2 attributes.
  static std::string bars_lines(const std::string& ends);

  // --- the path and the names (scene_svg_path.cpp) ---------------------------------------

  /// The part of the first lap on this level: a white casing, then one polyline per second
  /// coloured by time, and arrowheads every kArrowSpacingM metres.
  void draw_path(const Frame& f, int level);

  /// The start (circle) and, when the lap does not return to it, the end (square).
  void draw_path_ends(const Frame& f, int level);

  std::string path_points(const Frame& f, std::size_t first, std::size_t last) const;

  /// A filled arrowhead centred on `c` (pixels) pointing along the unit `d`.
  static std::string arrowhead_points(const Vec2& c, const Vec2& d);

  /// Arrowheads at kArrowSpacingM / 2, 3/2 kArrowSpacingM, ... metres from the start.
  void draw_arrows(const Frame& f, int level, double duration);

  /// Names centred on their points; one that would cover the start marker moves below it.
  void draw_labels(const Frame& f, int level);

  // --- legend ------------------------------------------------------------------------------

  /// One row per kind of mark: a sample drawn with the same classes as in the panels, and
  /// what it means.
  void draw_legend();

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

}  // namespace tsgraphs::report::scene_drawing
