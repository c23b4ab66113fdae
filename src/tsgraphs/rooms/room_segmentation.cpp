#include "tsgraphs/rooms/room_segmentation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "tsgraphs/core/raster_regions.hpp"
#include "tsgraphs/rooms/bend_cuts.hpp"
#include "tsgraphs/rooms/narrowings.hpp"
#include "tsgraphs/rooms/wall_lines.hpp"

namespace tsgraphs::rooms {
using namespace segmentation_steps;
namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// Cells within `radius` of a cell holding one of `points` (its centre within radius of one).
std::vector<std::uint8_t> discs(const GridFrame& f, const std::vector<Vec2>& points, double radius) {
  std::vector<std::uint8_t> away(f.size(), 1);  // 0 on the cells that hold a point
  for (const Vec2& p : points) {
    int c, r;
    if (f.cell_of(p, &c, &r)) away[f.index(c, r)] = 0;
  }
  const std::vector<float> d = distance_transform(f, away, false);
  std::vector<std::uint8_t> in(f.size(), 0);
  for (std::size_t i = 0; i < in.size(); ++i) in[i] = d[i] <= radius ? 1 : 0;
  return in;
}

/// Regions of fewer than `min_cells` cells join the neighbour they share the most cell edges
/// with (smallest first; ties: the lower label), or are dropped without one; the rest are
/// renumbered from 0 in the order of their first cell. Returns their number.
int merge_small_regions(const GridFrame& f, double min_cells, int n_labels, std::vector<int>* label) {
  std::vector<int>& lab = *label;
  std::vector<std::size_t> cells(static_cast<std::size_t>(n_labels), 0);
  for (int l : lab)
    if (l >= 0) ++cells[static_cast<std::size_t>(l)];
  std::vector<int> parent(static_cast<std::size_t>(n_labels));
  for (int k = 0; k < n_labels; ++k) parent[static_cast<std::size_t>(k)] = k;
  const auto root = [&](int k) {
    while (parent[static_cast<std::size_t>(k)] != k) k = parent[static_cast<std::size_t>(k)];
    return k;
  };
  // Shared edges between labels, counted once per pair of neighbouring cells.
  std::map<std::pair<int, int>, std::size_t> shared;
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c) {
      const int a = lab[f.index(c, r)];
      if (a < 0) continue;
      const int right = c + 1 < f.cols ? lab[f.index(c + 1, r)] : -1;
      const int up = r + 1 < f.rows ? lab[f.index(c, r + 1)] : -1;
      for (int b : {right, up})
        if (b >= 0 && b != a) ++shared[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<int> order;
  for (int k = 0; k < n_labels; ++k)
    if (static_cast<double>(cells[static_cast<std::size_t>(k)]) < min_cells) order.push_back(k);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return cells[a] < cells[b]; });
  for (int k : order) {
    const int rk = root(k);
    if (static_cast<double>(cells[static_cast<std::size_t>(rk)]) >= min_cells)
      continue;  // grown by an earlier merge
    std::map<int, std::size_t> by_root;
    for (const auto& [pair, count] : shared) {
      const int a = root(pair.first), b = root(pair.second);
      if (a == b) continue;
      if (a == rk) by_root[b] += count;
      if (b == rk) by_root[a] += count;
    }
    int best = -1;
    std::size_t best_count = 0;
    for (const auto& [other, count] : by_root) {
      if (count > best_count) {
        best = other;
        best_count = count;
      }
    }
    if (best < 0) {
      cells[static_cast<std::size_t>(rk)] = 0;
      parent[static_cast<std::size_t>(rk)] = rk;
      continue;
    }
    parent[static_cast<std::size_t>(rk)] = best;
    cells[static_cast<std::size_t>(best)] += cells[static_cast<std::size_t>(rk)];
  }
  std::vector<int> renumber(static_cast<std::size_t>(n_labels), -1);
  int n = 0;
  for (int& l : lab) {
    if (l < 0) continue;
    const int r = root(l);
    if (static_cast<double>(cells[static_cast<std::size_t>(r)]) < min_cells) {
      l = -1;
      continue;
    }
    if (renumber[static_cast<std::size_t>(r)] < 0) renumber[static_cast<std::size_t>(r)] = n++;
    l = renumber[static_cast<std::size_t>(r)];
  }
  return n;
}

/// Per region, the share of its edge cells (beside a cell of another label or none) that are
/// frontier: outwards, within `reach` cells, a cell nothing has seen (no ray, no ground, no wall)
/// comes before a wall, a region or a seen cell.
std::vector<double> frontier_shares(const GridFrame& f, const std::vector<int>& label, int n,
                                    const std::vector<std::uint8_t>& wall,
                                    const std::vector<std::uint8_t>& ground,
                                    const std::vector<std::uint8_t>& known, int reach) {
  static const int kDc[4] = {1, -1, 0, 0};
  static const int kDr[4] = {0, 0, 1, -1};
  std::vector<std::size_t> edge(static_cast<std::size_t>(n), 0), open_edge(static_cast<std::size_t>(n), 0);
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c) {
      const int l = label[f.index(c, r)];
      if (l < 0) continue;
      bool is_edge = false, frontier = false;
      for (int k = 0; k < 4; ++k) {
        const int cc = c + kDc[k], rr = r + kDr[k];
        if (f.inside(cc, rr) && label[f.index(cc, rr)] == l) continue;
        is_edge = true;
        for (int step = 1; step <= reach && !frontier; ++step) {
          const int sc = c + step * kDc[k], sr = r + step * kDr[k];
          if (!f.inside(sc, sr)) {
            frontier = true;
            break;
          }
          const std::size_t j = f.index(sc, sr);
          if (wall[j] || label[j] >= 0 || ground[j] || known[j]) break;
          frontier = true;
        }
      }
      if (!is_edge) continue;
      ++edge[static_cast<std::size_t>(l)];
      if (frontier) ++open_edge[static_cast<std::size_t>(l)];
    }
  }
  std::vector<double> share(static_cast<std::size_t>(n), 0.0);
  for (std::size_t k = 0; k < share.size(); ++k)
    if (edge[k] > 0) share[k] = static_cast<double>(open_edge[k]) / static_cast<double>(edge[k]);
  return share;
}

/// Renumbers the labels so that each 4-connected piece of one label is a region of its own,
/// from 0 in the order of their first cell; returns their number.
int split_regions(const GridFrame& f, std::vector<int>* label) {
  std::vector<int>& lab = *label;
  std::vector<int> out(lab.size(), -1);
  std::vector<std::size_t> stack;
  static const int kDc[4] = {1, -1, 0, 0};
  static const int kDr[4] = {0, 0, 1, -1};
  int n = 0;
  for (std::size_t start = 0; start < lab.size(); ++start) {
    if (lab[start] < 0 || out[start] >= 0) continue;
    out[start] = n;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      const int c = static_cast<int>(i % f.cols), r = static_cast<int>(i / f.cols);
      for (int k = 0; k < 4; ++k) {
        const int cc = c + kDc[k], rr = r + kDr[k];
        if (!f.inside(cc, rr)) continue;
        const std::size_t j = f.index(cc, rr);
        if (lab[j] == lab[start] && out[j] < 0) {
          out[j] = n;
          stack.push_back(j);
        }
      }
    }
    ++n;
  }
  lab = std::move(out);
  return n;
}

/// Puts each side of the rectangle that has a wall beside it (parallel, within
/// wall_snap, running along min_wall_overlap of it) on the nearest such wall. Returns per side
/// (-x, +x, -y, +y of the rect's frame) the wall's id or -1.
std::array<int, 4> snap_to_walls(OrientedRect* rect, const std::vector<WallLine>& walls,
                                 const RoomSegmentationConfig& cfg) {
  const Vec2 ux(std::cos(rect->yaw), std::sin(rect->yaw));
  const Vec2 uy(-ux.y(), ux.x());
  double lo[2] = {ux.dot(rect->center) - 0.5 * rect->size.x(), uy.dot(rect->center) - 0.5 * rect->size.y()};
  double hi[2] = {ux.dot(rect->center) + 0.5 * rect->size.x(), uy.dot(rect->center) + 0.5 * rect->size.y()};
  const double cos_parallel = std::cos(cfg.parallel_tolerance_deg * kDegToRad);
  std::array<int, 4> ids{-1, -1, -1, -1};
  double moved[4] = {0, 0, 0, 0};
  for (int side = 0; side < 4; ++side) {
    const int axis = side / 2;
    const Vec2& u = axis == 0 ? ux : uy;
    const Vec2& v = axis == 0 ? uy : ux;
    const double at = side % 2 == 0 ? lo[axis] : hi[axis];
    const double v_lo = side < 2 ? lo[1] : lo[0], v_hi = side < 2 ? hi[1] : hi[0];
    double best = cfg.wall_snap;
    for (const WallLine& w : walls) {
      if (std::abs(w.n.dot(u)) < cos_parallel) continue;  // either face: a plane's sign follows who saw it
      // Where the wall's line crosses u at the side's middle.
      const Vec2 mid = u * at + v * (0.5 * (v_lo + v_hi));
      const double pos = at - (w.n.dot(mid) + w.d) / w.n.dot(u);
      const double offset = std::abs(pos - at);
      const double a = v.dot(w.a), b = v.dot(w.b);
      const double overlap = std::min(std::max(a, b), v_hi) - std::max(std::min(a, b), v_lo);
      if (offset > best || overlap < cfg.min_wall_overlap * (v_hi - v_lo)) continue;
      best = offset;
      ids[side] = w.id;
      moved[side] = pos;
    }
  }
  // A rectangle thinner than the snap distance may find a wall beyond its other side: no wall
  // is then a side of it on that axis (its sides would cross).
  for (int axis = 0; axis < 2; ++axis) {
    const double new_lo = ids[2 * axis] >= 0 ? moved[2 * axis] : lo[axis];
    const double new_hi = ids[2 * axis + 1] >= 0 ? moved[2 * axis + 1] : hi[axis];
    if (new_hi > new_lo) continue;
    ids[2 * axis] = ids[2 * axis + 1] = -1;
  }
  for (int side = 0; side < 4; ++side) {
    if (ids[side] < 0) continue;
    (side % 2 == 0 ? lo : hi)[side / 2] = moved[side];
  }
  const Vec2 mid(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]));
  rect->center = ux * mid.x() + uy * mid.y();
  rect->size = Vec2(hi[0] - lo[0], hi[1] - lo[1]);
  return ids;
}

/// Whether a wall that bounds spaces runs into the rectangle farther than `margin` inside its
/// sides (a wall along a side, where the rectangle was snapped, does not): the rectangle then
/// covers the far side of a wall, as a diagonal corridor's rectangle does past the facade at its
/// ends.
bool crosses_a_wall(const OrientedRect& rect, const std::vector<WallLine>& walls, double margin) {
  if (rect.size.x() <= 2.0 * margin || rect.size.y() <= 2.0 * margin) return false;
  OrientedRect inner = rect;
  inner.size -= Vec2::Constant(2.0 * margin);
  const Polygon2 box = inner.corners();
  for (const WallLine& w : walls) {
    if (contains(box, w.a) || contains(box, w.b)) return true;
    for (std::size_t i = 0; i < box.size(); ++i)
      if (segments_intersect(w.a, w.b, box[i], box[(i + 1) % box.size()])) return true;
  }
  return false;
}

}  // namespace

bool short_of_reach(const WallCandidate& wall, double floor_z, const RoomSegmentationConfig& cfg) {
  return of_level(wall, floor_z, cfg) && wall.z1 < floor_z + cfg.wall_reach_height;
}

bool crosses_wall(const Vec2& a, const Vec2& b, const std::vector<WallCandidate>& walls, double floor_z,
                  const RoomSegmentationConfig& cfg) {
  for (const WallLine& w : level_walls(walls, floor_z, cfg))
    if (segments_intersect(a, b, w.a, w.b)) return true;
  return false;
}

int RoomSegmentation::space_at(const Vec2& p, double radius) const {
  int c, r;
  if (frame.size() == 0) return -1;
  if (frame.cell_of(p, &c, &r) && label[frame.index(c, r)] >= 0) return label[frame.index(c, r)];
  const int reach = static_cast<int>(std::ceil(radius / frame.resolution));
  const Vec2 q = (p - frame.origin) / frame.resolution;
  const int pc = static_cast<int>(std::floor(q.x())), pr = static_cast<int>(std::floor(q.y()));
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int rr = pr - reach; rr <= pr + reach; ++rr) {
    for (int cc = pc - reach; cc <= pc + reach; ++cc) {
      if (!frame.inside(cc, rr) || label[frame.index(cc, rr)] < 0) continue;
      const double d = (frame.center(cc, rr) - p).norm();
      if (d <= radius && d < best_d) {
        best_d = d;
        best = label[frame.index(cc, rr)];
      }
    }
  }
  return best;
}

void SegmentationInput::extend_bounds(Vec2* lo, Vec2* hi) const {
  for (const std::vector<Vec2>* set : {&free_space, &ground}) {
    for (const Vec2& p : *set) {
      *lo = lo->cwiseMin(p);
      *hi = hi->cwiseMax(p);
    }
  }
}

namespace {

/// The raster's frame: the input's, or one round its points; the cell masks checked against it.
GridFrame segmentation_frame(const SegmentationInput& in, const RoomSegmentationConfig& cfg) {
  GridFrame f = in.frame;
  if (f.size() == 0) {
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    in.extend_bounds(&lo, &hi);
    f = GridFrame::around(lo, hi, cfg.cell, std::max(in.free_radius, in.ground_radius) + 2.0 * cfg.cell);
  }
  for (const std::vector<std::uint8_t>* cells : {&in.seen, &in.known}) {
    if (!cells->empty() && cells->size() != f.size())
      throw std::invalid_argument("segment_rooms: a cell mask has " + std::to_string(cells->size()) +
                                  " cells, the frame " + std::to_string(f.size()));
  }
  return f;
}

/// 1-2. The walkable cells: the opened free space, what the rays saw and the ground, all cut by
/// the walls, their doors and the openings of their lines (drawn into `wall`).
std::vector<std::uint8_t> walkable_cells(const GridFrame& f, const SegmentationInput& in,
                                         const std::vector<WallLine>& walls,
                                         const RoomSegmentationConfig& cfg, std::vector<std::uint8_t>& wall) {
  std::vector<std::uint8_t> free = discs(f, in.free_space, in.free_radius);
  {
    // Rays pass at walking height over a ramp's first metres too: where the ground is known to
    // lie higher, what they saw is no floor of this level.
    const std::vector<std::uint8_t> raised = discs(f, in.raised, in.ground_radius);
    for (std::size_t i = 0; i < in.seen.size(); ++i) free[i] = free[i] || (in.seen[i] && !raised[i]);
  }
  std::vector<std::uint8_t> ground = discs(f, in.ground, in.ground_radius);
  for (std::size_t i = 0; i < f.size(); ++i) ground[i] = ground[i] || free[i];
  wall.assign(f.size(), 0);
  for (const WallLine& w : walls) draw_line(f, w.a, w.b, &wall);
  for (const auto& [a, b] : door_closures(walls, cfg)) draw_line(f, a, b, &wall);
  // Openings in a long wall line (a corridor's side past a bay): the gaps between its walls.
  for (const auto& [a, b] : line_openings(walls, cfg)) draw_line(f, a, b, &wall);
  for (std::size_t i = 0; i < f.size(); ++i)
    if (wall[i]) ground[i] = 0;
  return ground;
}

/// A region the robot does not fit in (a strip of cells just past a wall's line, between a
/// wall's two faces: its widest clearance under `min_clearance`) is no space.
void drop_unfit_regions(const GridFrame& f, int n_spaces, double min_clearance, std::vector<int>& label) {
  std::vector<std::uint8_t> mask(f.size(), 0);
  for (std::size_t i = 0; i < f.size(); ++i) mask[i] = label[i] >= 0 ? 1 : 0;
  const std::vector<float> clearance = distance_transform(f, mask);
  std::vector<float> widest(static_cast<std::size_t>(n_spaces), 0.0f);
  for (std::size_t i = 0; i < f.size(); ++i)
    if (label[i] >= 0)
      widest[static_cast<std::size_t>(label[i])] =
          std::max(widest[static_cast<std::size_t>(label[i])], clearance[i]);
  for (int& l : label)
    if (l >= 0 && widest[static_cast<std::size_t>(l)] < min_clearance) l = -1;
}

/// Every walkable cell no space holds (a ray seen through a door, a pocket too small or too thin
/// to be a space of its own) joins the space nearest to it over walkable cells, stepping
/// diagonally too (a ray drawn on a raster is a diagonal chain of cells) but never between two
/// wall cells: as ipa_room_segmentation grows its rooms back over the free space.
void grow_into_unlabelled(const GridFrame& f, const std::vector<std::uint8_t>& walkable,
                          const std::vector<std::uint8_t>& wall, std::vector<int>& label) {
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (label[i] >= 0) front.push_back(i);
  std::vector<std::size_t> next;
  while (!front.empty()) {
    next.clear();
    for (std::size_t i : front) {
      const int c = static_cast<int>(i % f.cols), r = static_cast<int>(i / f.cols);
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int cc = c + dc, rr = r + dr;
          if ((dc == 0 && dr == 0) || !f.inside(cc, rr)) continue;
          const std::size_t j = f.index(cc, rr);
          if (!walkable[j] || label[j] >= 0) continue;
          if (dc != 0 && dr != 0 && (wall[f.index(cc, r)] || wall[f.index(c, rr)])) continue;
          label[j] = label[i];
          next.push_back(j);
        }
      }
    }
    std::sort(next.begin(), next.end());
    front.swap(next);
  }
}

/// The spaces' outlines in the map frame; neighbouring spaces share cell edges, so each
/// outline is simplified on its own.
std::vector<Polygon2> space_outlines(const GridFrame& f, const std::vector<int>& label, int n,
                                     const RoomSegmentationConfig& cfg) {
  std::vector<Polygon2> outlines = trace_outlines(label, f.cols, f.rows, n, false);
  for (Polygon2& p : outlines) p = simplify_outlines({p}, cfg.simplify_tolerance / cfg.cell).front();
  for (Polygon2& p : outlines)
    for (Vec2& v : p) v = f.origin + cfg.cell * v;
  return outlines;
}

/// A space's footprint: its rectangle snapped to the walls beside its sides, with the walls of
/// its room-planes factor (four for a room, the two long sides for a corridor), when it fills its
/// rectangle and no wall runs into it; else its outline.
SegmentedSpace footprint(const Polygon2& outline, const std::vector<WallLine>& sides,
                         const std::vector<WallLine>& walls, const RoomSegmentationConfig& cfg) {
  SegmentedSpace s;
  OrientedRect rect = min_area_rect(outline);
  const bool rectangular = rect.area() > 0.0 && area(outline) >= cfg.rect_fill * rect.area();
  const std::array<int, 4> on = snap_to_walls(&rect, sides, cfg);
  // A factor's pair must face each other (the back-end's room-planes factor needs it).
  const auto faces = [&](int a, int b) {
    const Vec2* na = nullptr;
    const Vec2* nb = nullptr;
    for (const WallLine& w : sides) {
      if (w.id == a) na = &w.n;
      if (w.id == b) nb = &w.n;
    }
    return na != nullptr && nb != nullptr && na->dot(*nb) < 0.0;
  };
  const bool long_along_x = rect.size.x() >= rect.size.y();
  const double length = std::max(rect.size.x(), rect.size.y()),
               width = std::min(rect.size.x(), rect.size.y());
  s.room.kind = length >= cfg.corridor_aspect * width ? RoomKind::corridor : RoomKind::room;
  const auto take_outline = [&] {
    s.room.outline = outline;
    if (signed_area(s.room.outline) < 0.0) std::reverse(s.room.outline.begin(), s.room.outline.end());
    s.centroid = centroid(outline);
  };
  s.room.rect = rect;
  if (!rectangular) {
    take_outline();
    return s;
  }
  if (s.room.kind == RoomKind::room && std::all_of(on.begin(), on.end(), [](int id) { return id >= 0; }) &&
      faces(on[0], on[1]) && faces(on[2], on[3])) {
    s.room.wall_ids = {on[0], on[1], on[2], on[3]};
  } else if (s.room.kind == RoomKind::corridor) {
    const int a = long_along_x ? 2 : 0;  // the sides along the corridor's length
    if (on[a] >= 0 && on[a + 1] >= 0 && faces(on[a], on[a + 1])) {
      s.room.wall_ids = {on[a], on[a + 1]};
      // The factor's pair is along the rect's x axis: turn the rect so that x is across.
      if (long_along_x) {
        s.room.rect.yaw += M_PI / 2.0;
        s.room.rect.size = Vec2(rect.size.y(), rect.size.x());
      }
    }
    const int b = long_along_x ? 0 : 2;
    for (int e : {on[b], on[b + 1]})
      if (e >= 0) s.room.end_wall_ids.push_back(e);
  }
  s.centroid = s.room.rect.center;
  // A rectangle across a wall is no footprint (the free space does not cross it): the
  // outline is, and the rectangle's walls still make the factor.
  if (crosses_a_wall(s.room.rect, walls, cfg.wall_snap)) take_outline();
  return s;
}

}  // namespace

RoomSegmentation segment_rooms(const SegmentationInput& in, const RoomSegmentationConfig& cfg) {
  check_config(cfg, "RoomSegmentationConfig");
  RoomSegmentation out;
  if (in.free_space.empty() && in.seen.empty()) return out;
  const GridFrame f = segmentation_frame(in, cfg);
  out.frame = f;
  const std::vector<WallLine> walls = level_walls(in.walls, in.floor_z, cfg);
  const std::vector<WallLine> sides = level_walls(in.walls, in.floor_z, cfg, false);
  std::vector<std::uint8_t> wall;
  const std::vector<std::uint8_t> ground = walkable_cells(f, in, walls, cfg, wall);

  // 3. The parts of the walkable cells that only narrowings join (wall cells carry no label);
  // small ones join the neighbour they share the most cell edges with, or go.
  std::vector<int> label;
  const int n_spaces = split_at_narrowings(f, ground, 0.5 * cfg.max_door_width, cfg.door_narrowing,
                                           cfg.min_region_area, &label);
  drop_unfit_regions(f, n_spaces, cfg.min_fit_share * in.free_radius, label);
  const double cell_area = cfg.cell * cfg.cell;
  int n = merge_small_regions(f, cfg.min_region_area / cell_area, n_spaces, &label);
  std::vector<int> before_cut = label;
  const int n_before_cut = n;
  std::vector<Vec2> wall_directions;
  for (const WallLine& w : walls)
    if ((w.b - w.a).norm() > 0.0) wall_directions.push_back((w.b - w.a).normalized());
  if (cut_bends(f, n, cfg.corridor_aspect, cfg.max_corridor_width / cfg.cell, cfg.min_region_area / cell_area,
                cfg.bend_tolerance / cfg.cell, cfg.min_bend_deg * kDegToRad, wall_directions, &label)) {
    // The legs are regions of their own.
    const int pieces = split_regions(f, &label);
    n = merge_small_regions(f, cfg.min_region_area / cell_area, pieces, &label);
  } else {
    before_cut.clear();
  }
  if (in.label_every_cell) grow_into_unlabelled(f, ground, wall, label);
  out.label = label;

  // 4. Footprints.
  const std::vector<Polygon2> outlines = space_outlines(f, label, n, cfg);
  std::vector<std::size_t> counts(static_cast<std::size_t>(n), 0);
  for (int l : label)
    if (l >= 0) ++counts[static_cast<std::size_t>(l)];
  std::vector<double> frontier(static_cast<std::size_t>(n), 0.0);
  if (!in.known.empty()) {
    const int reach_cells = std::max(1, static_cast<int>(std::lround(cfg.frontier_reach / cfg.cell)));
    frontier = frontier_shares(f, label, n, wall, ground, in.known, reach_cells);
    // A leg cut off a region that is still being explored is too: the cut is no wall.
    if (!before_cut.empty()) {
      const std::vector<double> whole =
          frontier_shares(f, before_cut, n_before_cut, wall, ground, in.known, reach_cells);
      for (std::size_t i = 0; i < f.size(); ++i)
        if (label[i] >= 0 && before_cut[i] >= 0)
          frontier[static_cast<std::size_t>(label[i])] = std::max(
              frontier[static_cast<std::size_t>(label[i])], whole[static_cast<std::size_t>(before_cut[i])]);
    }
  }
  for (int k = 0; k < n; ++k) {
    SegmentedSpace s = footprint(outlines[static_cast<std::size_t>(k)], sides, walls, cfg);
    s.area = static_cast<double>(counts[static_cast<std::size_t>(k)]) * cell_area;
    s.frontier = frontier[static_cast<std::size_t>(k)];
    out.spaces.push_back(std::move(s));
  }
  return out;
}

}  // namespace tsgraphs::rooms
