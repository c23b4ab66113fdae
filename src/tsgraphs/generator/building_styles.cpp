#include "tsgraphs/generator/building_styles.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace tsgraphs::generator {
namespace {

constexpr double kRoomMin = 2.5;        // m: the narrowest room (issue's range 2.5-12 m)
constexpr double kRoomMax = 12.0;       // m: the widest and deepest room
constexpr double kTwoRowsAbove = 7.0;   // m: a block this deep may hold two rows of rooms
constexpr double kTwoRowChance = 0.35;  // of such a block
constexpr double kSplitJitter = 0.35;   // relative spread of the pieces of a split length
// generate --realistic: a block's front row as small offices.
constexpr double kSmallOfficeChance = 0.5;   // of a block's front row being small offices
constexpr double kSmallOfficeAreaMin = 6.0;  // m^2 of floor (the ground truth's, inside the walls)
constexpr double kSmallOfficeAreaMax = 12.0;
constexpr double kSmallOfficeDepthMax = 4.0;  // m: deeper, a room is no small office
constexpr double kWallsMax = 0.25;  // m two half walls take from a room's side at most (facade + interior)...
constexpr double kWallsMin = 0.1;   // ...and at least

/// The depth of a block's front row of small offices, or 0 when the block holds none.
double small_office_depth(double depth, Rng& rng) {
  if (depth < kRoomMin) return 0.0;
  if (depth <= kSmallOfficeDepthMax) return depth;
  if (depth < 2.0 * kRoomMin) return 0.0;  // the back row would be too shallow
  return rng.uniform(kRoomMin, std::min(kSmallOfficeDepthMax, depth - kRoomMin));
}

}  // namespace

std::vector<double> split_length(double length, double lo, double hi, Rng& rng) {
  if (length < 2.0 * lo) return {length};
  const int kmin = std::max(1, static_cast<int>(std::ceil(length / hi - 1e-9)));
  const int kmax = std::max(kmin, static_cast<int>(std::floor(length / lo + 1e-9)));
  const int k = rng.integer(kmin, kmax);
  std::vector<double> w(k);
  for (double& x : w) x = rng.uniform(1.0 - kSplitJitter, 1.0 + kSplitJitter);
  const double sum = std::accumulate(w.begin(), w.end(), 0.0);
  for (double& x : w) x *= length / sum;
  // Pull pieces back into [lo, hi], passing the difference to their neighbours.
  for (int pass = 0; pass < 4 * k; ++pass) {
    bool ok = true;
    for (int i = 0; i < k; ++i) {
      const double over = std::max(w[i] - hi, 0.0), under = std::max(lo - w[i], 0.0);
      if (over == 0.0 && under == 0.0) continue;
      ok = false;
      const int j = i + 1 < k ? i + 1 : i - 1;
      w[i] += under - over;
      w[j] -= under - over;
    }
    if (ok) return w;
  }
  return std::vector<double>(k, length / k);
}

DoorSpec random_door(int a, int b, Rng& rng) {
  const double u = rng.unit();
  const double width = u < 0.7   ? rng.uniform(0.85, 1.2)
                       : u < 0.9 ? rng.uniform(1.2, 1.6)
                                 : rng.uniform(1.6, 2.0);
  return {a, b, width, rng.uniform(0.15, 0.85)};
}

std::vector<int> fill_block(FloorPlan* plan, const Region& block, Side side, int corridor, Rng& rng,
                            const std::string& prefix, Furnishing furnishing) {
  const bool along_x = side == Side::kSouth || side == Side::kNorth;
  const double length = along_x ? block.width() : block.depth();
  const double depth = along_x ? block.depth() : block.width();
  if (length < 1e-6 || depth < 1e-6) return {};
  // World rectangle of [u0, u1] along the side and [v0, v1] away from it.
  const auto rect = [&](double u0, double u1, double v0, double v1) {
    switch (side) {
      case Side::kSouth:
        return Region{{block.lo.x() + u0, block.lo.y() + v0}, {block.lo.x() + u1, block.lo.y() + v1}};
      case Side::kNorth:
        return Region{{block.lo.x() + u0, block.hi.y() - v1}, {block.lo.x() + u1, block.hi.y() - v0}};
      case Side::kWest:
        return Region{{block.lo.x() + v0, block.lo.y() + u0}, {block.lo.x() + v1, block.lo.y() + u1}};
      case Side::kEast:
        break;
    }
    return Region{{block.hi.x() - v1, block.lo.y() + u0}, {block.hi.x() - v0, block.lo.y() + u1}};
  };
  std::vector<double> rows = {depth};
  const double small =
      plan->realistic && rng.chance(kSmallOfficeChance) ? small_office_depth(depth, rng) : 0.0;
  if (small > 0.0) {
    rows = {small};
    if (depth - small > 1e-9) rows.push_back(depth - small);
  } else if (depth > kRoomMax || (depth > kTwoRowsAbove && rng.chance(kTwoRowChance))) {
    const double front = std::clamp(rng.uniform(kRoomMin, depth - kRoomMin), kRoomMin, kRoomMax);
    rows = {front, depth - front};
  }
  std::vector<int> out;
  std::vector<std::pair<double, double>> front_spans;
  std::vector<int> front_rooms;
  double v = 0.0;
  for (std::size_t row = 0; row < rows.size(); ++row) {
    // Each row draws its own range within [2.5, 12] m, so blocks of small and of large rooms both occur.
    double lo = rng.uniform(kRoomMin, 4.5), hi = std::min(kRoomMax, rng.uniform(lo + 2.5, kRoomMax));
    if (row == 0 && small > 0.0) {  // widths that give 6-12 m^2 inside the walls
      lo = std::max(kRoomMin, kSmallOfficeAreaMin / (rows[0] - kWallsMax) + kWallsMax);
      hi = std::max(lo, kSmallOfficeAreaMax / (rows[0] - kWallsMin) + kWallsMin);
    }
    double u = 0.0;
    for (double w : split_length(length, lo, hi, rng)) {
      const Region r = rect(u, u + w, v, v + rows[row]);
      const int id = plan->add_rect(prefix + "room" + std::to_string(plan->spaces.size()), SpaceKind::kRoom,
                                    r.lo, r.hi, furnishing);
      out.push_back(id);
      if (row == 0) {
        if (corridor >= 0) plan->doors.push_back(random_door(id, corridor, rng));
        front_spans.push_back({u, u + w});
        front_rooms.push_back(id);
      } else {
        // A back room opens into the front room it overlaps most.
        int best = -1;
        double overlap = 0.0;
        for (std::size_t k = 0; k < front_spans.size(); ++k) {
          const double o = std::min(u + w, front_spans[k].second) - std::max(u, front_spans[k].first);
          if (o > overlap) {
            overlap = o;
            best = front_rooms[k];
          }
        }
        if (best >= 0) plan->doors.push_back(random_door(id, best, rng));
      }
      u += w;
    }
    v += rows[row];
  }
  return out;
}

void mirror_spaces(FloorPlan* plan, int first, const Region& region, bool mx, bool my) {
  if (!mx && !my) return;
  for (std::size_t i = static_cast<std::size_t>(first); i < plan->spaces.size(); ++i) {
    Polygon2& o = plan->spaces[i].outline;
    for (Vec2& p : o) {
      if (mx) p.x() = region.lo.x() + region.hi.x() - p.x();
      if (my) p.y() = region.lo.y() + region.hi.y() - p.y();
    }
    if (signed_area(o) < 0) std::reverse(o.begin(), o.end());
  }
}

Polygon2 clip_half_plane(const Polygon2& poly, const Vec2& at, const Vec2& n) {
  Polygon2 out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    const double da = n.dot(a - at), db = n.dot(b - at);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  // Drop repeated points (a vertex on the line).
  Polygon2 clean;
  for (const Vec2& p : out) {
    if (clean.empty() || (clean.back() - p).norm() > 1e-9) clean.push_back(p);
  }
  while (clean.size() > 1 && (clean.back() - clean.front()).norm() <= 1e-9) clean.pop_back();
  return clean;
}

Vec2 minimum_region(const std::string& style) {
  if (style == "office") return {12.0, 8.0};
  if (style == "atrium") return {16.0, 14.0};
  if (style == "library") return {16.0, 12.0};
  if (style == "open_plan") return {16.0, 12.0};
  if (style == "irregular") return {14.0, 14.0};
  throw std::invalid_argument("no such building style: " + style);
}

}  // namespace tsgraphs::generator
