#include "tsgraphs/rooms/map_walls.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tsgraphs/core/raster_regions.hpp"

namespace tsgraphs::rooms {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kSearchStepDeg = 0.5;   // the coarse search over half a turn
constexpr double kRefineSpanDeg = 1.0;   // ...then within this of each direction found
constexpr double kRefineStepDeg = 0.05;  // ...in these steps

/// An edge cell: blocked, with the free space one step along `side` * normal.
struct EdgeCell {
  double offset;  ///< across the direction, cells
  double along;   ///< along it, cells
};

/// A straight run of edge cells in one bin.
struct Piece {
  double offset;  ///< the bin's centre, cells
  double t0, t1;  ///< along the direction, cells
  double length() const { return t1 - t0; }
};

/// Per cell, the distance (m) to the nearest cell of `cells`.
std::vector<float> distance_to(const GridFrame& f, const std::vector<std::uint8_t>& cells) {
  std::vector<std::uint8_t> away(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) away[i] = cells[i] ? 0 : 1;
  return distance_transform(f, away, false);
}

/// The blocked cells joined to the raster's border through blocked cells (8-connected): the
/// building's structure, walls joined to walls and to what lies round it. What stands free
/// inside (a table, a pillar, a chair's legs) is furniture, not wall.
std::vector<std::uint8_t> structure(const GridFrame& f, const std::vector<std::uint8_t>& free) {
  std::vector<std::uint8_t> blocked(free.size());
  for (std::size_t i = 0; i < free.size(); ++i) blocked[i] = free[i] ? 0 : 1;
  const std::vector<std::uint8_t> inside =
      enclosed_regions(blocked, f.cols, f.rows, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < free.size(); ++i) blocked[i] = blocked[i] && !inside[i];
  return blocked;
}

/// The structure's cells with a free cell among their 8 neighbours: the edge in every direction.
struct Edge {
  const GridFrame* frame;
  const std::vector<std::uint8_t>* free;
  std::vector<std::size_t> cells;
};

/// The edge of the cells `of` (blocked ones) next to the free space.
Edge edge_of(const GridFrame& f, const std::vector<std::uint8_t>& free, const std::vector<std::uint8_t>& of) {
  Edge e{&f, &free, {}};
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c) {
      if (!of[f.index(c, r)] || free[f.index(c, r)]) continue;
      bool beside = false;
      for (int dr = -1; dr <= 1 && !beside; ++dr)
        for (int dc = -1; dc <= 1 && !beside; ++dc)
          beside = f.inside(c + dc, r + dr) && free[f.index(c + dc, r + dr)];
      if (beside) e.cells.push_back(f.index(c, r));
    }
  }
  return e;
}

/// The edge cells facing `side` (+1 or -1) along the normal at angle `theta` (the free space is
/// the neighbour that way), with their offsets across it and positions along it (cell units,
/// cell centres).
std::vector<EdgeCell> edge_cells(const Edge& edge, double theta, int side) {
  const GridFrame& f = *edge.frame;
  const double nx = std::cos(theta), ny = std::sin(theta);
  const int dc = static_cast<int>(std::lround(side * nx)), dr = static_cast<int>(std::lround(side * ny));
  std::vector<EdgeCell> out;
  for (std::size_t i : edge.cells) {
    const int c = static_cast<int>(i % f.cols), r = static_cast<int>(i / f.cols);
    const int cc = c + dc, rr = r + dr;
    if (!f.inside(cc, rr) || !(*edge.free)[f.index(cc, rr)]) continue;
    const double x = c + 0.5, y = r + 0.5;
    out.push_back({nx * x + ny * y, -ny * x + nx * y});
  }
  return out;
}

/// The runs along of `along` (sorted) with gaps of at most max_gap cells that are at least
/// min_piece cells long, at `offset`.
void runs_of(const std::vector<double>& along, double offset, double max_gap, double min_piece,
             std::vector<Piece>* out) {
  for (std::size_t a = 0; a < along.size();) {
    std::size_t b = a;
    while (b + 1 < along.size() && along[b + 1] - along[b] <= max_gap + 1.0) ++b;
    const Piece p{offset, along[a], along[b]};
    if (p.length() >= min_piece) out->push_back(p);
    a = b + 1;
  }
}

/// The pieces of `cells`: an edge at a slant is a staircase whose cells' offsets lie within a
/// cell of its line, so the cells are binned by offset a cell wide and each two neighbouring bins
/// looked at together; the pairs that explain the most length are taken first, each bin in one
/// pair at most. A pair's runs are its pieces, at its cells' mean offset.
std::vector<Piece> pieces_of(const std::vector<EdgeCell>& cells, double max_gap, double min_piece) {
  std::map<long, std::vector<const EdgeCell*>> bins;
  for (const EdgeCell& e : cells) bins[static_cast<long>(std::floor(e.offset))].push_back(&e);
  struct Pair {
    long bin;
    double length;
    std::vector<Piece> pieces;
  };
  std::vector<Pair> pairs;
  for (const auto& [bin, members] : bins) {
    std::vector<const EdgeCell*> both = members;
    const auto next = bins.find(bin + 1);
    if (next != bins.end()) both.insert(both.end(), next->second.begin(), next->second.end());
    std::vector<double> along;
    double offset = 0.0;
    for (const EdgeCell* e : both) {
      along.push_back(e->along);
      offset += e->offset;
    }
    std::sort(along.begin(), along.end());
    Pair p{bin, 0.0, {}};
    runs_of(along, offset / static_cast<double>(both.size()), max_gap, min_piece, &p.pieces);
    for (const Piece& q : p.pieces) p.length += q.length();
    if (p.length > 0.0) pairs.push_back(std::move(p));
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Pair& a, const Pair& b) { return a.length > b.length; });
  std::set<long> used;
  std::vector<Piece> out;
  for (const Pair& p : pairs) {
    if (used.count(p.bin) || used.count(p.bin + 1)) continue;
    used.insert(p.bin);
    used.insert(p.bin + 1);
    out.insert(out.end(), p.pieces.begin(), p.pieces.end());
  }
  std::sort(out.begin(), out.end(), [](const Piece& a, const Piece& b) {
    return a.offset != b.offset ? a.offset < b.offset : a.t0 < b.t0;
  });
  return out;
}

/// The wall length the edge explains along the normal at `theta` (both faces), cells.
double explained(const Edge& edge, double theta, double max_gap, double min_piece) {
  double total = 0.0;
  for (int side : {1, -1})
    for (const Piece& p : pieces_of(edge_cells(edge, theta, side), max_gap, min_piece)) total += p.length();
  return total;
}

/// How sharply the edge lines up across the normal at `theta`: the sum of the squared counts of
/// its cells per one-cell bin of offset (both faces). Sharper than the explained length, which
/// stays the same over the angles within which a wall's staircase keeps to two bins.
double sharpness(const Edge& edge, double theta) {
  double total = 0.0;
  for (int side : {1, -1}) {
    std::map<long, double> count;
    for (const EdgeCell& e : edge_cells(edge, theta, side))
      count[static_cast<long>(std::floor(e.offset))] += 1.0;
    for (const auto& [bin, n] : count) total += n * n;
  }
  return total;
}

/// The angular distance between two directions of lines (modulo half a turn), rad.
double line_angle_between(double a, double b) {
  const double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d);
}

/// The angle within kRefineSpanDeg of `theta` at which the edge lines up most sharply.
double refined(const Edge& edge, double theta) {
  double best = theta, best_score = -1.0;
  for (double d = -kRefineSpanDeg; d <= kRefineSpanDeg + 1e-9; d += kRefineStepDeg) {
    const double s = sharpness(edge, theta + d * kDegToRad);
    if (s > best_score) {
      best_score = s;
      best = theta + d * kDegToRad;
    }
  }
  return best;
}

/// Step 2: the wall directions (normals' angles), best first. Walls mostly meet at right angles:
/// the best direction's perpendicular comes next; then any other that explains enough.
std::vector<double> wall_directions(const Edge& edge, const MapWallsConfig& cfg, double max_gap,
                                    double min_piece) {
  const int steps = static_cast<int>(std::lround(180.0 / kSearchStepDeg));
  std::vector<double> score(static_cast<std::size_t>(steps));
  for (int k = 0; k < steps; ++k)
    score[static_cast<std::size_t>(k)] = explained(edge, k * kSearchStepDeg * kDegToRad, max_gap, min_piece);
  std::vector<int> order(static_cast<std::size_t>(steps));
  for (int k = 0; k < steps; ++k) order[static_cast<std::size_t>(k)] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return score[a] > score[b]; });
  const double best = score[static_cast<std::size_t>(order[0])];
  std::vector<double> out;
  if (best <= 0.0) return out;
  const double separation = cfg.min_direction_separation_deg * kDegToRad;
  const auto take = [&](double theta) {
    if (std::any_of(out.begin(), out.end(),
                    [&](double t) { return line_angle_between(t, theta) < separation; }))
      return;
    const double t = refined(edge, theta);
    if (out.empty() || explained(edge, t, max_gap, min_piece) >= cfg.min_direction_share * best)
      out.push_back(t);
  };
  take(order[0] * kSearchStepDeg * kDegToRad);
  take(out.front() + M_PI / 2.0);
  for (int k : order) {
    if (score[static_cast<std::size_t>(k)] < cfg.min_direction_share * best) break;
    take(k * kSearchStepDeg * kDegToRad);
  }
  return out;
}

WallCandidate wall_of(const GridFrame& f, double theta, int side, double offset, const Piece& p, int id,
                      double height) {
  const Vec2 n(std::cos(theta), std::sin(theta)), u(-n.y(), n.x());
  const Vec2 a = f.origin + f.resolution * (n * offset + u * p.t0);
  const Vec2 b = f.origin + f.resolution * (n * offset + u * p.t1);
  WallCandidate w;
  w.id = id;
  const Eigen::Vector3d normal(side * n.x(), side * n.y(), 0.0);
  w.plane = Plane::from_point_normal(Eigen::Vector3d(a.x(), a.y(), 0.0), normal);
  w.end_a = a;
  w.end_b = b;
  w.z0 = 0.0;
  w.z1 = height;
  w.height = height;
  w.top_seen = false;
  return w;
}

}  // namespace

std::vector<std::uint8_t> open_free_space(const GridFrame& frame, const std::vector<std::uint8_t>& free,
                                          double radius) {
  if (free.size() != frame.size())
    throw std::invalid_argument("open_free_space: the mask does not match the frame");
  const std::vector<float> clearance = distance_transform(frame, free);
  std::vector<std::uint8_t> away(free.size(), 1);  // 0 on the cells the disc's centre may take
  for (std::size_t i = 0; i < free.size(); ++i)
    if (free[i] && clearance[i] > radius) away[i] = 0;
  const std::vector<float> reach = distance_transform(frame, away, false);
  std::vector<std::uint8_t> out(free.size(), 0);
  for (std::size_t i = 0; i < free.size(); ++i) out[i] = free[i] && reach[i] <= radius ? 1 : 0;
  return out;
}

std::vector<WallCandidate> map_walls(const GridFrame& frame, const std::vector<std::uint8_t>& free,
                                     const std::vector<std::uint8_t>& occupied,
                                     const MapWallsConfig& config) {
  check_config(config, "MapWallsConfig");
  for (const std::vector<std::uint8_t>* mask : {&free, &occupied})
    if (mask->size() != frame.size())
      throw std::invalid_argument("map_walls: a mask has " + std::to_string(mask->size()) +
                                  " cells, the frame " + std::to_string(frame.size()));
  const std::vector<std::uint8_t> open = open_free_space(frame, free, config.robot_radius);
  const double res = frame.resolution;
  const double min_piece = config.min_piece / res;
  std::vector<WallCandidate> out;
  const std::vector<std::uint8_t> joined = structure(frame, open);
  std::vector<std::uint8_t> apart(joined.size());
  for (std::size_t i = 0; i < apart.size(); ++i) apart[i] = joined[i] ? 0 : 1;
  Edge walls = edge_of(frame, open, joined), furniture = edge_of(frame, open, apart);
  // An edge is a wall only where the rays ended on something behind it.
  const std::vector<float> to_hit = distance_to(frame, occupied);
  for (Edge* e : {&walls, &furniture})
    e->cells.erase(std::remove_if(e->cells.begin(), e->cells.end(),
                                  [&](std::size_t i) { return to_hit[i] > config.fringe_width; }),
                   e->cells.end());
  // Walls joined to the structure, and faces of what stands free longer than furniture is (a
  // partition, a row of cabinets).
  for (const auto& [edge, min_length] :
       {std::make_pair(&walls, config.min_wall), std::make_pair(&furniture, config.min_free_standing)}) {
    for (double theta : wall_directions(walls, config, config.max_gap, min_piece)) {
      for (int side : {1, -1}) {
        const std::vector<Piece> pieces =
            pieces_of(edge_cells(*edge, theta, side), config.max_gap, min_piece);
        // A face's pieces share its offset; a face whose pieces add up to min_length is a wall.
        for (std::size_t i = 0; i < pieces.size();) {
          std::size_t j = i;
          double length = 0.0;
          for (; j < pieces.size() && pieces[j].offset == pieces[i].offset; ++j) length += pieces[j].length();
          if (length * res >= min_length)
            for (std::size_t k = i; k < j; ++k)
              out.push_back(wall_of(frame, theta, side, pieces[k].offset, pieces[k],
                                    static_cast<int>(out.size()), config.wall_height));
          i = j;
        }
      }
    }
  }
  return out;
}

}  // namespace tsgraphs::rooms
