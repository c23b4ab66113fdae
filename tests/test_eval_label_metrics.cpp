// compare_labels: IPA figures and room F1 of two labellings of one raster.
#include <gtest/gtest.h>

#include "tsgraphs/eval/label_metrics.hpp"

namespace tsgraphs::eval {
namespace {

constexpr int kCols = 40, kRows = 20;

/// Two 20 x 20 rooms side by side (label 0 left, 1 right).
std::vector<int> two_rooms() {
  std::vector<int> l(kCols * kRows);
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kCols; ++c) l[static_cast<std::size_t>(r) * kCols + c] = c < 20 ? 0 : 1;
  return l;
}

TEST(LabelMetrics, TheTruthScoresFull) {
  const LabelFigures f = compare_labels(two_rooms(), two_rooms(), kCols);
  EXPECT_DOUBLE_EQ(*f.ipa.precision_micro, 1.0);
  EXPECT_DOUBLE_EQ(*f.ipa.recall_micro, 1.0);
  EXPECT_DOUBLE_EQ(*f.rooms.f1, 1.0);
  EXPECT_EQ(f.rooms.n_matched, 2);
}

TEST(LabelMetrics, TwoRoomsAsOneKeepRecallAndLosePrecision) {
  const std::vector<int> one(kCols * kRows, 0);
  const LabelFigures f = compare_labels(one, two_rooms(), kCols);
  EXPECT_DOUBLE_EQ(*f.ipa.precision_micro, 0.5);  // the segment lies half in one true room
  EXPECT_DOUBLE_EQ(*f.ipa.recall_micro, 1.0);
  EXPECT_EQ(f.rooms.n_matched, 1);  // IoU 0.5 with either: one pair
  EXPECT_DOUBLE_EQ(*f.rooms.precision, 1.0);
  EXPECT_DOUBLE_EQ(*f.rooms.recall, 0.5);
}

TEST(LabelMetrics, SmallRegionsAndUnlabelledCellsCountNowhere) {
  std::vector<int> seg = two_rooms();
  for (int c = 0; c < 10; ++c) seg[static_cast<std::size_t>(c)] = 2;  // a 10-cell speck: no segment
  for (int c = 30; c < 40; ++c) seg[static_cast<std::size_t>(kCols + c)] = -1;
  const LabelFigures f = compare_labels(seg, two_rooms(), kCols);
  EXPECT_EQ(f.ipa.n_segments, 2);
  EXPECT_EQ(f.rooms.n_segments, 2);
  EXPECT_DOUBLE_EQ(*f.ipa.precision_micro, 1.0);
  EXPECT_LT(*f.ipa.recall_micro, 1.0);
}

TEST(LabelMetrics, NoSegmentGivesNoPrecision) {
  const LabelFigures f = compare_labels(std::vector<int>(kCols * kRows, -1), two_rooms(), kCols);
  EXPECT_FALSE(f.ipa.precision_micro);
  EXPECT_DOUBLE_EQ(*f.ipa.recall_micro, 0.0);
  EXPECT_FALSE(f.rooms.f1);
}

TEST(LabelMetrics, LabellingsOfTwoRastersAreRefused) {
  EXPECT_THROW(compare_labels(two_rooms(), std::vector<int>(10, 0), kCols), std::invalid_argument);
}

}  // namespace
}  // namespace tsgraphs::eval
