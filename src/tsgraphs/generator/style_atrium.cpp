// Atrium: a corridor ring round one or two voids, rooms off it (building_styles.hpp).
#include <algorithm>

#include "tsgraphs/generator/building_styles.hpp"

namespace tsgraphs::generator {
namespace {

constexpr double kRingMin = 1.8;  // m: ring corridor widths
constexpr double kRingMax = 3.5;
constexpr double kRoomDepthMin = 3.0;  // m: rooms off the ring
constexpr double kRoomDepthMax = 8.0;
constexpr double kVoidMin = 3.0;    // m: the smallest side of a void
constexpr double kBridgeMin = 1.5;  // m: a bridge between two voids
constexpr double kBridgeMax = 3.0;
constexpr double kTwoVoidChance = 0.35;
constexpr double kLongSideRooms = 0.85;  // chance of rooms along each long side
constexpr double kShortSideRooms = 0.5;  // along each short side

}  // namespace

void fill_atrium(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix) {
  const double W = region.width(), H = region.depth();
  const double cw = rng.uniform(kRingMin, kRingMax);
  // Room depths per side (0: the ring runs along the facade there), shrunk until a void fits.
  double ds = rng.chance(kLongSideRooms) ? rng.uniform(kRoomDepthMin, kRoomDepthMax) : 0.0;
  double dn = rng.chance(kLongSideRooms) ? rng.uniform(kRoomDepthMin, kRoomDepthMax) : 0.0;
  double dw = rng.chance(kShortSideRooms) ? rng.uniform(kRoomDepthMin, kRoomDepthMax) : 0.0;
  double de = rng.chance(kShortSideRooms) ? rng.uniform(kRoomDepthMin, kRoomDepthMax) : 0.0;
  for (double* d : {&ds, &dn}) {
    if (H - ds - dn - 2 * cw < kVoidMin) *d = std::max(0.0, std::min(*d, 0.5 * (H - 2 * cw - kVoidMin)));
    if (*d > 0 && *d < kRoomDepthMin) *d = 0.0;
  }
  for (double* d : {&dw, &de}) {
    if (W - dw - de - 2 * cw < kVoidMin) *d = std::max(0.0, std::min(*d, 0.5 * (W - 2 * cw - kVoidMin)));
    if (*d > 0 && *d < kRoomDepthMin) *d = 0.0;
  }
  const double x0 = region.lo.x(), y0 = region.lo.y(), x1 = region.hi.x(), y1 = region.hi.y();
  const double xw = x0 + dw, xe = x1 - de, ys = y0 + ds, yn = y1 - dn;
  const int s = plan->add_rect(prefix + "corridor_south", SpaceKind::kCorridor, {xw, ys}, {xe, ys + cw});
  const int n = plan->add_rect(prefix + "corridor_north", SpaceKind::kCorridor, {xw, yn - cw}, {xe, yn});
  const int w =
      plan->add_rect(prefix + "corridor_west", SpaceKind::kCorridor, {xw, ys + cw}, {xw + cw, yn - cw});
  const int e =
      plan->add_rect(prefix + "corridor_east", SpaceKind::kCorridor, {xe - cw, ys + cw}, {xe, yn - cw});
  plan->open_joints.insert(plan->open_joints.end(), {{s, w}, {s, e}, {n, w}, {n, e}});
  const double vx0 = xw + cw, vx1 = xe - cw, vy0 = ys + cw, vy1 = yn - cw;
  const double cb = rng.uniform(kBridgeMin, kBridgeMax);
  if (vx1 - vx0 >= 2 * kVoidMin + cb && rng.chance(kTwoVoidChance)) {
    const double xm = rng.uniform(vx0 + kVoidMin, vx1 - kVoidMin - cb);
    const int b = plan->add_rect(prefix + "bridge", SpaceKind::kCorridor, {xm, vy0}, {xm + cb, vy1});
    plan->open_joints.insert(plan->open_joints.end(), {{b, s}, {b, n}});
    plan->add_rect(prefix + "void_west", SpaceKind::kVoid, {vx0, vy0}, {xm, vy1});
    plan->add_rect(prefix + "void_east", SpaceKind::kVoid, {xm + cb, vy0}, {vx1, vy1});
  } else {
    plan->add_rect(prefix + "void", SpaceKind::kVoid, {vx0, vy0}, {vx1, vy1});
  }
  if (ds > 0) fill_block(plan, {{x0, y0}, {x1, ys}}, Side::kNorth, s, rng, prefix);
  if (dn > 0) fill_block(plan, {{x0, yn}, {x1, y1}}, Side::kSouth, n, rng, prefix);
  if (dw > 0) fill_block(plan, {{x0, ys}, {xw, yn}}, Side::kEast, w, rng, prefix);
  if (de > 0) fill_block(plan, {{xe, ys}, {x1, yn}}, Side::kWest, e, rng, prefix);
}

}  // namespace tsgraphs::generator
