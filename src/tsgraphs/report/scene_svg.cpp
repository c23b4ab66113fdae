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
#include <cstddef>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tsgraphs/report/scene_drawing.hpp"

namespace tsgraphs::report {
namespace scene_drawing {

SceneDrawer::SceneDrawer(const Scene& scene, const scene::Trajectory& trajectory)
    : scene_(scene), path_(sample_first_lap(scene, trajectory)) {
  for (const scene::VoxelMap& vm : scene.voxel_maps) voxels_.push_back(voxel_footprint(scene, vm));
}

std::string SceneDrawer::draw() {
  layout();
  open_document();
  for (const Panel& p : panels_) draw_panel(p);
  draw_legend();
  out_ += "</svg>\n";
  return out_;
}

Extent SceneDrawer::world_extent() const {
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

void SceneDrawer::layout() {
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

double SceneDrawer::legend_height() const { return (legend_rows() + kLegendTitleRows) * kLegendRow; }

int SceneDrawer::legend_rows() const {
  return kLegendFixedRows + (voxels_.empty() ? 0 : 1) + (scene_.people.empty() ? 0 : 1);
}

void SceneDrawer::open_document() {
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

void SceneDrawer::write_defs() {
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
  out_ +=
      std::string(".wall.full { fill: ") + kWallFill + "; stroke: " + kWallFill + "; stroke-width: 0.5; }\n";
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

void SceneDrawer::draw_panel(const Panel& p) {
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

void SceneDrawer::draw_scale_bar(double x, double y) {
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

void SceneDrawer::draw_legend() {
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

}  // namespace scene_drawing

std::string scene_svg(const scene::Scene& scene, const scene::Trajectory& trajectory) {
  return scene_drawing::SceneDrawer(scene, trajectory).draw();
}

}  // namespace tsgraphs::report
