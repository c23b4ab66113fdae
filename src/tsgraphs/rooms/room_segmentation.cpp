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
#include "tsgraphs/rooms/narrowings.hpp"

namespace tsgraphs::rooms {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kLineStep = 0.5;  // cells between the samples that draw a wall: the line stays 8-connected

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

/// The wall's line at floor height: unit normal n (as the plane's, horizontal) and offset d.
struct WallLine {
  int id = -1;
  Vec2 n = Vec2::UnitX();
  double d = 0.0;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  ///< its extent, on the line
};

WallLine line_at(const WallCandidate& w, double floor_z) {
  WallLine l;
  l.id = w.id;
  const double len = w.plane.n.head<2>().norm();
  l.n = w.plane.n.head<2>() / len;
  l.d = (w.plane.d + w.plane.n.z() * floor_z) / len;
  l.a = w.end_a - (l.n.dot(w.end_a) + l.d) * l.n;
  l.b = w.end_b - (l.n.dot(w.end_b) + l.d) * l.n;
  return l;
}

/// A vertical plane of min_wall_height whose points start below a wall's reach and rise
/// min_wall_height above this floor (a wall of the storey below, whose top no ray from here
/// passes above, is not this level's)...
bool of_level(const WallCandidate& w, double floor_z, const RoomSegmentationConfig& cfg) {
  return std::abs(w.plane.n.z()) <= cfg.max_normal_z && w.height >= cfg.min_wall_height &&
         w.z0 <= floor_z + cfg.wall_reach_height && w.z1 >= floor_z + cfg.min_wall_height;
}

/// One of the lines ends within `gap` of the other, and they are not parallel: a corner or a T.
bool joined(const WallLine& p, const WallLine& q, double gap, double cos_parallel) {
  if (std::abs(p.n.dot(q.n)) >= cos_parallel) return false;
  return distance_to_segment(p.a, q.a, q.b) <= gap || distance_to_segment(p.b, q.a, q.b) <= gap ||
         distance_to_segment(q.a, p.a, p.b) <= gap || distance_to_segment(q.b, p.a, p.b) <= gap;
}

/// `p` lies on the line of `q` (parallel, within `offset` of it at both ends) with an end within
/// `gap` of one of q's: the next piece of the same wall past a door.
bool in_line(const WallLine& p, const WallLine& q, double offset, double gap, double cos_parallel) {
  if (std::abs(p.n.dot(q.n)) < cos_parallel) return false;
  if (std::abs(q.n.dot(p.a) + q.d) > offset || std::abs(q.n.dot(p.b) + q.d) > offset) return false;
  return std::min({(p.a - q.a).norm(), (p.a - q.b).norm(), (p.b - q.a).norm(), (p.b - q.b).norm()}) <= gap;
}

/// The walls of the level as lines at floor height: with `reaching`, only those that bound
/// spaces: their points span wall_reach_height, or no ray saw above their top and they join
/// (wall_joint_gap) a wall that bounds, or lie in line with one (on its line within a raster
/// cell, a door's width from its end: a pier between two doors, whose lintel a low sensor
/// does not see); else every vertical plane of min_wall_height that comes
/// down to the level (they may carry a footprint's side: a low sensor sees a small room's walls
/// only up to its head height plus a little).
std::vector<WallLine> level_walls(const std::vector<WallCandidate>& walls, double floor_z,
                                  const RoomSegmentationConfig& cfg, bool reaching = true) {
  std::vector<WallLine> out, unseen_top;
  for (const WallCandidate& w : walls) {
    if (!of_level(w, floor_z, cfg)) continue;
    // ...and reach wall_reach_height, or rise to where no ray saw above them.
    if (reaching && w.z1 < floor_z + cfg.wall_reach_height) {
      if (!w.top_seen) unseen_top.push_back(line_at(w, floor_z));
      continue;
    }
    out.push_back(line_at(w, floor_z));
  }
  // A plane whose top is unseen bounds once it joins one that does, in the input's order.
  const double cos_parallel = std::cos(cfg.parallel_tolerance_deg * kDegToRad);
  std::vector<bool> taken(unseen_top.size(), false);
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t i = 0; i < unseen_top.size(); ++i) {
      if (taken[i]) continue;
      const bool joins = std::any_of(out.begin(), out.end(), [&](const WallLine& o) {
        return joined(unseen_top[i], o, cfg.wall_joint_gap, cos_parallel) ||
               in_line(unseen_top[i], o, cfg.cell, cfg.max_door_width, cos_parallel);
      });
      if (!joins) continue;
      taken[i] = true;
      out.push_back(unseen_top[i]);
      grew = true;
    }
  }
  return out;
}

/// The openings closed between the level's walls that lie on one straight line (parallel
/// within parallel_tolerance_deg, both ends within line_tolerance of the line's first wall): a
/// wall seen in pieces (furniture in front of it, doors in it), or the walls of a row of rooms.
/// Along each line, a gap between consecutive walls is closed when it is no wider than a door or
/// than `opening_share` of the length the line's walls cover (an opening in a long wall); a wide
/// gap between the walls of two far rooms on one line stays open.
std::vector<std::pair<Vec2, Vec2>> line_openings(const std::vector<WallLine>& walls,
                                                 const RoomSegmentationConfig& cfg) {
  const double cos_parallel = std::cos(cfg.parallel_tolerance_deg * kDegToRad);
  struct Line {
    Vec2 origin, along;
    std::vector<std::pair<Vec2, Vec2>> walls;  // each ordered along the line
  };
  std::vector<Line> lines;
  for (const WallLine& w : walls) {
    if ((w.b - w.a).norm() <= 0.0) continue;
    std::size_t k = 0;
    for (; k < lines.size(); ++k) {
      const Vec2 normal(-lines[k].along.y(), lines[k].along.x());
      if (std::abs(normal.dot(w.n)) < cos_parallel) continue;
      const auto off = [&](const Vec2& p) { return std::abs(normal.dot(p - lines[k].origin)); };
      if (off(w.a) <= cfg.line_tolerance && off(w.b) <= cfg.line_tolerance) break;
    }
    if (k == lines.size()) lines.push_back({w.a, (w.b - w.a).normalized(), {}});
    const bool forward = lines[k].along.dot(w.b - w.a) >= 0.0;
    lines[k].walls.emplace_back(forward ? w.a : w.b, forward ? w.b : w.a);
  }
  std::vector<std::pair<Vec2, Vec2>> out;
  for (Line& l : lines) {
    const auto t = [&](const Vec2& p) { return l.along.dot(p - l.origin); };
    std::stable_sort(l.walls.begin(), l.walls.end(),
                     [&](const auto& x, const auto& y) { return t(x.first) < t(y.first); });
    double support = 0.0, reach = -std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : l.walls) {
      support += std::max(0.0, t(b) - std::max(t(a), reach));
      reach = std::max(reach, t(b));
    }
    const double closed = std::max(cfg.max_door_width, cfg.opening_share * support);
    const Vec2* last = nullptr;  // the far end of the walls so far
    for (const auto& [a, b] : l.walls) {
      if (last != nullptr && t(a) > t(*last) && t(a) - t(*last) <= closed) out.emplace_back(*last, a);
      if (last == nullptr || t(b) > t(*last)) last = &b;
    }
  }
  return out;
}

/// The segments that close the doors: from each end of a wall at least min_door_post long, on
/// along its line to the first other wall it meets within max_door_width: one in line with it
/// (its nearer end; a pier between two doors is part of the wall whatever its length), or one
/// at least min_door_post long that it crosses (a pillar's face is no wall to close a gap to);
/// and, besides, to the corner where it and such a wall would cross within wall_joint_gap of
/// both their ends.
std::vector<std::pair<Vec2, Vec2>> door_closures(const std::vector<WallLine>& walls,
                                                 const RoomSegmentationConfig& cfg) {
  const double cos_parallel = std::cos(cfg.parallel_tolerance_deg * kDegToRad);
  std::vector<std::pair<Vec2, Vec2>> out;
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const WallLine& w = walls[i];
    const double length = (w.b - w.a).norm();
    if (length < cfg.min_door_post) continue;
    const Vec2 dir = (w.b - w.a) / length;
    for (int end = 0; end < 2; ++end) {
      const Vec2 from = end == 0 ? w.a : w.b;
      const Vec2 out_dir = end == 0 ? Vec2(-dir) : dir;
      const Vec2 far = from + cfg.max_door_width * out_dir;
      double best = cfg.max_door_width;
      Vec2 to = from;
      double corner_along = cfg.wall_joint_gap;
      std::optional<Vec2> corner;
      for (std::size_t j = 0; j < walls.size(); ++j) {
        const WallLine& o = walls[j];
        if (j == i) continue;
        Vec2 at;
        if (std::abs(o.n.dot(w.n)) >= cos_parallel) {
          // In line: the other wall's nearer end, if it lies on this line within a wall's thickness.
          for (const Vec2& e : {o.a, o.b}) {
            const double along = out_dir.dot(e - from);
            const double side = std::abs(w.n.dot(e - from));
            if (along > 0.0 && along < best && side <= cfg.wall_snap) {
              best = along;
              to = e;
            }
          }
        } else if ((o.b - o.a).norm() >= cfg.min_door_post) {
          const Vec2 u = (o.b - o.a).normalized();
          if (segments_intersect(from, far, o.a, o.b, &at)) {
            const double along = out_dir.dot(at - from);
            if (along > 0.0 && along < best) {
              best = along;
              to = at;
            }
          } else if (segments_intersect(from, from + cfg.wall_joint_gap * out_dir,
                                        o.a - cfg.wall_joint_gap * u, o.b + cfg.wall_joint_gap * u, &at)) {
            // A corner whose two walls were both mapped short of it (each ends within
            // wall_joint_gap of where they would cross): closed as well, not instead of a
            // door farther on.
            const double along = out_dir.dot(at - from);
            if (along > 0.0 && along < corner_along) {
              corner_along = along;
              corner = at;
            }
          }
        }
      }
      if (best < cfg.max_door_width) out.emplace_back(from, to);
      if (corner) out.emplace_back(from, *corner);
    }
  }
  return out;
}

void draw_line(const GridFrame& f, const Vec2& a, const Vec2& b, std::vector<std::uint8_t>* blocked) {
  const double length = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (kLineStep * f.resolution))));
  for (int s = 0; s <= steps; ++s) {
    int c, r;
    if (f.cell_of(a + (b - a) * (static_cast<double>(s) / steps), &c, &r)) (*blocked)[f.index(c, r)] = 1;
  }
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

/// Region k of `lab` in its bounding box, one cell of margin round it (cell units), with what
/// is not the region: the outside (`outside`) and its holes (`parts`, `sizes`). A hole smaller
/// than a region (a pillar, a wall drawn round one) is something one walks round inside the
/// space, not what the space runs round: it neither narrows the width nor has corners.
struct RegionInBox {
  GridFrame box;
  int c0 = 0, r0 = 0;
  std::size_t cells = 0;
  std::vector<std::uint8_t> in;
  std::vector<int> parts;
  std::vector<std::size_t> sizes;
  int outside = -1;
  double width = 0.0;  ///< twice the largest clearance, holes smaller than a region filled (cells)
};

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

/// Long for its width: its area at least `corridor_aspect` times the square of its width.
bool corridor_like(const RegionInBox& region, double corridor_aspect) {
  return static_cast<double>(region.cells) >= corridor_aspect * region.width * region.width;
}

/// Cuts each corridor-like region (its area at least `corridor_aspect` times the square of its
/// widest width, twice its largest clearance, holes of fewer than `min_cells` not counted: a
/// pillar stands inside a space) into its straight legs: at every corner where its
/// outline turns inwards (an inner corner of a bend, a corner of what it runs round: an
/// atrium's void, a walled-off room) the outline's edge arriving there (counter-clockwise round
/// the region, clockwise round a hole) is drawn on across the region until it leaves it, if it
/// does within the corridor's width. Each corner square thus goes to one leg, the same way round
/// every bend. The edge leaving the corner is drawn back instead where only it ends at another
/// inner corner (the mouth of a side corridor: the corridor it leaves stays whole), where only
/// it crosses the region (a step in the width), or where it is corridor_aspect times longer
/// than the arriving edge (a corridor's side running on past a bay). An edge within its
/// simplification's angular error of a wall's direction (`wall_directions`, unit) takes it,
/// and is as long as the straight run of edges it then belongs to.
/// Cut cells lose their label; returns whether any was cut.
bool cut_bends(const GridFrame& f, int n, double corridor_aspect, double min_cells, double tolerance_cells,
               double min_turn, const std::vector<Vec2>& wall_directions, std::vector<int>* label) {
  std::vector<int>& lab = *label;
  bool cut = false;
  for (int k = 0; k < n; ++k) {
    const RegionInBox region = region_in_box(f, lab, k, min_cells);
    if (region.cells == 0 || !corridor_like(region, corridor_aspect)) continue;
    const GridFrame& box = region.box;
    const std::vector<std::uint8_t>& in = region.in;
    const std::vector<int>& parts = region.parts;
    const std::vector<std::size_t>& sizes = region.sizes;
    const int outside = region.outside, c0 = region.c0, r0 = region.r0;
    const double width = region.width;
    const auto counted = [&](int p) {
      return p == outside || static_cast<double>(sizes[static_cast<std::size_t>(p)]) >= min_cells;
    };
    // Its outline, counter-clockwise, and its holes' outlines, each clockwise round the hole:
    // the region lies left of every edge, and an inner corner is a right turn.
    std::vector<Polygon2> loops;
    {
      std::vector<int> only(box.size(), -1);
      for (std::size_t i = 0; i < in.size(); ++i)
        if (in[i]) only[i] = 0;
      loops.push_back(trace_outlines(only, box.cols, box.rows, 1, false).front());
    }
    for (std::size_t p = 0; p < sizes.size(); ++p) {
      if (static_cast<int>(p) == outside || !counted(static_cast<int>(p))) continue;
      std::vector<int> only(box.size(), -1);
      for (std::size_t i = 0; i < parts.size(); ++i)
        if (parts[i] == static_cast<int>(p)) only[i] = 0;
      Polygon2 hole = trace_outlines(only, box.cols, box.rows, 1, false).front();
      std::reverse(hole.begin(), hole.end());
      loops.push_back(hole);
    }
    // The inner corners of all its loops (box coordinates), then one cut per corner.
    struct Corner {
      Vec2 at, d_in, d_out;
      double len_in = 0.0, len_out = 0.0;  ///< the arriving and leaving edges' lengths (cells)
      bool drawn_back = false;             ///< the leaving edge drawn back, not the arriving one drawn on
    };
    std::vector<Corner> corners;
    // A simplified edge's direction is known to within atan(2 tolerance / length); within that
    // of a mapped wall's, it runs along the wall: the raggedness is the raster's (a railing's
    // end, a ramp's top), the sides are the building's, and a cut drawn on from it follows them.
    const auto along_walls = [&](const Vec2& d, double length) {
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
    };
    for (Polygon2& loop : loops) {
      loop = simplify_outlines({loop}, tolerance_cells).front();
      const std::size_t m = loop.size();
      if (m < 3) continue;
      // Edge i runs from vertex i to i + 1; its direction as along_walls gives it.
      std::vector<Vec2> dir(m);
      std::vector<double> len(m);
      for (std::size_t i = 0; i < m; ++i) {
        len[i] = (loop[(i + 1) % m] - loop[i]).norm();
        dir[i] = along_walls((loop[(i + 1) % m] - loop[i]).normalized(), len[i]);
      }
      // The length of the straight run of edges that edge e belongs to, going back (or on):
      // a side whose end the raster made ragged is as long as the whole side.
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
    // A walk on from a corner along `d`, the edge it draws on having the region on its `left`:
    // the region's cells it crosses, and where it left the region (empty if it did not within
    // the corridor's width). Its cells are taken half a cell to the side that was outside along
    // the edge, so that a walk drawing a wall on past a mouth leaves the region where the wall
    // resumes, whichever way the outline runs.
    const double max_walk = 1.5 * width + tolerance_cells + 2.0;
    const auto walk = [&](const Corner& from, const Vec2& d, bool left,
                          std::vector<std::size_t>* run) -> std::optional<Vec2> {
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
    };
    const auto at_other_corner = [&](const Corner& from, const Vec2& q) {
      for (const Corner& o : corners)
        if (&o != &from && (o.at - q).norm() <= tolerance_cells + 1.0) return true;
      return false;
    };
    // The edge arriving at a corner drawn on (d_in), or the edge leaving it drawn back
    // (-d_out). A cut that ends at another inner corner is the mouth between two (a side
    // corridor's, a bridge's): both take it, so a T-junction keeps its through corridor whole.
    // Judged before any cut, as its partner's cut would hide the mouth.
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

void RoomSegmentationConfig::validate() const {
  check_ranges(*this, "RoomSegmentationConfig");  // each field's limits, declared in visit()
}

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

RoomSegmentation segment_rooms(const SegmentationInput& in, const RoomSegmentationConfig& cfg) {
  cfg.validate();
  RoomSegmentation out;
  if (in.free_space.empty() && in.seen.empty()) return out;
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
  out.frame = f;

  // 1-2. The walkable cells: the opened free space, what the rays saw and the ground, all cut
  // by the walls.
  std::vector<std::uint8_t> free = discs(f, in.free_space, in.free_radius);
  {
    // Rays pass at walking height over a ramp's first metres too: where the ground is known to
    // lie higher, what they saw is no floor of this level.
    const std::vector<std::uint8_t> raised = discs(f, in.raised, in.ground_radius);
    for (std::size_t i = 0; i < in.seen.size(); ++i) free[i] = free[i] || (in.seen[i] && !raised[i]);
  }
  std::vector<std::uint8_t> ground = discs(f, in.ground, in.ground_radius);
  for (std::size_t i = 0; i < f.size(); ++i) ground[i] = ground[i] || free[i];
  std::vector<std::uint8_t> wall(f.size(), 0);
  const std::vector<WallLine> walls = level_walls(in.walls, in.floor_z, cfg);
  const std::vector<WallLine> sides = level_walls(in.walls, in.floor_z, cfg, false);
  for (const WallLine& w : walls) draw_line(f, w.a, w.b, &wall);
  for (const auto& [a, b] : door_closures(walls, cfg)) draw_line(f, a, b, &wall);
  // Openings in a long wall line (a corridor's side past a bay): the gaps between its walls.
  for (const auto& [a, b] : line_openings(walls, cfg)) draw_line(f, a, b, &wall);
  for (std::size_t i = 0; i < f.size(); ++i)
    if (wall[i]) ground[i] = 0;

  // 3. The parts of the walkable cells that only narrowings join (wall cells carry no label);
  // small ones join the neighbour they share the most cell edges with, or go.
  std::vector<int> label;
  const int n_spaces = split_at_narrowings(f, ground, 0.5 * cfg.max_door_width, cfg.door_narrowing,
                                           cfg.min_region_area, &label);
  // A region the robot does not fit in (a strip of cells just past a wall's line, between a
  // wall's two faces) is no space.
  {
    std::vector<std::uint8_t> mask(f.size(), 0);
    for (std::size_t i = 0; i < f.size(); ++i) mask[i] = label[i] >= 0 ? 1 : 0;
    const std::vector<float> clearance = distance_transform(f, mask);
    std::vector<float> widest(static_cast<std::size_t>(n_spaces), 0.0f);
    for (std::size_t i = 0; i < f.size(); ++i)
      if (label[i] >= 0)
        widest[static_cast<std::size_t>(label[i])] =
            std::max(widest[static_cast<std::size_t>(label[i])], clearance[i]);
    for (int& l : label)
      if (l >= 0 && widest[static_cast<std::size_t>(l)] < cfg.min_fit_share * in.free_radius) l = -1;
  }
  const double cell_area = cfg.cell * cfg.cell;
  int n = merge_small_regions(f, cfg.min_region_area / cell_area, n_spaces, &label);
  std::vector<int> before_cut = label;
  const int n_before_cut = n;
  std::vector<Vec2> wall_directions;
  for (const WallLine& w : walls)
    if ((w.b - w.a).norm() > 0.0) wall_directions.push_back((w.b - w.a).normalized());
  if (cut_bends(f, n, cfg.corridor_aspect, cfg.min_region_area / cell_area, cfg.bend_tolerance / cfg.cell,
                cfg.min_bend_deg * kDegToRad, wall_directions, &label)) {
    // The legs are regions of their own.
    const int pieces = split_regions(f, &label);
    n = merge_small_regions(f, cfg.min_region_area / cell_area, pieces, &label);
  } else {
    before_cut.clear();
  }
  out.label = label;

  // 4. Footprints.
  // Neighbouring spaces share cell edges, so each outline is simplified on its own.
  std::vector<Polygon2> outlines = trace_outlines(label, f.cols, f.rows, n, false);
  for (Polygon2& p : outlines) p = simplify_outlines({p}, cfg.simplify_tolerance / cfg.cell).front();
  for (Polygon2& p : outlines)
    for (Vec2& v : p) v = f.origin + cfg.cell * v;
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
    SegmentedSpace s;
    const Polygon2& outline = outlines[static_cast<std::size_t>(k)];
    s.area = static_cast<double>(counts[static_cast<std::size_t>(k)]) * cell_area;
    s.frontier = frontier[static_cast<std::size_t>(k)];
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
    if (rectangular) {
      // The room-planes factor: four walls for a room, the two long sides for a corridor.
      if (s.room.kind == RoomKind::room &&
          std::all_of(on.begin(), on.end(), [](int id) { return id >= 0; }) && faces(on[0], on[1]) &&
          faces(on[2], on[3])) {
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
    } else {
      take_outline();
    }
    out.spaces.push_back(std::move(s));
  }
  return out;
}

}  // namespace tsgraphs::rooms
