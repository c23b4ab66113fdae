// Irregular: a diagonal corridor, a pentagonal ring, or rooms merged into L and T shapes
// (building_styles.hpp).
#include <algorithm>
#include <cmath>

#include "tsgraphs/generator/building_styles.hpp"

namespace tsgraphs::generator {
namespace {

constexpr double kDiagonalMinDeg = 30.0;  // the corridor's angle to the facade (the 30-60 degrees)
constexpr double kDiagonalMaxDeg = 60.0;
constexpr double kCorridorMin = 1.5;  // m: corridor widths of this style
constexpr double kCorridorMax = 3.0;
constexpr double kCutMin = 3.0;  // m between the walls that cut a side into rooms
constexpr double kCutMax = 7.0;
constexpr double kRoomAreaMin = 5.0;   // m^2: a smaller piece joins its neighbour
constexpr double kCornerGapMin = 2.8;  // m from the pentagon's corners to the facade
constexpr double kCornerGapMax = 4.0;
constexpr double kCoreMin = 2.2;           // m: the central room's smallest radius
constexpr double kSplitCornerArea = 55.0;  // m^2: a corner room this large is cut in two
constexpr double kRowMin = 2.5;            // m: depth of a row of rooms
constexpr double kMergeChance = 0.55;      // of a front room taking in the room behind it
constexpr double kMergeStep = 1.0;         // m: the least step in an L or T room's outline

void fill_diagonal(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix) {
  // One draw per statement (the operands' order is unspecified): the angle, then its sign.
  const double degrees = rng.uniform(kDiagonalMinDeg, kDiagonalMaxDeg);
  const double a = degrees * M_PI / 180.0 * (rng.chance(0.5) ? 1.0 : -1.0);
  const double cw = rng.uniform(kCorridorMin, kCorridorMax);
  const Vec2 d(std::cos(a), std::sin(a)), n(-d.y(), d.x());
  const Vec2 c = 0.5 * (region.lo + region.hi) + rng.uniform(-0.15, 0.15) * region.width() * Vec2::UnitX();
  const Polygon2 rect = {
      region.lo, {region.hi.x(), region.lo.y()}, region.hi, {region.lo.x(), region.hi.y()}};
  const Polygon2 strip = clip_half_plane(clip_half_plane(rect, c - 0.5 * cw * n, n), c + 0.5 * cw * n, -n);
  const int corridor = plan->add(prefix + "corridor_diagonal", SpaceKind::kCorridor, strip);
  for (const double sign : {1.0, -1.0}) {
    const Polygon2 side = clip_half_plane(rect, c + sign * 0.5 * cw * n, sign * n);
    if (side.size() < 3 || area(side) < kRoomAreaMin) continue;
    double x0 = side[0].x(), x1 = side[0].x();
    for (const Vec2& p : side) {
      x0 = std::min(x0, p.x());
      x1 = std::max(x1, p.x());
    }
    // Walls straight across (x = const): they meet the corridor at its angle. A piece too
    // small to be a room loses one of its walls to its neighbour.
    std::vector<double> xs = {x0};
    for (double w : split_length(x1 - x0, kCutMin, kCutMax, rng)) xs.push_back(xs.back() + w);
    xs.back() = x1;
    const auto piece = [&](double lo, double hi) {
      return clip_half_plane(clip_half_plane(side, {lo, 0.0}, Vec2::UnitX()), {hi, 0.0}, -Vec2::UnitX());
    };
    for (bool changed = true; changed && xs.size() > 2;) {
      changed = false;
      for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
        const Polygon2 p = piece(xs[k], xs[k + 1]);
        if (p.size() >= 3 && area(p) >= kRoomAreaMin) continue;
        xs.erase(xs.begin() + static_cast<long>(k + 2 < xs.size() ? k + 1 : k));
        changed = true;
        break;
      }
    }
    for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
      const Polygon2 p = piece(xs[k], xs[k + 1]);
      if (p.size() < 3 || area(p) < 1e-6) continue;
      const int room = plan->add(prefix + "room" + std::to_string(plan->spaces.size()), SpaceKind::kRoom, p,
                                 Furnishing::kOffice);
      plan->doors.push_back(random_door(room, corridor, rng));
    }
  }
}

void fill_pentagon(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix) {
  const Vec2 c = 0.5 * (region.lo + region.hi);
  const double r_out =
      0.5 * std::min(region.width(), region.depth()) - rng.uniform(kCornerGapMin, kCornerGapMax);
  double cw = rng.uniform(kCorridorMin, kCorridorMax);
  const double apothem = std::cos(M_PI / 5.0);
  double r_in = r_out - cw / apothem;
  if (r_in < kCoreMin) {
    r_in = kCoreMin;
    cw = (r_out - r_in) * apothem;
  }
  const double phi = rng.uniform(0.0, 2.0 * M_PI / 5.0);
  Polygon2 outer(5), inner(5);
  for (int k = 0; k < 5; ++k) {
    const Vec2 u(std::cos(phi + 2.0 * M_PI * k / 5.0), std::sin(phi + 2.0 * M_PI * k / 5.0));
    outer[k] = c + r_out * u;
    inner[k] = c + r_in * u;
  }
  const int core = plan->add(prefix + "room_core", SpaceKind::kRoom, inner, Furnishing::kOffice);
  std::vector<int> ring(5);
  for (int k = 0; k < 5; ++k) {
    ring[k] = plan->add(prefix + "corridor_" + std::to_string(k), SpaceKind::kCorridor,
                        {inner[k], inner[(k + 1) % 5], outer[(k + 1) % 5], outer[k]});
  }
  for (int k = 0; k < 5; ++k) plan->open_joints.push_back({ring[k], ring[(k + 1) % 5]});
  plan->doors.push_back(random_door(core, ring[rng.integer(0, 4)], rng));
  // The corners: from each outer vertex a wall straight out to the facade.
  const double W = region.width(), H = region.depth();
  const auto perimeter = [&](const Vec2& p) {  // counter-clockwise from the lower left corner
    if (std::abs(p.y() - region.lo.y()) < 1e-9) return p.x() - region.lo.x();
    if (std::abs(p.x() - region.hi.x()) < 1e-9) return W + (p.y() - region.lo.y());
    if (std::abs(p.y() - region.hi.y()) < 1e-9) return W + H + (region.hi.x() - p.x());
    return 2 * W + H + (region.hi.y() - p.y());
  };
  const Vec2 corners[4] = {
      region.lo, {region.hi.x(), region.lo.y()}, region.hi, {region.lo.x(), region.hi.y()}};
  const double corner_s[4] = {0.0, W, W + H, 2 * W + H};
  const auto hit = [&](const Vec2& from) {
    const Vec2 dir = (from - c).normalized();
    double t = 1e18;
    if (dir.x() > 1e-12) t = std::min(t, (region.hi.x() - c.x()) / dir.x());
    if (dir.x() < -1e-12) t = std::min(t, (region.lo.x() - c.x()) / dir.x());
    if (dir.y() > 1e-12) t = std::min(t, (region.hi.y() - c.y()) / dir.y());
    if (dir.y() < -1e-12) t = std::min(t, (region.lo.y() - c.y()) / dir.y());
    Vec2 p = c + t * dir;
    p = p.cwiseMax(region.lo).cwiseMin(region.hi);
    return p;
  };
  const auto corner_room = [&](const Vec2& v0, const Vec2& v1, int corridor) {
    const Vec2 h0 = hit(v0), h1 = hit(v1);
    Polygon2 poly = {v0, h0};
    double s0 = perimeter(h0), s1 = perimeter(h1);
    if (s1 <= s0) s1 += 2 * (W + H);
    for (int lap = 0; lap < 2; ++lap) {
      for (int k = 0; k < 4; ++k) {
        const double s = corner_s[k] + lap * 2 * (W + H);
        if (s > s0 + 1e-9 && s < s1 - 1e-9) poly.push_back(corners[k]);
      }
    }
    poly.push_back(h1);
    poly.push_back(v1);
    const int room = plan->add(prefix + "room" + std::to_string(plan->spaces.size()), SpaceKind::kRoom, poly,
                               Furnishing::kOffice);
    plan->doors.push_back(random_door(room, corridor, rng));
    return poly;
  };
  for (int k = 0; k < 5; ++k) {
    const Vec2 v0 = outer[k], v1 = outer[(k + 1) % 5];
    const Vec2 mid = 0.5 * (v0 + v1);
    // Estimate the corner's area from the whole, then cut large ones at the edge's middle.
    Polygon2 whole = {v0, hit(v0), hit(v1), v1};
    if (area(whole) > kSplitCornerArea) {
      corner_room(v0, mid, ring[k]);
      corner_room(mid, v1, ring[k]);
    } else {
      corner_room(v0, v1, ring[k]);
    }
  }
}

void fill_merged_rooms(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix) {
  const double W = region.width(), H = region.depth();
  const double cw = std::min(rng.uniform(kCorridorMin, kCorridorMax), H - 4 * kRowMin);
  const double d1 = 0.5 * (H - cw) + rng.uniform(-0.1, 0.1) * (H - cw);
  const double x0 = region.lo.x(), y0 = region.lo.y();
  const int corridor =
      plan->add_rect(prefix + "corridor", SpaceKind::kCorridor, {x0, y0 + d1}, {x0 + W, y0 + d1 + cw});
  // Each side: a front row on the corridor and a back row, cut independently.
  for (const bool south : {true, false}) {
    const double depth = south ? d1 : H - d1 - cw;
    const double front = rng.uniform(kRowMin, depth - kRowMin);
    // y ranges of the two rows, the front one against the corridor.
    const double fy0 = south ? y0 + d1 - front : y0 + d1 + cw, fy1 = fy0 + front;
    const double by0 = south ? y0 : fy1, by1 = south ? fy0 : y0 + H;
    const auto cuts = [&](double lo, double hi) {
      std::vector<double> xs = {x0};
      for (double w : split_length(W, lo, hi, rng)) xs.push_back(xs.back() + w);
      xs.back() = x0 + W;
      return xs;
    };
    const std::vector<double> fx = cuts(kRowMin, 6.0), bx = cuts(3.0, 8.0);
    std::vector<bool> back_taken(bx.size() - 1, false);
    for (std::size_t i = 0; i + 1 < fx.size(); ++i) {
      // Take in the back room overlapping most, when the steps of the outline are not slivers.
      int best = -1;
      double overlap = 0.0;
      for (std::size_t j = 0; j + 1 < bx.size(); ++j) {
        const double o = std::min(fx[i + 1], bx[j + 1]) - std::max(fx[i], bx[j]);
        const double step0 = std::abs(fx[i] - bx[j]), step1 = std::abs(fx[i + 1] - bx[j + 1]);
        const bool clean = (step0 < 1e-9 || step0 >= kMergeStep) && (step1 < 1e-9 || step1 >= kMergeStep);
        if (!back_taken[j] && clean && o > overlap) {
          overlap = o;
          best = static_cast<int>(j);
        }
      }
      int room;
      if (best >= 0 && overlap >= kMergeStep && rng.chance(kMergeChance)) {
        back_taken[best] = true;
        const Polygon2 outline =
            south ? stacked_outline(bx[best], bx[best + 1], by0, by1, fx[i], fx[i + 1], fy1)
                  : stacked_outline(fx[i], fx[i + 1], fy0, fy1, bx[best], bx[best + 1], by1);
        room = plan->add(prefix + "room" + std::to_string(plan->spaces.size()), SpaceKind::kRoom, outline,
                         Furnishing::kOffice);
      } else {
        room = plan->add_rect(prefix + "room" + std::to_string(plan->spaces.size()), SpaceKind::kRoom,
                              {fx[i], fy0}, {fx[i + 1], fy1}, Furnishing::kOffice);
      }
      plan->doors.push_back(random_door(room, corridor, rng));
    }
    for (std::size_t j = 0; j + 1 < bx.size(); ++j) {
      if (!back_taken[j])
        plan->add_rect(prefix + "room" + std::to_string(plan->spaces.size()), SpaceKind::kRoom, {bx[j], by0},
                       {bx[j + 1], by1}, Furnishing::kOffice);
    }
  }
}

}  // namespace

void fill_irregular(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix,
                    IrregularVariant variant) {
  if (variant == IrregularVariant::kAny) {
    const double u = rng.unit();
    variant = u < 0.4    ? IrregularVariant::kDiagonal
              : u < 0.75 ? IrregularVariant::kPentagon
                         : IrregularVariant::kMergedRooms;
  }
  switch (variant) {
    case IrregularVariant::kDiagonal:
      fill_diagonal(plan, region, rng, prefix);
      break;
    case IrregularVariant::kPentagon:
      fill_pentagon(plan, region, rng, prefix);
      break;
    case IrregularVariant::kMergedRooms:
    case IrregularVariant::kAny:
      fill_merged_rooms(plan, region, rng, prefix);
      break;
  }
}

}  // namespace tsgraphs::generator
