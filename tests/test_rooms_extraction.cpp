// Room extraction on constructed rooms: four walls, a corridor, a railing side, a bookshelf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rooms_test_support.hpp"
#include "tsgraphs/rooms/room_extraction.hpp"

namespace tsgraphs::rooms {
namespace {

constexpr double kStep = 0.1;  // spacing of the constructed free-space nodes (m)

using test::bounds;
using test::Bounds;
using test::room_walls;
using test::wall;

/// Free-space points on the grid of this file's spacing.
std::vector<Eigen::Vector3d> grid(double x0, double x1, double y0, double y1) {
  return test::grid(kStep, x0, x1, y0, y1);
}

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

TEST(RoomExtraction, FourWallRoomIsBoundedByItsWalls) {
  std::vector<WallCandidate> walls = room_walls();
  walls.push_back(wall(4, {8, 0}, {-1, 0}, {8, 0}, {8, 4}));  // next room's wall, behind wall 1
  walls.push_back(wall(5, {2, 0}, {1, 0}, {2, -3}, {2, 6}));  // a plane the cluster crosses
  const auto room = extract_room(grid(0.5, 4.5, 0.5, 3.5), {}, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::room);
  EXPECT_EQ(sorted(room->wall_ids), (std::vector<int>{0, 1, 2, 3}));
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 0.0, 0.02);
  EXPECT_NEAR(b.x1, 5.0, 0.02);
  EXPECT_NEAR(b.y0, 0.0, 0.02);
  EXPECT_NEAR(b.y1, 4.0, 0.02);
}

TEST(RoomExtraction, RotatedRoomMatchesItsWalls) {
  const double yaw = 30.0 * M_PI / 180.0;
  const Eigen::Rotation2Dd R(yaw);
  const Vec2 t(3.0, -2.0);
  const std::vector<WallCandidate> walls = test::moved_room_walls(R, t);
  std::vector<Eigen::Vector3d> cluster = grid(0.5, 4.5, 0.5, 3.5);
  for (Eigen::Vector3d& p : cluster) p.head<2>() = R * p.head<2>() + t;
  const auto room = extract_room(cluster, {}, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::room);
  OrientedRect truth;
  truth.center = R * Vec2(2.5, 2.0) + t;
  truth.size = Vec2(5.0, 4.0);
  truth.yaw = yaw;
  EXPECT_LT((room->rect.center - truth.center).norm(), 0.02);
  EXPECT_GT(dice(room->rect, truth), 0.99);
}

TEST(RoomExtraction, CorridorRunsAsFarAsBothItsWalls) {
  // Walls along y = 0 (x 0..10) and y = 2 (x 1..9); the free space walked covers x 2..8 only.
  const std::vector<WallCandidate> walls = {wall(0, {0, 0}, {0, 1}, {0, 0}, {10, 0}),
                                            wall(1, {0, 2}, {0, -1}, {1, 2}, {9, 2})};
  const auto room = extract_room(grid(2.0, 8.0, 0.4, 1.6), {}, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::corridor);
  EXPECT_EQ(sorted(room->wall_ids), (std::vector<int>{0, 1}));
  EXPECT_TRUE(room->end_wall_ids.empty());
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.y1 - b.y0, 2.0, 0.02);  // width from the planes
  EXPECT_NEAR(b.x0, 1.0, 0.02);         // length: where both walls run, not the cluster's 6 m
  EXPECT_NEAR(b.x1, 9.0, 0.02);
}

TEST(RoomExtraction, CorridorIsCarriedAlongItsWallsPastUnmappedGroundToAWallAcross) {
  // Corridor [0, 24] x [0, 2] closed by a wall at x = 24; walked at x 3..13, its ground mapped
  // densely to x = 15, sparsely (a strip down the middle, holes) to x = 18, not beyond.
  const std::vector<WallCandidate> walls = {wall(0, {0, 0}, {0, 1}, {0, 0}, {24, 0}),
                                            wall(1, {0, 2}, {0, -1}, {0, 2}, {24, 2}),
                                            wall(2, {24, 0}, {-1, 0}, {24, -3}, {24, 5})};
  std::vector<Eigen::Vector3d> context = grid(0.4, 15.2, 0.4, 1.6);
  for (const Eigen::Vector3d& p : grid(0.8, 18.0, 0.8, 1.2))
    if (p.x() > 15.5 && std::fmod(p.x(), 2.0) > 0.5) context.push_back(p);
  const auto room = extract_room(grid(3.0, 13.0, 0.4, 1.6), context, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::corridor);
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 0.0, 0.02);
  EXPECT_NEAR(b.x1, 24.0, 0.02);
}

TEST(RoomExtraction, RailingSideIsBoundedByTheCluster) {
  // Room [0, 5] x [0, 4] whose side x = 5 is a railing (no plane); beyond it a void and the
  // atrium's far wall at x = 12, which must not be taken as the room's fourth wall.
  std::vector<WallCandidate> walls = room_walls();
  walls.erase(walls.begin() + 1);
  walls.push_back(wall(6, {12, 0}, {-1, 0}, {12, -1}, {12, 5}));
  const auto room = extract_room(grid(0.5, 4.6, 0.5, 3.5), {}, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::corridor);
  EXPECT_EQ(sorted(room->wall_ids), (std::vector<int>{2, 3}));
  EXPECT_EQ(room->end_wall_ids, (std::vector<int>{0}));
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 0.0, 0.02);   // the wall
  EXPECT_NEAR(b.x1, 5.0, 0.02);   // as far as both side walls run: to the railing
  EXPECT_NEAR(b.y0, 0.0, 0.02);
  EXPECT_NEAR(b.y1, 4.0, 0.02);
}

TEST(RoomExtraction, SpaceBetweenWallAndBookshelfIsItsOwnRoom) {
  std::vector<WallCandidate> walls = room_walls();
  walls.push_back(wall(4, {1.5, 0}, {-1, 0}, {1.5, 0.5}, {1.5, 3.5}));  // shelf front, facing wall 0
  const auto room = extract_room(grid(0.4, 1.1, 0.4, 3.6), {}, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::room);
  EXPECT_EQ(sorted(room->wall_ids), (std::vector<int>{0, 2, 3, 4}));
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 0.0, 0.02);
  EXPECT_NEAR(b.x1, 1.5, 0.02);
  EXPECT_NEAR(b.y0, 0.0, 0.02);
  EXPECT_NEAR(b.y1, 4.0, 0.02);
}

TEST(RoomExtraction, ShelfTheClusterGoesAroundDoesNotCutTheRoom) {
  std::vector<WallCandidate> walls = room_walls();
  walls.push_back(wall(4, {1.5, 0}, {-1, 0}, {1.5, 1.0}, {1.5, 3.0}));
  std::vector<Eigen::Vector3d> cluster;
  for (const Eigen::Vector3d& p : grid(0.4, 4.6, 0.4, 3.6)) {
    const bool at_shelf = p.x() > 1.2 && p.x() < 2.1 && p.y() > 0.7 && p.y() < 3.3;
    if (!at_shelf) cluster.push_back(p);
  }
  const auto room = extract_room(cluster, {}, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(sorted(room->wall_ids), (std::vector<int>{0, 1, 2, 3}));
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x1 - b.x0, 5.0, 0.02);
  EXPECT_NEAR(b.y1 - b.y0, 4.0, 0.02);
}

TEST(RoomExtraction, OneWallAndARailingMakeACorridorCarriedToItsEndWalls) {
  // Corridor [0, 14] x [0, 3]: a wall at y = 0, a railing at y = 3 (no plane; the free space
  // stops lambda_th = 0.4 short of it), end walls at x = 0 and x = 14. Walked: x 5..8 only.
  const std::vector<WallCandidate> walls = {wall(0, {0, 0}, {0, 1}, {0, 0}, {14, 0}),
                                            wall(1, {0, 0}, {1, 0}, {0, -5}, {0, 3}),
                                            wall(2, {14, 0}, {-1, 0}, {14, -5}, {14, 3})};
  const auto room = extract_room(grid(5.0, 8.0, 0.4, 2.6), grid(0.4, 13.6, 0.4, 2.6), walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::corridor);
  EXPECT_TRUE(room->one_sided);
  EXPECT_EQ(room->wall_ids, (std::vector<int>{0}));
  EXPECT_EQ(sorted(room->end_wall_ids), (std::vector<int>{1, 2}));
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 0.0, 0.02);
  EXPECT_NEAR(b.x1, 14.0, 0.02);
  EXPECT_NEAR(b.y0, 0.0, 0.02);
  EXPECT_NEAR(b.y1, 3.0, 0.05);  // the free space's edge plus lambda_th: the railing
}

TEST(RoomExtraction, OpenSideCorridorStopsWhereACrossingAisleOpens) {
  // As above, but at x < 3 a second aisle leaves the corridor beyond its open side (y > 3).
  const std::vector<WallCandidate> walls = {wall(0, {0, 0}, {0, 1}, {0, 0}, {14, 0}),
                                            wall(2, {14, 0}, {-1, 0}, {14, -5}, {14, 3})};
  std::vector<Eigen::Vector3d> context = grid(0.4, 13.6, 0.4, 2.6);
  for (const Eigen::Vector3d& p : grid(0.4, 2.6, 2.7, 9.0)) context.push_back(p);
  const auto room = extract_room(grid(5.0, 8.0, 0.4, 2.6), context, walls);
  ASSERT_TRUE(room.has_value());
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 2.7, 0.3);  // where the crossing aisle begins
  EXPECT_NEAR(b.x1, 14.0, 0.02);
}

TEST(RoomExtraction, CorridorIsCarriedAlongItsWallsButNotThroughADoor) {
  // Corridor [0, 20] x [0, 2] walked at x 8..12; at x = 16 a wall across it, and through a door
  // a 0.4 m wide, 1 m deep strip of free space (the wall and lambda_th on both sides) leads on.
  const std::vector<WallCandidate> walls = {wall(0, {0, 0}, {0, 1}, {0, 0}, {20, 0}),
                                            wall(1, {0, 2}, {0, -1}, {0, 2}, {20, 2}),
                                            wall(2, {16, 0}, {-1, 0}, {16, 0}, {16, 2})};
  std::vector<Eigen::Vector3d> context = grid(0.4, 15.6, 0.4, 1.6);
  for (const Eigen::Vector3d& p : grid(15.7, 16.7, 0.8, 1.2)) context.push_back(p);  // the door
  for (const Eigen::Vector3d& p : grid(16.8, 19.6, 0.4, 1.6)) context.push_back(p);
  const auto room = extract_room(grid(8.0, 12.0, 0.4, 1.6), context, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::corridor);
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 0.0, 0.02);   // where the walls begin (no end wall)
  EXPECT_NEAR(b.x1, 16.0, 0.02);  // the door's wall stops it
}

TEST(RoomExtraction, WallCrossedOnlyThroughADoorStillBoundsTheRoom) {
  // The segment of a room walked out through a door at x 2..3 in the wall y = 4 reaches 1 m
  // into the corridor beyond: the wall still bounds the room.
  std::vector<Eigen::Vector3d> segment = grid(0.5, 4.5, 0.5, 3.5);
  for (const Eigen::Vector3d& p : grid(2.1, 2.9, 3.6, 5.0)) segment.push_back(p);
  const auto room = extract_room(segment, {}, room_walls());
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::room);
  EXPECT_EQ(sorted(room->wall_ids), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_NEAR(bounds(room->rect).y1, 4.0, 0.02);
}

TEST(RoomExtraction, LowFurnitureIsNotAWallButABookshelfIs) {
  // A sideboard along x = 4 facing the room; the free space stops in front of it.
  RoomExtractionConfig config;
  config.max_wall_clearance = 1.5;  // so that the room's own wall at x = 5 is reached
  std::vector<WallCandidate> walls = room_walls();
  WallCandidate front = wall(4, {4, 0}, {-1, 0}, {4, 0}, {4, 4});
  front.height = 0.9;
  walls.push_back(front);
  const auto low = extract_room(grid(0.5, 3.6, 0.5, 3.5), {}, walls, config);
  ASSERT_TRUE(low.has_value());
  EXPECT_EQ(sorted(low->wall_ids), (std::vector<int>{0, 1, 2, 3}));
  walls.back().height = 2.0;
  const auto shelf = extract_room(grid(0.5, 3.6, 0.5, 3.5), {}, walls, config);
  ASSERT_TRUE(shelf.has_value());
  EXPECT_EQ(sorted(shelf->wall_ids), (std::vector<int>{0, 2, 3, 4}));
}

TEST(RoomExtraction, NothingWithoutAFacingPair) {
  const std::vector<Eigen::Vector3d> cluster = grid(0.5, 4.5, 0.5, 3.5);
  EXPECT_FALSE(extract_room(cluster, {}, {room_walls()[0], room_walls()[2]}).has_value());
  // One wall beside an open hall: its far side is no railing but more free space.
  EXPECT_FALSE(extract_room(grid(2.0, 8.0, 0.4, 2.0), grid(0.0, 10.0, 0.4, 9.0),
                            {wall(0, {0, 0}, {0, 1}, {0, 0}, {10, 0})})
                   .has_value());
  EXPECT_FALSE(extract_room({}, {}, room_walls()).has_value());
  // A pair whose segments lie beside the cluster, not along it, does not bound it.
  const std::vector<WallCandidate> beside = {wall(0, {0, 0}, {1, 0}, {0, 10}, {0, 14}),
                                             wall(1, {5, 0}, {-1, 0}, {5, 10}, {5, 14})};
  EXPECT_FALSE(extract_room(cluster, {}, beside).has_value());
}

}  // namespace
}  // namespace tsgraphs::rooms
