// Office: rooms off one or more corridors (building_styles.hpp).
#include <algorithm>

#include "tsgraphs/generator/building_styles.hpp"

namespace tsgraphs::generator {
namespace {

constexpr double kCorridorMin = 1.2;  // m: corridor widths drawn from [1.2, 3.5] (the range)
constexpr double kCorridorMax = 3.5;
constexpr double kRoomMin = 2.5;    // m: a block is at least one room deep
constexpr double kBlockMax = 20.0;  // m: the deepest block (two rows of rooms)

enum class Layout { kDouble, kSingle, kBent, kBranch };

}  // namespace

void fill_office(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix) {
  const int first = static_cast<int>(plan->spaces.size());
  const double W = region.width(), H = region.depth();
  const Vec2 o = region.lo;
  const double cw = std::min(rng.uniform(kCorridorMin, kCorridorMax), H - kRoomMin);
  std::vector<Layout> layouts = {Layout::kSingle};
  if (H >= cw + 2 * kRoomMin) layouts.insert(layouts.end(), {Layout::kDouble, Layout::kDouble});
  if (H >= cw + 2 * kRoomMin && W >= cw + 2 * kRoomMin)
    layouts.insert(layouts.end(), {Layout::kBent, Layout::kBranch});
  const Layout layout = rng.pick(layouts);
  const auto P = [&](double x, double y) { return Vec2(o.x() + x, o.y() + y); };
  const auto corridor = [&](const std::string& name, double x0, double y0, double x1, double y1) {
    return plan->add_rect(prefix + name, SpaceKind::kCorridor, P(x0, y0), P(x1, y1));
  };
  // The south block's depth: a room or more, and the rest on the other side at least a room.
  const double d1 = std::min(rng.uniform(kRoomMin, std::max(kRoomMin, H - cw - kRoomMin)), kBlockMax);
  switch (layout) {
    case Layout::kSingle: {
      const int c = corridor("corridor", 0, H - cw, W, H);
      fill_block(plan, {P(0, 0), P(W, H - cw)}, Side::kNorth, c, rng, prefix);
      break;
    }
    case Layout::kDouble: {
      const int c = corridor("corridor", 0, d1, W, d1 + cw);
      fill_block(plan, {P(0, 0), P(W, d1)}, Side::kNorth, c, rng, prefix);
      fill_block(plan, {P(0, d1 + cw), P(W, H)}, Side::kSouth, c, rng, prefix);
      break;
    }
    case Layout::kBent: {
      // A leg along x to xb, then a leg along y (holding the corner) to the north facade.
      const double xb = rng.uniform(std::max(kRoomMin, W - cw - kBlockMax), W - cw - kRoomMin);
      const int h = corridor("corridor_a", 0, d1, xb, d1 + cw);
      const int v = corridor("corridor_b", xb, d1, xb + cw, H);
      plan->open_joints.push_back({h, v});
      fill_block(plan, {P(0, 0), P(xb + cw, d1)}, Side::kNorth, h, rng, prefix);
      fill_block(plan, {P(0, d1 + cw), P(xb, H)}, Side::kSouth, h, rng, prefix);
      fill_block(plan, {P(xb + cw, 0), P(W, H)}, Side::kWest, v, rng, prefix);
      break;
    }
    case Layout::kBranch: {
      // A main corridor the whole length and a branch off it to the north facade.
      const double cb = std::min(rng.uniform(kCorridorMin, kCorridorMax), W - 2 * kRoomMin);
      const double xb = rng.uniform(kRoomMin, W - cb - kRoomMin);
      const int m = corridor("corridor_main", 0, d1, W, d1 + cw);
      const int b = corridor("corridor_branch", xb, d1 + cw, xb + cb, H);
      plan->open_joints.push_back({m, b});
      fill_block(plan, {P(0, 0), P(W, d1)}, Side::kNorth, m, rng, prefix);
      fill_block(plan, {P(0, d1 + cw), P(xb, H)}, Side::kSouth, m, rng, prefix);
      fill_block(plan, {P(xb + cb, d1 + cw), P(W, H)}, Side::kSouth, m, rng, prefix);
      break;
    }
  }
  // One draw per statement (a call's argument order is unspecified): my first, as gcc drew it.
  const bool my = rng.chance(0.5);
  const bool mx = rng.chance(0.5);
  mirror_spaces(plan, first, region, mx, my);
}

}  // namespace tsgraphs::generator
