// Room figures of docs/metrics.md: consistency across two laps, and detected rooms against
// ground-truth rooms (rooms_events.jsonl itself: test_io_run_folder.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "tsgraphs/eval/room_metrics.hpp"

using namespace tsgraphs;
using namespace tsgraphs::eval;

namespace {

// Axis-aligned footprint [x0, x1] x [y0, y1].
OrientedRect box(double x0, double y0, double x1, double y1) {
  OrientedRect r;
  r.center = Vec2(0.5 * (x0 + x1), 0.5 * (y0 + y1));
  r.size = Vec2(x1 - x0, y1 - y0);
  return r;
}

Polygon2 box_polygon(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

io::RoomEvent event(int lap, int level, const OrientedRect& rect, bool is_new = true) {
  io::RoomEvent e;
  e.lap = lap;
  e.level = level;
  e.rect = rect;
  e.center = rect.center;
  e.is_new = is_new;
  return e;
}

io::RoomTruth truth_room(const std::string& name, const std::string& level, const Polygon2& polygon) {
  io::RoomTruth t;
  t.name = name;
  t.level = level;
  t.polygon = polygon;
  return t;
}

// An L: the 6 x 2 foot along x and the 2 x 6 leg along y, area 20; the notch is [2,6] x [2,6].
const Polygon2 kL = {{0, 0}, {6, 0}, {6, 2}, {2, 2}, {2, 6}, {0, 6}};

}  // namespace

// ---- consistency ------------------------------------------------------------------------------

TEST(RoomConsistency, CountsPairsOfLapOneAndLapTwoRooms) {
  // Lap 1: A, B and C (4 x 4 each; B and C side by side). Lap 2: A shifted by (0.4, 0.3), a room E
  // over all of B and three quarters of C, C's footprint on another level, and a lap-3 event.
  const OrientedRect A = box(0, 0, 4, 4), B = box(8, 0, 12, 4), C = box(12, 0, 16, 4);
  const OrientedRect A2 = box(0.4, 0.3, 4.4, 4.3), E = box(8, 0, 15, 4);
  const std::vector<io::RoomEvent> events = {
      event(1, 0, A),        event(1, 0, B), event(1, 0, C),        event(2, 0, A2, false),
      event(2, 0, E, false), event(2, 1, C), event(3, 0, C, false),
  };
  // E's Dice is 2*16/(16+28) with B and 2*12/(16+28) with C: both >= 0.5, it pairs with B only.
  ASSERT_GE(dice(C, E), kPairMinDice);
  const Consistency c = consistency(events);
  EXPECT_EQ(c.N1st, 3);
  EXPECT_EQ(c.N2nd, 3);
  EXPECT_EQ(c.N_re, 2);
  EXPECT_NEAR(c.f_re, 2.0 / 3.0, 1e-12);
  const double dice_a = 2.0 * 3.6 * 3.7 / 32.0, dice_b = 32.0 / 44.0;
  ASSERT_TRUE(c.dcs && c.d_center);
  EXPECT_NEAR(*c.dcs, 0.5 * (dice_a + dice_b), 1e-9);
  EXPECT_NEAR(*c.d_center, 0.5 * (0.5 + 1.5), 1e-9);
  ASSERT_EQ(c.pairs.size(), 2u);
  EXPECT_EQ(c.pairs[0].a, 0u);  // A-A2 first: the highest Dice
  EXPECT_EQ(c.pairs[0].b, 0u);
  EXPECT_EQ(c.pairs[1].a, 1u);  // then B-E; C stays unpaired
  EXPECT_EQ(c.pairs[1].b, 1u);
}

TEST(RoomConsistency, GreedyTakesTheHighestDiceFirst) {
  // X matches P better than Y does; Y could pair with P only, so greedy leaves Y (and Q) alone
  // where a maximum matching would not.
  const OrientedRect P = box(0, 0, 10, 4), Q = box(3, 0, 13, 4);
  const OrientedRect X = box(1, 0, 10, 4), Y = box(0, 0, 6, 4);
  ASSERT_GT(dice(P, X), dice(P, Y));
  ASSERT_GE(dice(Q, X), kPairMinDice);
  ASSERT_LT(dice(Q, Y), kPairMinDice);
  const Consistency c = consistency_between({{P, "g"}, {Q, "g"}}, {{X, "g"}, {Y, "g"}});
  EXPECT_EQ(c.N_re, 1);
  EXPECT_NEAR(*c.dcs, dice(P, X), 1e-12);
  EXPECT_NEAR(*c.d_center, 0.5, 1e-12);
}

TEST(RoomConsistency, PairsNeedTheSameLevelAndDiceOfAHalf) {
  const OrientedRect A = box(0, 0, 10, 1);
  // Shifted along x by s, Dice = (10 - s) / 10.
  const OrientedRect at_049 = box(5.1, 0, 15.1, 1), at_051 = box(4.9, 0, 14.9, 1);
  EXPECT_NEAR(dice(A, at_049), 0.49, 1e-9);
  EXPECT_EQ(consistency_between({{A, "g"}}, {{at_049, "g"}}).N_re, 0);
  const Consistency paired = consistency_between({{A, "g"}}, {{at_051, "g"}});
  EXPECT_EQ(paired.N_re, 1);
  EXPECT_NEAR(*paired.dcs, 0.51, 1e-9);
  EXPECT_NEAR(*paired.d_center, 4.9, 1e-9);
  // Identical footprints on two levels never pair.
  const Consistency other_level = consistency_between({{A, "ground"}}, {{A, "first"}});
  EXPECT_EQ(other_level.N_re, 0);
  EXPECT_EQ(other_level.f_re, 0.0);
  EXPECT_FALSE(other_level.dcs);
  EXPECT_FALSE(other_level.d_center);
}

TEST(RoomConsistency, RotatedFootprintAndEmptyLaps) {
  // The same 6 x 2 rectangle described with a quarter turn and swapped sides: Dice 1.
  OrientedRect turned = box(0, 0, 2, 6);
  turned.size = Vec2(6, 2);
  turned.yaw = M_PI / 2;
  const Consistency c = consistency_between({{box(0, 0, 2, 6), "g"}}, {{turned, "g"}});
  ASSERT_EQ(c.N_re, 1);
  EXPECT_NEAR(*c.dcs, 1.0, 1e-9);
  EXPECT_NEAR(*c.d_center, 0.0, 1e-12);
  // Nothing in lap 1: f_re is 0, not a division by zero; the figures of the pairs are null.
  const Consistency none = consistency({event(2, 0, box(0, 0, 4, 4))});
  EXPECT_EQ(none.N1st, 0);
  EXPECT_EQ(none.N2nd, 1);
  EXPECT_EQ(none.f_re, 0.0);
  EXPECT_FALSE(none.dcs);
}

// ---- against ground truth ---------------------------------------------------------------------

TEST(RoomsVsTruth, PrecisionRecallF1AndMeanIou) {
  const std::vector<io::RoomTruth> truth = {
      truth_room("G1", "ground", box_polygon(0, 0, 4, 4)),
      truth_room("G2", "ground", box_polygon(4, 0, 10, 4)),
      truth_room("G3", "ground", box_polygon(0, 4, 4, 8)),
  };
  const std::vector<DetectedRoom> detected = {
      {box(0.5, 0, 4, 4), "ground"},  // G1: IoU 14/16
      {box(4, 0, 10, 3), "ground"},   // G2: IoU 18/24
      {box(20, 0, 22, 2), "ground"},  // nothing there
      {box(0, 4, 4, 8), "first"},     // G3's footprint on another level
  };
  const RoomsVsTruth r = rooms_vs_truth(detected, truth);
  EXPECT_EQ(r.n_matched, 2);
  EXPECT_EQ(r.n_rooms_final, 4);
  ASSERT_TRUE(r.precision && r.recall && r.f1 && r.mean_iou);
  EXPECT_NEAR(*r.precision, 0.5, 1e-12);
  EXPECT_NEAR(*r.recall, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(*r.f1, 4.0 / 7.0, 1e-12);
  EXPECT_NEAR(*r.mean_iou, 0.5 * (0.875 + 0.75), 1e-9);
  EXPECT_EQ(r.under_segmented, 0);
  EXPECT_EQ(r.over_segmented, 0);

  const RoomsVsTruth nothing = rooms_vs_truth({}, truth);
  EXPECT_FALSE(nothing.precision);
  EXPECT_NEAR(*nothing.recall, 0.0, 1e-12);
  EXPECT_FALSE(nothing.f1);
  EXPECT_FALSE(nothing.mean_iou);
}

TEST(RoomsVsTruth, OneDetectionOverTwoRoomsIsUnderSegmented) {
  const std::vector<io::RoomTruth> truth = {
      truth_room("G1", "g", box_polygon(0, 0, 4, 4)),
      truth_room("G2", "g", box_polygon(4, 0, 8, 4)),
      truth_room("G3", "g", box_polygon(0, 10, 4, 14)),
      truth_room("G4", "g", box_polygon(4, 10, 8, 14)),
  };
  const std::vector<DetectedRoom> detected = {
      {box(1, 0, 8, 4), "g"},      // 75 % of G1 and all of G2: under-segmented, matches G2 (16/28)
      {box(0, 10, 4.8, 14), "g"},  // all of G3 but only 20 % of G4: not under-segmented
  };
  const RoomsVsTruth r = rooms_vs_truth(detected, truth);
  EXPECT_EQ(r.under_segmented, 1);
  EXPECT_EQ(r.over_segmented, 0);
  EXPECT_EQ(r.n_matched, 2);
  EXPECT_NEAR(*r.mean_iou, 0.5 * (16.0 / 28.0 + 16.0 / 19.2), 1e-9);
}

TEST(RoomsVsTruth, OneRoomSplitByTwoDetectionsIsOverSegmented) {
  const std::vector<io::RoomTruth> truth = {
      truth_room("hall", "g", box_polygon(0, 0, 10, 4)),
      truth_room("office", "g", box_polygon(20, 0, 30, 4)),
  };
  const std::vector<DetectedRoom> detected = {
      {box(0, 0, 6, 4), "g"},    // 60 % of the hall: matched, IoU 0.6
      {box(6, 0, 10, 4), "g"},   // 40 %: the hall is over-segmented
      {box(20, 0, 29, 4), "g"},  // 90 % of the office: matched, IoU 0.9
      {box(29, 0, 31, 4), "g"},  // 10 % of the office: not enough to split it
  };
  const RoomsVsTruth r = rooms_vs_truth(detected, truth);
  EXPECT_EQ(r.over_segmented, 1);
  EXPECT_EQ(r.under_segmented, 0);
  EXPECT_EQ(r.n_matched, 2);
  EXPECT_NEAR(*r.precision, 0.5, 1e-12);
  EXPECT_NEAR(*r.recall, 1.0, 1e-12);
  EXPECT_NEAR(*r.mean_iou, 0.5 * (0.6 + 0.9), 1e-9);
}

TEST(RoomsVsTruth, NonConvexTruthPolygons) {
  ASSERT_NEAR(area(kL), 20.0, 1e-12);
  EXPECT_NEAR(intersection_area(box(0, 0, 6, 6), kL), 20.0, 1e-9);  // the L inside its bounding box
  EXPECT_NEAR(intersection_area(box(2, 2, 6, 6), kL), 0.0, 1e-9);   // the notch
  EXPECT_NEAR(intersection_area(box(1, 1, 5, 5), kL), 16.0 - 9.0, 1e-9);
  // The leg, as a rectangle turned by a quarter: IoU 12 / 20.
  OrientedRect leg;
  leg.center = Vec2(1, 3);
  leg.size = Vec2(6, 2);
  leg.yaw = M_PI / 2;
  EXPECT_NEAR(iou(leg, kL), 0.6, 1e-9);
  // Clockwise vertex order gives the same figures.
  const Polygon2 cw(kL.rbegin(), kL.rend());
  EXPECT_NEAR(iou(leg, cw), 0.6, 1e-9);
  // A U cut into two pieces by the rectangle: 2 x 2 on each side of the gap.
  const Polygon2 u = {{0, 0}, {6, 0}, {6, 4}, {4, 4}, {4, 1}, {2, 1}, {2, 4}, {0, 4}};
  EXPECT_NEAR(intersection_area(box(0, 2, 6, 4), u), 8.0, 1e-9);

  // The L's bounding box matches it (IoU 20/36) and its leg alone does better (0.6): one-to-one,
  // the leg takes it and the box is a false positive.
  const std::vector<io::RoomTruth> truth = {truth_room("L", "g", kL)};
  const RoomsVsTruth r = rooms_vs_truth({{box(0, 0, 6, 6), "g"}, {leg, "g"}}, truth);
  EXPECT_EQ(r.n_matched, 1);
  EXPECT_NEAR(*r.mean_iou, 0.6, 1e-9);
  EXPECT_NEAR(*r.precision, 0.5, 1e-12);
  EXPECT_EQ(r.over_segmented, 1);  // both cover at least a quarter of the L
}
