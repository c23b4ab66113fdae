// IPA precision / recall (docs/metrics.md) against hand computations on toy rooms at 0.05 m
// cells, and the empty cases.
#include <gtest/gtest.h>

#include "tsgraphs/eval/ipa_segmentation_metrics.hpp"

using namespace tsgraphs;
using namespace tsgraphs::eval;

namespace {

Polygon2 box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

io::RoomTruth truth(const std::string& name, const Polygon2& polygon, const std::string& level = "G") {
  return {name, level, polygon, 0.0};
}

LevelFootprint footprint(const Polygon2& polygon, const std::string& level = "G") { return {polygon, level}; }

}  // namespace

TEST(IpaSegmentationMetrics, TwoRoomsThreeSegmentsByHand) {
  // Truth (cells of 0.05 m): A = [0,2] x [0,1], 40 x 20 = 800 cells; B = [2,3] x [0,1], 400 cells;
  // C = [5,5.4] x [0,0.4], 8 x 8 = 64 cells, a "mini room" (<= 100 cells): left out.
  const std::vector<io::RoomTruth> rooms = {truth("A", box(0, 0, 2, 1)), truth("B", box(2, 0, 3, 1)),
                                            truth("C", box(5, 0, 5.4, 0.4))};
  // Segments:
  //   S1 = [0,1.6] x [0,1] (area 1.6), S2 = [1.5,2.5] x [0,1] (area 1.0): the strip [1.5,1.6] they
  //     share goes to the smaller, S2;
  //   S4 = [0.2,0.6] x [0.2,0.6] (area 0.16, 64 cells) inside S1: its cells go to S4, which is then
  //     left out (<= 100 cells), so S1 keeps [0,1.5] x [0,1] minus S4: 600 - 64 = 536 cells, all in A;
  //   S2: 400 cells, 200 in A and 200 in B;
  //   S3 = [2.5,3.5] x [0,1]: 400 cells, clipped to the free space (A u B u C): the 200 in B.
  const std::vector<LevelFootprint> segments = {footprint(box(0, 0, 1.6, 1)), footprint(box(1.5, 0, 2.5, 1)),
                                                footprint(box(2.5, 0, 3.5, 1)),
                                                footprint(box(0.2, 0.2, 0.6, 0.6))};
  const std::vector<CellRegion> seg = segments_of(segments, rooms);
  ASSERT_EQ(seg.size(), 4u);
  EXPECT_EQ(seg[0].cells.size(), 536u);
  EXPECT_EQ(seg[1].cells.size(), 400u);
  EXPECT_EQ(seg[2].cells.size(), 200u);
  EXPECT_EQ(seg[3].cells.size(), 64u);

  const IpaFigures f = ipa_segmentation_metrics(segments, rooms, rooms);
  EXPECT_EQ(f.n_segments, 3);  // S4 left out
  EXPECT_EQ(f.n_truth, 2);     // C left out
  // Overlaps: S1-A 536; S2-A 200, S2-B 200; S3-B 200.
  // precision_micro = (536/536 + 200/400 + 200/200) / 3 = 2.5 / 3
  // precision_macro = (536 + 200 + 200) / (536 + 400 + 200) = 936 / 1136
  // recall_micro = (536/800 + 200/400) / 2 = (0.67 + 0.5) / 2 = 0.585
  // recall_macro = (536 + 200) / (800 + 400) = 736 / 1200
  ASSERT_TRUE(f.precision_micro && f.precision_macro && f.recall_micro && f.recall_macro);
  EXPECT_NEAR(*f.precision_micro, 2.5 / 3.0, 1e-12);
  EXPECT_NEAR(*f.precision_macro, 936.0 / 1136.0, 1e-12);
  EXPECT_NEAR(*f.recall_micro, 0.585, 1e-12);
  EXPECT_NEAR(*f.recall_macro, 736.0 / 1200.0, 1e-12);
}

TEST(IpaSegmentationMetrics, OnlyVisitedRoomsCountButEveryRoomIsFreeSpace) {
  // A = [0,2] x [0,1] (800 cells, visited), D = [0,3] x [2,3] (1200 cells, never entered).
  const io::RoomTruth A = truth("A", box(0, 0, 2, 1)), D = truth("D", box(0, 2, 3, 3));
  const std::vector<LevelFootprint> segments = {footprint(box(0, 0, 2, 1)), footprint(box(0, 2, 3, 3))};
  const IpaFigures f = ipa_segmentation_metrics(segments, {A, D}, {A});
  // The segment on D is free space but overlaps no room that counts:
  // precision_micro = (1 + 0) / 2, precision_macro = 800 / 2000; recall = 1.
  EXPECT_NEAR(*f.precision_micro, 0.5, 1e-12);
  EXPECT_NEAR(*f.precision_macro, 0.4, 1e-12);
  EXPECT_NEAR(*f.recall_micro, 1.0, 1e-12);
  EXPECT_NEAR(*f.recall_macro, 1.0, 1e-12);
}

TEST(IpaSegmentationMetrics, LevelsAreApart) {
  // A footprint over A's x-y on the upper level: the upper level has no free space there, so it
  // is clipped to nothing; A is then found by nobody.
  const io::RoomTruth A = truth("A", box(0, 0, 2, 1)), U = truth("U", box(0, 0, 2, 1), "U");
  const IpaFigures f = ipa_segmentation_metrics({footprint(box(0, 0, 2, 1), "U")}, {A}, {A});
  EXPECT_EQ(f.n_segments, 0);
  EXPECT_FALSE(f.precision_micro);
  EXPECT_NEAR(*f.recall_micro, 0.0, 1e-12);
  // With the upper room in the truth, the same footprint is a perfect segment of it, not of A.
  const IpaFigures g = ipa_segmentation_metrics({footprint(box(0, 0, 2, 1), "U")}, {A, U}, {A, U});
  EXPECT_NEAR(*g.precision_micro, 1.0, 1e-12);
  EXPECT_NEAR(*g.recall_micro, 0.5, 1e-12);  // A: 0, U: 1
  EXPECT_NEAR(*g.recall_macro, 0.5, 1e-12);
}

TEST(IpaSegmentationMetrics, NothingToCountIsEmptyNotNaN) {
  const io::RoomTruth A = truth("A", box(0, 0, 2, 1));
  const IpaFigures none = ipa_segmentation_metrics({}, {A}, {A});
  EXPECT_FALSE(none.precision_micro);
  EXPECT_FALSE(none.precision_macro);
  ASSERT_TRUE(none.recall_micro && none.recall_macro);
  EXPECT_EQ(*none.recall_micro, 0.0);  // the room is there and nothing found it
  EXPECT_EQ(*none.recall_macro, 0.0);
  const IpaFigures no_truth = ipa_precision_recall({{"G", {cell_key(0, 0)}}}, {});
  EXPECT_FALSE(no_truth.precision_micro);  // the one segment is a mini segment
  EXPECT_FALSE(no_truth.recall_micro);
}
