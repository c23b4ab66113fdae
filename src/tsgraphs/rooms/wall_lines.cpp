#include "tsgraphs/rooms/wall_lines.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace tsgraphs::rooms::segmentation_steps {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

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

/// A wall across the line (normal `normal` through `origin`) passes within `gap` of `p` and
/// reaches more than `gap` past the line on both sides: a corridor's or a room's side that the
/// line runs into, not a wall that ends on it.
bool passes_through(const Vec2& p, const Vec2& origin, const Vec2& normal, const std::vector<WallLine>& walls,
                    double gap, double cos_parallel) {
  return std::any_of(walls.begin(), walls.end(), [&](const WallLine& o) {
    if (std::abs(o.n.dot(normal)) >= cos_parallel || distance_to_segment(p, o.a, o.b) > gap) return false;
    const double sa = normal.dot(o.a - origin), sb = normal.dot(o.b - origin);
    return std::min(sa, sb) < -gap && std::max(sa, sb) > gap;
  });
}

}  // namespace

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

/// The walls of the level as lines at floor height: with `reaching`, only those that bound
/// spaces: their points span wall_reach_height, or no ray saw above their top and they join
/// (wall_joint_gap) a wall that bounds, or lie in line with one (on its line within a raster
/// cell, a door's width from its end: a pier between two doors, whose lintel a low sensor
/// does not see); else every vertical plane of min_wall_height that comes
/// down to the level (they may carry a footprint's side: a low sensor sees a small room's walls
/// only up to its head height plus a little).
std::vector<WallLine> level_walls(const std::vector<WallCandidate>& walls, double floor_z,
                                  const RoomSegmentationConfig& cfg, bool reaching) {
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
/// gap between the walls of two far rooms on one line stays open, and so does a wider gap whose
/// two ends lie on walls that pass through the line (wall_joint_gap): it spans a space between
/// those walls (the partitions of two rows of rooms facing over a corridor), no opening in one.
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
    const Vec2 normal(-l.along.y(), l.along.x());
    const auto across = [&](const Vec2& p) {
      return passes_through(p, l.origin, normal, walls, cfg.wall_joint_gap, cos_parallel);
    };
    const Vec2* last = nullptr;  // the far end of the walls so far
    for (const auto& [a, b] : l.walls) {
      const double gap = last != nullptr ? t(a) - t(*last) : 0.0;
      if (gap > 0.0 && (gap <= cfg.max_door_width || (gap <= closed && !(across(*last) && across(a)))))
        out.emplace_back(*last, a);
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

}  // namespace tsgraphs::rooms::segmentation_steps
