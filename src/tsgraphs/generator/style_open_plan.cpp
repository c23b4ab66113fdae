// Open plan: one large hall with meeting rooms off it (building_styles.hpp); its
// partitions, desks and pillars come with the furniture (furnishing.hpp).
#include <algorithm>

#include "tsgraphs/generator/building_styles.hpp"

namespace tsgraphs::generator {
namespace {

constexpr double kMeetingChance = 0.6;    // of a row of meeting rooms along one side
constexpr double kMeetingDepthMin = 3.0;  // m
constexpr double kMeetingDepthMax = 5.0;
constexpr double kHallMin = 10.0;  // m: what the hall keeps of the region's depth

}  // namespace

void fill_open_plan(FloorPlan* plan, const Region& region, Rng& rng, const std::string& prefix) {
  Region hall = region;
  const double d = rng.uniform(kMeetingDepthMin, kMeetingDepthMax);
  const bool meeting = rng.chance(kMeetingChance);
  const bool along_x = rng.chance(0.5);
  const bool far_side = rng.chance(0.5);
  Region rooms = region;
  Side side = Side::kSouth;
  if (meeting && along_x && region.depth() - d >= kHallMin) {
    if (far_side) {
      hall.hi.y() -= d;
      rooms.lo.y() = hall.hi.y();
      side = Side::kSouth;
    } else {
      hall.lo.y() += d;
      rooms.hi.y() = hall.lo.y();
      side = Side::kNorth;
    }
  } else if (meeting && !along_x && region.width() - d >= kHallMin) {
    if (far_side) {
      hall.hi.x() -= d;
      rooms.lo.x() = hall.hi.x();
      side = Side::kWest;
    } else {
      hall.lo.x() += d;
      rooms.hi.x() = hall.lo.x();
      side = Side::kEast;
    }
  }
  const int h = plan->add_rect(prefix + "hall", SpaceKind::kHall, hall.lo, hall.hi, Furnishing::kOpenPlan);
  if (hall.lo != region.lo || hall.hi != region.hi)
    fill_block(plan, rooms, side, h, rng, prefix + "meeting_");
}

}  // namespace tsgraphs::generator
