// The flush rule (width / direction / doorway) and the baseline's timer trigger.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tsgraphs/rooms/room_flush_trigger.hpp"
#include "tsgraphs/rooms/room_timer_trigger.hpp"

namespace tsgraphs::rooms {
namespace {

constexpr double kStep = 0.1;  // spacing of the constructed free-space nodes (m)

AisleMeasurement aisle(double width, double heading_deg) {
  AisleMeasurement a;
  a.valid = true;
  a.width = width;
  const double h = heading_deg * M_PI / 180.0;
  a.direction = Vec2(std::cos(h), std::sin(h));
  a.direction_defined = true;
  return a;
}

void add_grid(std::vector<Eigen::Vector3d>& out, double x0, double x1, double y0, double y1) {
  for (int i = 0; x0 + i * kStep <= x1 + 1e-9; ++i) {
    for (int j = 0; y0 + j * kStep <= y1 + 1e-9; ++j) out.emplace_back(x0 + i * kStep, y0 + j * kStep, 0.0);
  }
}

TEST(RoomFlushTrigger, WidthChangeOfHalfFlushesOnceConfirmedAndFivePercentDoesNot) {
  RoomFlushTrigger trigger;  // width_change_ratio 0.3, confirm_keyframes 2
  for (int k = 0; k < 5; ++k) EXPECT_EQ(trigger.update(aisle(2.0, 0.0), false), FlushReason::none);
  EXPECT_EQ(trigger.update(aisle(2.1, 0.0), false), FlushReason::none);  // +5 %
  EXPECT_EQ(trigger.segment_keyframes(), 6);
  EXPECT_DOUBLE_EQ(trigger.segment_median_width(), 2.0);
  EXPECT_EQ(trigger.update(aisle(3.0, 0.0), false), FlushReason::none);  // +50 %: held
  EXPECT_EQ(trigger.pending_keyframes(), 1);
  EXPECT_EQ(trigger.update(aisle(3.1, 0.0), false), FlushReason::width_change);  // confirmed
  EXPECT_EQ(trigger.starting_keyframes(), 2);  // both changed keyframes start the new segment...
  EXPECT_EQ(trigger.segment_keyframes(), 1);   // ...which is measured from the latest
  EXPECT_DOUBLE_EQ(trigger.segment_median_width(), 3.1);
  EXPECT_EQ(trigger.update(aisle(1.5, 0.0), false), FlushReason::none);  // -50 %
  EXPECT_EQ(trigger.update(aisle(1.5, 0.0), false), FlushReason::width_change);
}

TEST(RoomFlushTrigger, OneKeyframeBlipJoinsTheSegment) {
  RoomFlushTrigger trigger;
  for (int k = 0; k < 4; ++k) trigger.update(aisle(2.0, 0.0), false);
  EXPECT_EQ(trigger.update(aisle(1.0, 0.0), false), FlushReason::none);  // the map filling in, say
  EXPECT_EQ(trigger.pending_keyframes(), 1);
  EXPECT_EQ(trigger.update(aisle(2.0, 0.0), false), FlushReason::none);
  EXPECT_EQ(trigger.pending_keyframes(), 0);
  EXPECT_EQ(trigger.segment_keyframes(), 6);
}

TEST(RoomFlushTrigger, TurnOfNinetyDegreesFlushesAndTwentyDoesNot) {
  RoomFlushTrigger trigger;  // direction_change_deg 30
  for (int k = 0; k < 5; ++k) EXPECT_EQ(trigger.update(aisle(2.0, 0.0), false), FlushReason::none);
  EXPECT_EQ(trigger.update(aisle(2.0, 20.0), false), FlushReason::none);
  EXPECT_EQ(trigger.update(aisle(2.0, 180.0), false), FlushReason::none);  // the same axis, walked back
  EXPECT_EQ(trigger.update(aisle(2.0, 90.0), false), FlushReason::none);
  EXPECT_EQ(trigger.update(aisle(2.0, 90.0), false), FlushReason::direction_change);
  // A keyframe without a dominant direction (an open room) is not judged by its direction.
  AisleMeasurement open = aisle(2.0, 0.0);
  open.direction_defined = false;
  EXPECT_EQ(trigger.update(open, false), FlushReason::none);
  EXPECT_EQ(trigger.pending_keyframes(), 0);
}

TEST(RoomFlushTrigger, WidthsBothWiderThanAnAisleAreOneOpenSpace) {
  RoomFlushTrigger trigger;  // max_aisle_width 4 m
  for (int k = 0; k < 3; ++k) trigger.update(aisle(5.9, 0.0), false);
  // Standing where the cross-section reaches through a door: 40 % wider, still the room.
  for (int k = 0; k < 3; ++k) EXPECT_EQ(trigger.update(aisle(8.3, 0.0), false), FlushReason::none);
  EXPECT_EQ(trigger.pending_keyframes(), 0);
  // From the room into a 2 m corridor is a change.
  trigger.update(aisle(2.0, 0.0), false);
  EXPECT_EQ(trigger.update(aisle(2.0, 0.0), false), FlushReason::width_change);
}

TEST(RoomFlushTrigger, NarrowBlipBetweenTwoRoomsIsADoorway) {
  RoomFlushTrigger trigger;
  for (int k = 0; k < 3; ++k) trigger.update(aisle(6.0, 0.0), false);
  EXPECT_EQ(trigger.update(aisle(0.3, 0.0), false), FlushReason::none);  // in the door
  EXPECT_EQ(trigger.update(aisle(5.0, 0.0), false), FlushReason::doorway);
  EXPECT_EQ(trigger.segment_keyframes(), 1);
  // A blip of half the width (furniture near the robot) is not a doorway.
  for (int k = 0; k < 3; ++k) trigger.update(aisle(5.0, 0.0), false);
  EXPECT_EQ(trigger.update(aisle(2.5, 0.0), false), FlushReason::none);
  EXPECT_EQ(trigger.update(aisle(5.0, 0.0), false), FlushReason::none);
}

TEST(RoomFlushTrigger, TurningInARoomWiderThanAnAisleDoesNotFlush) {
  RoomFlushTrigger trigger;  // max_aisle_width 4 m
  for (int k = 0; k < 3; ++k) trigger.update(aisle(5.0, 0.0), false);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(trigger.update(aisle(5.0, 90.0), false), FlushReason::none);
}

TEST(RoomFlushTrigger, DoorwayFlushesAndInvalidMeasurementsAreIgnored) {
  RoomFlushTrigger trigger;
  EXPECT_EQ(trigger.update(aisle(2.0, 0.0), true), FlushReason::none);  // nothing accumulated yet
  EXPECT_EQ(trigger.update(aisle(2.0, 0.0), false), FlushReason::none);
  EXPECT_EQ(trigger.update(AisleMeasurement{}, false), FlushReason::none);
  EXPECT_EQ(trigger.segment_keyframes(), 2);
  EXPECT_EQ(trigger.update(aisle(2.0, 0.0), true), FlushReason::doorway);
  EXPECT_EQ(trigger.segment_keyframes(), 1);
}

TEST(MeasureAisle, CorridorWidthAndDirection) {
  std::vector<Eigen::Vector3d> cluster;
  add_grid(cluster, 0.0, 10.0, 0.0, 2.0);
  const AisleMeasurement a = measure_aisle(cluster, Eigen::Vector3d(5.0, 1.0, 0.0));
  ASSERT_TRUE(a.valid);
  EXPECT_TRUE(a.direction_defined);
  EXPECT_NEAR(a.width, 2.0, 1e-6);
  EXPECT_GT(std::abs(a.direction.x()), 0.999);
  // An open square hall has no dominant direction.
  std::vector<Eigen::Vector3d> hall;
  add_grid(hall, 0.0, 8.0, 0.0, 8.0);
  EXPECT_FALSE(measure_aisle(hall, Eigen::Vector3d(4.0, 4.0, 0.0)).direction_defined);
  // Nobody near the robot: no measurement.
  EXPECT_FALSE(measure_aisle(cluster, Eigen::Vector3d(30.0, 1.0, 0.0)).valid);
}

TEST(MeasureAisle, WidthOfARoomIsItsShorterSideWhicheverItsAxis) {
  std::vector<Eigen::Vector3d> room;
  add_grid(room, 0.0, 7.0, 0.0, 5.0);
  for (const Eigen::Vector3d& robot :
       {Eigen::Vector3d(2.0, 2.5, 0.0), Eigen::Vector3d(3.5, 1.0, 0.0), Eigen::Vector3d(5.5, 3.5, 0.0)}) {
    const AisleMeasurement a = measure_aisle(room, robot);
    ASSERT_TRUE(a.valid);
    EXPECT_NEAR(a.width, 5.0, 0.25);  // near a corner a diagonal is a little shorter; never the 7 m side
  }
}

TEST(MeasureAisle, WalkFromCorridorIntoWiderHallFlushesOnceAtTheHall) {
  // Corridor 2 m wide (x in [0, 10]) opening into a hall 3 m wide (x in [10, 16]).
  std::vector<Eigen::Vector3d> cluster;
  add_grid(cluster, 0.0, 9.9, 0.0, 2.0);
  add_grid(cluster, 10.0, 16.0, -0.5, 2.5);
  RoomFlushTrigger trigger;
  std::vector<double> flushes;
  for (int x = 1; x <= 15; ++x) {
    const FlushReason r = trigger.update(measure_aisle(cluster, Eigen::Vector3d(x, 1.0, 0.0)), false);
    if (r != FlushReason::none) {
      EXPECT_EQ(r, FlushReason::width_change);
      flushes.push_back(x);
    }
  }
  ASSERT_EQ(flushes.size(), 1u);
  EXPECT_GE(flushes[0], 10.0);
  EXPECT_LE(flushes[0], 11.0);
}

TEST(MeasureAisle, WalkRoundACornerFlushesAtTheCorner) {
  // L: corridor along x (y in [0, 2], x in [0, 10]) then along y (x in [8, 10], y up to 14).
  std::vector<Eigen::Vector3d> cluster;
  add_grid(cluster, 0.0, 10.0, 0.0, 2.0);
  add_grid(cluster, 8.0, 10.0, 2.1, 14.0);
  RoomFlushTrigger trigger;
  int flushes_before_corner = 0;
  int flushes_after_corner = 0;
  for (int x = 1; x <= 6; ++x) {
    if (trigger.update(measure_aisle(cluster, Eigen::Vector3d(x, 1.0, 0.0)), false) != FlushReason::none) {
      ++flushes_before_corner;
    }
  }
  for (int y = 1; y <= 13; ++y) {
    if (trigger.update(measure_aisle(cluster, Eigen::Vector3d(9.0, y, 0.0)), false) != FlushReason::none) {
      ++flushes_after_corner;
    }
  }
  EXPECT_EQ(flushes_before_corner, 0);
  EXPECT_GE(flushes_after_corner, 1);
  // The new segment runs along y.
  const AisleMeasurement end = measure_aisle(cluster, Eigen::Vector3d(9.0, 12.0, 0.0));
  EXPECT_GT(std::abs(end.direction.y()), 0.999);
  EXPECT_NEAR(end.width, 2.0, 1e-6);
}

TEST(RoomTimerTrigger, FiresEverySecond) {
  RoomTimerTrigger timer;
  std::vector<int> fired;
  for (int k = 0; k <= 50; ++k) {
    if (timer.update(k / 10.0)) fired.push_back(k);
  }
  EXPECT_EQ(fired, (std::vector<int>{10, 20, 30, 40, 50}));
  // Irregular keyframes: a long gap fires once, and the grid stays on whole seconds.
  RoomTimerTrigger gaps;
  EXPECT_FALSE(gaps.update(0.0));
  EXPECT_FALSE(gaps.update(0.5));
  EXPECT_TRUE(gaps.update(3.7));
  EXPECT_TRUE(gaps.update(4.0));
  EXPECT_FALSE(gaps.update(4.8));
  EXPECT_TRUE(gaps.update(5.0));
}

}  // namespace
}  // namespace tsgraphs::rooms
