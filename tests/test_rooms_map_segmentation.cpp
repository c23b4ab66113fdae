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
using test::FloorBox;
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

/// The cells within `width` of a free cell that are not free: a wall drawn round the free space.
std::vector<std::uint8_t> hit_round(const GridFrame& f, const std::vector<std::uint8_t>& free, double width) {
  const int reach = static_cast<int>(std::ceil(width / f.resolution));
  std::vector<std::uint8_t> hit(f.size(), 0);
  for (int r = 0; r < f.rows; ++r)
    for (int c = 0; c < f.cols; ++c) {
      if (free[f.index(c, r)]) continue;
      for (int dr = -reach; dr <= reach && !hit[f.index(c, r)]; ++dr)
        for (int dc = -reach; dc <= reach; ++dc)
          if (f.inside(c + dc, r + dr) && free[f.index(c + dc, r + dr)]) {
            hit[f.index(c, r)] = 1;
            break;
          }
    }
  return hit;
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

TEST(MapSegmentation, ARoomSeenOnlyThroughItsDoorIsARoomOfItsOwn) {
  // The office was never entered: the laser saw into it through its door from the east room, a
  // fan of rays a cell wide that end on its walls. The fan's sides are where the view ended, no
  // walls, and its rays (diagonal chains of cells) are one room with the part near the door.
  DrawnFloor d = test::draw_floor();
  const int office = 4;
  const FloorBox inside{12.15, 6.15, 15.85, 9.85};
  const auto in_office = [&](const Vec2& p) {
    return p.x() >= inside.x0 && p.x() <= inside.x1 && p.y() >= inside.y0 && p.y() <= inside.y1;
  };
  for (std::size_t i = 0; i < d.cells.size(); ++i) {
    if (!in_office(d.frame.center(i))) continue;
    if (d.cells[i] == FloorCell::kFree) d.cells[i] = FloorCell::kUnknown;
    d.truth[i] = -1;
  }
  const Vec2 eye(11.4, 8.0);
  for (int deg = -39; deg <= 39; deg += 3) {
    const Vec2 u(std::cos(deg * M_PI / 180.0), std::sin(deg * M_PI / 180.0));
    for (double t = 0.0; t < 8.0; t += 0.01) {
      int c, r;
      if (!d.frame.cell_of(eye + t * u, &c, &r)) break;
      const std::size_t i = d.frame.index(c, r);
      if (d.cells[i] == FloorCell::kOccupied) break;
      if (d.cells[i] == FloorCell::kUnknown) d.cells[i] = FloorCell::kFree;
      if (in_office(d.frame.center(i))) d.truth[i] = office;
    }
  }
  const MapSegmentation seg = segment_map(d.frame, d.mask(FloorCell::kFree), d.mask(FloorCell::kOccupied));
  for (std::size_t k = 0; k < d.names.size(); ++k)
    EXPECT_GE(best_iou(seg.rooms, d, static_cast<int>(k)), k == office ? 0.5 : 0.8) << d.names[k];
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
  const std::vector<WallCandidate> walls = map_walls(f, free, hit_round(f, free, 0.1));
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
  EXPECT_TRUE(map_walls(f, free, hit_round(f, free, 0.05)).empty());
}

TEST(MapWalls, AnEdgeWithOnlyUnknownBehindItIsNoWall) {
  // A 6 x 4 m room: its south and west walls were hit behind a band of unknown 0.1 m wide (a laser
  // map's fringe), its north side is where the view ended (unknown only), its east side was hit
  // 0.5 m behind the edge (beyond the fringe). Walls come out along south and west only.
  GridFrame f;
  f.resolution = 0.05;
  f.cols = f.rows = 200;
  std::vector<std::uint8_t> free(f.size(), 0), hit(f.size(), 0);
  for (std::size_t i = 0; i < free.size(); ++i) {
    const Vec2 p = f.center(i);
    free[i] = p.x() > 2.0 && p.x() < 8.0 && p.y() > 2.0 && p.y() < 6.0 ? 1 : 0;
    const bool south = p.y() > 1.8 && p.y() < 1.9 && p.x() > 1.8 && p.x() < 8.6;
    const bool west = p.x() > 1.8 && p.x() < 1.9 && p.y() > 1.8 && p.y() < 6.2;
    const bool east = p.x() > 8.5 && p.x() < 8.6 && p.y() > 1.8 && p.y() < 6.2;
    hit[i] = south || west || east ? 1 : 0;
  }
  const std::vector<WallCandidate> walls = map_walls(f, free, hit);
  bool south = false, west = false;
  for (const WallCandidate& w : walls) {
    const Vec2 mid = 0.5 * (w.end_a + w.end_b);
    EXPECT_LT(mid.y(), 5.5) << "a wall along the north side, where nothing was hit";
    EXPECT_LT(mid.x(), 7.5) << "a wall along the east side, hit farther behind than a fringe";
    south = south || (mid.y() < 2.2 && (w.end_b - w.end_a).norm() > 4.0);
    west = west || (mid.x() < 2.2 && (w.end_b - w.end_a).norm() > 2.5);
  }
  EXPECT_TRUE(south);
  EXPECT_TRUE(west);
}

TEST(MapWalls, ConfigOutOfRangeIsRefused) {
  GridFrame f;
  f.cols = f.rows = 10;
  MapWallsConfig cfg;
  cfg.min_piece = 0.0;
  const std::vector<std::uint8_t> free(f.size(), 1), none(f.size(), 0);
  EXPECT_THROW(map_walls(f, free, none, cfg), std::invalid_argument);
  EXPECT_THROW(map_walls(f, free, std::vector<std::uint8_t>(3, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace tsgraphs::rooms
