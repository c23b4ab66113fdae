// Library: halls of free-standing shelves off a corridor that is narrow, then wide
// (building_styles.hpp).
#include <algorithm>

#include "tsgraphs/generator/building_styles.hpp"

namespace tsgraphs::generator {
namespace {

constexpr double kNarrowMin = 1.2;  // m: the narrow part of the corridor
constexpr double kNarrowMax = 1.8;
constexpr double kWideMin = 2.5;  // m: its wide part
constexpr double kWideMax = 4.0;
constexpr double kHallMin = 6.0;            // m: the smallest hall side
constexpr double kHallMax = 18.0;           // m: halls wider than this are split
constexpr double kReadingRoomChance = 0.5;  // of a row of small rooms along the far facade
constexpr double kReadingDepthMin = 3.0;
constexpr double kReadingDepthMax = 5.0;
constexpr double kSecondDoorChance = 0.5;  // of a hall having two doors onto the corridor

}  // namespace

void fill_library(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix) {
  const int first = static_cast<int>(plan->spaces.size());
  const double W = region.width(), H = region.depth();
  const Vec2 o = region.lo;
  const auto P = [&](double x, double y) { return Vec2(o.x() + x, o.y() + y); };
  const double cn = rng.uniform(kNarrowMin, kNarrowMax);
  const double cwide = std::min(rng.uniform(kWideMin, kWideMax), H - kHallMin);
  const double xs = std::clamp(rng.uniform(0.3, 0.6) * W, kHallMin, W - kHallMin);
  const int narrow = plan->add_rect(prefix + "corridor_narrow", SpaceKind::kCorridor, P(0, 0), P(xs, cn));
  const int wide = plan->add_rect(prefix + "corridor_wide", SpaceKind::kCorridor, P(xs, 0), P(W, cwide));
  plan->open_joints.push_back({narrow, wide});
  double top = H;
  if (H - cwide - kReadingDepthMax >= kHallMin && rng.chance(kReadingRoomChance)) {
    const double d = rng.uniform(kReadingDepthMin, kReadingDepthMax);
    top = H - d;
    fill_block(plan, {P(0, top), P(W, H)}, Side::kSouth, -1, rng, prefix + "reading_");
  }
  // Halls over each part of the corridor, entered from it.
  const auto halls = [&](double x0, double x1, double y, int corridor) {
    double x = x0;
    for (double w : split_length(x1 - x0, kHallMin, kHallMax, rng)) {
      const int h = plan->add_rect(prefix + "hall" + std::to_string(plan->spaces.size()), SpaceKind::kHall,
                                   P(x, y), P(x + w, top), Furnishing::kShelves);
      plan->doors.push_back(random_door(h, corridor, rng));
      if (rng.chance(kSecondDoorChance)) plan->doors.push_back(random_door(h, corridor, rng));
      x += w;
    }
  };
  halls(0, xs, cn, narrow);
  halls(xs, W, cwide, wide);
  // One draw per statement (a call's argument order is unspecified): my first, as gcc drew it.
  const bool my = rng.chance(0.5);
  const bool mx = rng.chance(0.5);
  mirror_spaces(plan, first, region, mx, my);
}

}  // namespace tsgraphs::generator
