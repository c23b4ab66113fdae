#include "tsgraphs/rooms/bend_cuts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "tsgraphs/core/raster_regions.hpp"
#include "tsgraphs/rooms/wall_lines.hpp"

namespace tsgraphs::rooms::segmentation_steps {

RegionInBox region_in_box(const GridFrame& f, const std::vector<int>& lab, int k, double min_cells) {
  RegionInBox out;
  int c0 = f.cols, r0 = f.rows, c1 = -1, r1 = -1;
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c) {
      if (lab[f.index(c, r)] != k) continue;
      ++out.cells;
      c0 = std::min(c0, c);
      c1 = std::max(c1, c);
      r0 = std::min(r0, r);
      r1 = std::max(r1, r);
    }
  }
  if (c1 < 0) return out;
  out.c0 = c0;
  out.r0 = r0;
  out.box.resolution = 1.0;
  out.box.cols = c1 - c0 + 3;
  out.box.rows = r1 - r0 + 3;
  out.in.assign(out.box.size(), 0);
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c)
      if (lab[f.index(c, r)] == k) out.in[out.box.index(c - c0 + 1, r - r0 + 1)] = 1;
  std::vector<std::uint8_t> other(out.box.size(), 0);
  for (std::size_t i = 0; i < out.in.size(); ++i) other[i] = out.in[i] ? 0 : 1;
  out.parts = label_regions(other, out.box.cols, out.box.rows, false, &out.sizes);
  out.outside = out.parts[0];  // the margin's corner is outside the region
  std::vector<std::uint8_t> filled = out.in;
  for (std::size_t i = 0; i < out.parts.size(); ++i) {
    const int p = out.parts[i];
    if (p >= 0 && p != out.outside && static_cast<double>(out.sizes[static_cast<std::size_t>(p)]) < min_cells)
      filled[i] = 1;
  }
  const std::vector<float> clearance = distance_transform(out.box, filled);
  out.width = 2.0 * *std::max_element(clearance.begin(), clearance.end());
  return out;
}

bool corridor_like(const RegionInBox& region, double corridor_aspect, double max_width) {
  return region.width <= max_width &&
         static_cast<double>(region.cells) >= corridor_aspect * region.width * region.width;
}

namespace {

/// An inner corner of a region's outline (box coordinates).
struct Corner {
  Vec2 at, d_in, d_out;
  double len_in = 0.0, len_out = 0.0;  ///< the arriving and leaving edges' lengths (cells)
  bool drawn_back = false;             ///< the leaving edge drawn back, not the arriving one drawn on
};

/// The region's outline, counter-clockwise, and its counted holes' outlines, each clockwise
/// round the hole: the region lies left of every edge, and an inner corner is a right turn.
std::vector<Polygon2> region_loops(const RegionInBox& region, double min_cells) {
  const GridFrame& box = region.box;
  const auto counted = [&](int p) {
    return p == region.outside || static_cast<double>(region.sizes[static_cast<std::size_t>(p)]) >= min_cells;
  };
  std::vector<Polygon2> loops;
  {
    std::vector<int> only(box.size(), -1);
    for (std::size_t i = 0; i < region.in.size(); ++i)
      if (region.in[i]) only[i] = 0;
    loops.push_back(trace_outlines(only, box.cols, box.rows, 1, false).front());
  }
  for (std::size_t p = 0; p < region.sizes.size(); ++p) {
    if (static_cast<int>(p) == region.outside || !counted(static_cast<int>(p))) continue;
    std::vector<int> only(box.size(), -1);
    for (std::size_t i = 0; i < region.parts.size(); ++i)
      if (region.parts[i] == static_cast<int>(p)) only[i] = 0;
    Polygon2 hole = trace_outlines(only, box.cols, box.rows, 1, false).front();
    std::reverse(hole.begin(), hole.end());
    loops.push_back(hole);
  }
  return loops;
}

/// A simplified edge's direction is known to within atan(2 tolerance / length); within that of a
/// mapped wall's, it runs along the wall: the raggedness is the raster's (a railing's end, a
/// ramp's top), the sides are the building's, and a cut drawn on from it follows them.
Vec2 along_walls(const Vec2& d, double length, double tolerance_cells,
                 const std::vector<Vec2>& wall_directions) {
  double best = std::atan2(2.0 * tolerance_cells, length);
  Vec2 out = d;
  for (const Vec2& w : wall_directions) {
    const double c = d.dot(w);
    const double angle = std::acos(std::min(1.0, std::abs(c)));
    if (angle < best) {
      best = angle;
      out = c >= 0.0 ? w : Vec2(-w);
    }
  }
  return out;
}

/// The inner corners of the loops turning min_turn or more, each with its edges' directions as
/// along_walls gives them and the lengths of the straight runs they belong to (a side whose end
/// the raster made ragged is as long as the whole side). The loops are simplified in place.
std::vector<Corner> inner_corners(std::vector<Polygon2>& loops, double tolerance_cells, double min_turn,
                                  const std::vector<Vec2>& wall_directions) {
  std::vector<Corner> corners;
  for (Polygon2& loop : loops) {
    loop = simplify_outlines({loop}, tolerance_cells).front();
    const std::size_t m = loop.size();
    if (m < 3) continue;
    // Edge i runs from vertex i to i + 1.
    std::vector<Vec2> dir(m);
    std::vector<double> len(m);
    for (std::size_t i = 0; i < m; ++i) {
      len[i] = (loop[(i + 1) % m] - loop[i]).norm();
      dir[i] =
          along_walls((loop[(i + 1) % m] - loop[i]).normalized(), len[i], tolerance_cells, wall_directions);
    }
    const auto run_length = [&](std::size_t e, bool back) {
      double total = len[e];
      for (std::size_t k = 1; k < m; ++k) {
        const std::size_t o = back ? (e + m - k) % m : (e + k) % m;
        if ((dir[o] - dir[e]).norm() > 1e-9) break;
        total += len[o];
      }
      return total;
    };
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t e_in = (i + m - 1) % m, e_out = i;
      const Vec2 raw_in = (loop[i] - loop[e_in]).normalized(),
                 raw_out = (loop[(i + 1) % m] - loop[i]).normalized();
      const double turn = raw_in.x() * raw_out.y() - raw_in.y() * raw_out.x();
      if (turn > -std::sin(min_turn)) continue;  // not an inner corner turning min_turn or more
      if (dir[e_in].x() * dir[e_out].y() - dir[e_in].y() * dir[e_out].x() > -std::sin(min_turn))
        continue;  // nor along the walls
      corners.push_back(
          {loop[i], dir[e_in], dir[e_out], run_length(e_in, true), run_length(e_out, false), false});
    }
  }
  return corners;
}

/// Walks from a region's corners across it: region k of `lab`, its box at (c0, r0).
struct CornerWalk {
  const GridFrame& f;
  const std::vector<int>& lab;
  int k, c0, r0;
  double tolerance_cells, max_walk;

  /// A walk on from a corner along `d`, the edge it draws on having the region on its `left`:
  /// the region's cells it crosses, and where it left the region (none if it did not within
  /// max_walk). Its cells are taken half a cell to the side that was outside along the edge, so
  /// that a walk drawing a wall on past a mouth leaves the region where the wall resumes,
  /// whichever way the outline runs.
  std::optional<Vec2> operator()(const Corner& from, const Vec2& d, bool left,
                                 std::vector<std::size_t>* run) const {
    const Vec2 outside = left ? Vec2(d.y(), -d.x()) : Vec2(-d.y(), d.x());
    const Vec2 start = Vec2(c0 - 1, r0 - 1) + from.at + 0.5 * outside;
    run->clear();
    for (double t = kLineStep; t <= max_walk; t += kLineStep) {
      const Vec2 q = start + t * d;
      const int c = static_cast<int>(std::floor(q.x())), r = static_cast<int>(std::floor(q.y()));
      if (!f.inside(c, r) || lab[f.index(c, r)] != k) {
        if (!run->empty()) return q - 0.5 * outside - Vec2(c0 - 1, r0 - 1);
        if (t > tolerance_cells + 1.0) return std::nullopt;  // never entered the region
        continue;
      }
      run->push_back(f.index(c, r));
    }
    return std::nullopt;
  }
};

/// Which edge each corner's cut follows: the edge arriving at it drawn on (d_in), or the edge
/// leaving it drawn back (-d_out). A cut that ends at another inner corner is the mouth between
/// two (a side corridor's, a bridge's): both take it, so a T-junction keeps its through corridor
/// whole. Judged before any cut, as its partner's cut would hide the mouth.
void choose_cut_edges(std::vector<Corner>& corners, const CornerWalk& walk, double corridor_aspect) {
  const auto at_other_corner = [&](const Corner& from, const Vec2& q) {
    for (const Corner& o : corners)
      if (&o != &from && (o.at - q).norm() <= walk.tolerance_cells + 1.0) return true;
    return false;
  };
  std::vector<std::size_t> run;
  for (Corner& corner : corners) {
    const std::optional<Vec2> end_in = walk(corner, corner.d_in, true, &run);
    const std::optional<Vec2> end_out = walk(corner, -corner.d_out, false, &run);
    const bool mouth_in = end_in && at_other_corner(corner, *end_in);
    const bool mouth_out = end_out && at_other_corner(corner, *end_out);
    // Else the edge that crosses the region within its width, if only one does (a step in a
    // corridor's width: its one edge runs on along the wider part). Else the longer edge if
    // it is corridor_aspect times the other's length: that edge is a corridor's side and the
    // other the end of a bay open to it (a landing, a balcony beside a gallery), and the side
    // runs on across the bay's opening. Else d_in, not the longer edge: which of two legs
    // is longer changes as the map grows, the outline's turning sense does not, so a
    // corner stays with the same leg.
    if (mouth_in != mouth_out)
      corner.drawn_back = mouth_out;
    else if (end_in.has_value() != end_out.has_value())
      corner.drawn_back = end_out.has_value();
    else if (end_in)
      corner.drawn_back = corner.len_out >= corridor_aspect * corner.len_in;
  }
}

}  // namespace

/// Cuts each corridor-like region (its area at least `corridor_aspect` times the square of its
/// widest width, twice its largest clearance, holes of fewer than `min_cells` not counted: a
/// pillar stands inside a space; that width at most `max_width_cells`) into its straight legs:
/// at every corner where its outline turns inwards (an inner corner of a bend, a corner of what
/// it runs round: an atrium's void, a walled-off room) the outline's edge arriving there (counter-clockwise
/// round the region, clockwise round a hole) is drawn on across the region until it leaves it, if it does
/// within the corridor's width. Each corner square thus goes to one leg, the same way round every bend. The
/// edge leaving the corner is drawn back instead where only it ends at another inner corner (the mouth of a
/// side corridor: the corridor it leaves stays whole), where only it crosses the region (a step in the
/// width), or where it is corridor_aspect times longer than the arriving edge (a corridor's side running on
/// past a bay). An edge within its simplification's angular error of a wall's direction (`wall_directions`,
/// unit) takes it, and is as long as the straight run of edges it then belongs to. Cut cells lose their
/// label; returns whether any was cut.
bool cut_bends(const GridFrame& f, int n, double corridor_aspect, double max_width_cells, double min_cells,
               double tolerance_cells, double min_turn, const std::vector<Vec2>& wall_directions,
               std::vector<int>* label) {
  std::vector<int>& lab = *label;
  bool cut = false;
  for (int k = 0; k < n; ++k) {
    const RegionInBox region = region_in_box(f, lab, k, min_cells);
    if (region.cells == 0 || !corridor_like(region, corridor_aspect, max_width_cells)) continue;
    std::vector<Polygon2> loops = region_loops(region, min_cells);
    std::vector<Corner> corners = inner_corners(loops, tolerance_cells, min_turn, wall_directions);
    const CornerWalk walk{
        f, lab, k, region.c0, region.r0, tolerance_cells, 1.5 * region.width + tolerance_cells + 2.0};
    choose_cut_edges(corners, walk, corridor_aspect);
    std::vector<std::size_t> run;
    for (const Corner& corner : corners) {
      const Vec2 d = corner.drawn_back ? Vec2(-corner.d_out) : corner.d_in;
      if (!walk(corner, d, !corner.drawn_back, &run))
        continue;  // not within the width, or a mouth already cut
      for (std::size_t j : run) lab[j] = -1;
      cut = true;
    }
  }
  return cut;
}

}  // namespace tsgraphs::rooms::segmentation_steps
