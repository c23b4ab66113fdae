// segment_map and map_walls: the room segmentation of a 2-D occupancy map.
#include <gtest/gtest.h>

#include <cmath>

#include "drawn_floor_support.hpp"
#include "tsgraphs/eval/label_metrics.hpp"
#include "tsgraphs/rooms/map_segmentation.hpp"
#include "tsgraphs/rooms/map_walls.hpp"

namespace tsgraphs::rooms {
namespace {

using test::DrawnFloor;
using test::FloorCell;

/// IoU of true room k with the segment holding most of it.
double best_iou(const RoomSegmentation& seg, const DrawnFloor& d, int k) {
  std::vector<std::size_t> shared(seg.spaces.size(), 0), size(seg.spaces.size(), 0);
  std::size_t truth = 0;
  for (std::size_t i = 0; i < d.truth.size(); ++i) {
    if (seg.label[i] >= 0) ++size[static_cast<std::size_t>(seg.label[i])];
    if (d.truth[i] != k) continue;
    ++truth;
    if (seg.label[i] >= 0) ++shared[static_cast<std::size_t>(seg.label[i])];
  }
  double best = 0.0;
  for (std::size_t s = 0; s < shared.size(); ++s)
    if (shared[s] > 0)
      best =
          std::max(best, static_cast<double>(shared[s]) / static_cast<double>(truth + size[s] - shared[s]));
  return best;
}

TEST(MapSegmentation, ADrawnFloorGivesItsRooms) {
  // Rooms, 0.8 m doors, a corridor, an L-shaped room round a small office, furniture and
  // chairs' legs: one space per room, each matching its room closely, nothing else.
  const DrawnFloor d = test::draw_floor();
  const MapSegmentation seg = segment_map(d.frame, d.mask(FloorCell::kFree), d.mask(FloorCell::kOccupied));
  for (std::size_t k = 0; k < d.names.size(); ++k)
    EXPECT_GE(best_iou(seg.rooms, d, static_cast<int>(k)), 0.8) << d.names[k];
  const eval::LabelFigures f = eval::compare_labels(seg.rooms.label, d.truth, d.frame.cols);
  EXPECT_EQ(f.rooms.n_segments, 5);
  EXPECT_EQ(f.rooms.n_matched, 5);
  ASSERT_TRUE(f.ipa.precision_micro && f.ipa.recall_micro);
  EXPECT_GT(*f.ipa.precision_micro, 0.95);
  EXPECT_GT(*f.ipa.recall_micro, 0.95);
}

TEST(MapSegmentation, TheSameMapGivesTheSameRooms) {
  const DrawnFloor d = test::draw_floor();
  const MapSegmentation a = segment_map(d.frame, d.mask(FloorCell::kFree), d.mask(FloorCell::kOccupied));
  const MapSegmentation b = segment_map(d.frame, d.mask(FloorCell::kFree), d.mask(FloorCell::kOccupied));
  EXPECT_EQ(a.rooms.label, b.rooms.label);
  ASSERT_EQ(a.walls.size(), b.walls.size());
}

TEST(MapSegmentation, AMaskOfAnotherSizeIsRefused) {
  const DrawnFloor d = test::draw_floor();
  std::vector<std::uint8_t> free = d.mask(FloorCell::kFree);
  free.pop_back();
  EXPECT_THROW(segment_map(d.frame, free, d.mask(FloorCell::kOccupied)), std::invalid_argument);
}

TEST(MapWalls, TheWallsOfARotatedRoomFollowItsDirection) {
  // A 6 x 4 m room turned by 20 degrees: its four walls come out along 20 and 110 degrees, each
  // normal pointing into the room.
  GridFrame f;
  f.resolution = 0.05;
  f.cols = f.rows = 200;
  const double yaw = 20.0 * M_PI / 180.0;
  const Vec2 c(5.0, 5.0), u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x());
  std::vector<std::uint8_t> free(f.size(), 0);
  for (std::size_t i = 0; i < free.size(); ++i) {
    const Vec2 p = f.center(i) - c;
    free[i] = std::abs(p.dot(u)) < 3.0 && std::abs(p.dot(v)) < 2.0 ? 1 : 0;
  }
  const std::vector<WallCandidate> walls = map_walls(f, free);
  ASSERT_GE(walls.size(), 4u);
  double length = 0.0;
  for (const WallCandidate& w : walls) {
    const Vec2 along = (w.end_b - w.end_a).normalized();
    EXPECT_GT(std::max(std::abs(along.dot(u)), std::abs(along.dot(v))), std::cos(1.0 * M_PI / 180.0));
    const Vec2 mid = 0.5 * (w.end_a + w.end_b);
    EXPECT_GT(w.plane.n.head<2>().dot(c - mid), 0.0) << "normal away from the room";
    length += (w.end_b - w.end_a).norm();
  }
  EXPECT_NEAR(length, 2.0 * (6.0 + 4.0), 1.5);
}

TEST(MapWalls, ClutterAndLaserFansGiveNoWall) {
  // Free space of chair legs' specks and thin fans of rays only: no straight edge a robot walks
  // along, no wall.
  GridFrame f;
  f.resolution = 0.05;
  f.cols = f.rows = 200;
  std::vector<std::uint8_t> free(f.size(), 0);
  for (int k = 0; k < 40; ++k) {  // rays from (5, 5), a cell wide
    const double a = k * 2.0 * M_PI / 40.0;
    for (double t = 0.0; t < 4.5; t += 0.02) {
      int c, r;
      if (f.cell_of(Vec2(5.0, 5.0) + t * Vec2(std::cos(a), std::sin(a)), &c, &r)) free[f.index(c, r)] = 1;
    }
  }
  EXPECT_TRUE(map_walls(f, free).empty());
}

TEST(MapWalls, ConfigOutOfRangeIsRefused) {
  GridFrame f;
  f.cols = f.rows = 10;
  MapWallsConfig cfg;
  cfg.min_piece = 0.0;
  EXPECT_THROW(map_walls(f, std::vector<std::uint8_t>(f.size(), 1), cfg), std::invalid_argument);
}

}  // namespace
}  // namespace tsgraphs::rooms
