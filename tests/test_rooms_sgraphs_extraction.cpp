// The S-Graphs+ baseline's room extraction on constructed inputs: a room, a corridor, the
// counting rule, its map-axis classes on a rotated room, and what it rejects.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rooms_test_support.hpp"
#include "tsgraphs/rooms/sgraphs_room_extraction.hpp"

namespace tsgraphs::rooms {
namespace {

constexpr double kStep = 0.2;  // ESDF slice cell spacing of the baseline's free space (m)

using test::bounds;
using test::Bounds;
using test::room_walls;
using test::wall;

/// Free-space points on the grid of this file's spacing.
std::vector<Eigen::Vector3d> grid(double x0, double x1, double y0, double y1) {
  return test::grid(kStep, x0, x1, y0, y1);
}

/// The room's cluster: cells 0.4 m and more from its walls.
std::vector<Eigen::Vector3d> room_cluster() { return grid(0.4, 4.6, 0.4, 3.6); }

TEST(SgraphsRoomExtraction, FourWallRoomIsBoundedByItsWalls) {
  const auto room = extract_room_sgraphs(room_cluster(), room_walls());
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::room);
  EXPECT_EQ(room->wall_ids, (std::vector<int>{0, 1, 2, 3}));  // x+, x-, y+, y-
  EXPECT_DOUBLE_EQ(room->rect.yaw, 0.0);
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 0.0, 0.01);
  EXPECT_NEAR(b.x1, 5.0, 0.01);
  EXPECT_NEAR(b.y0, 0.0, 0.01);
  EXPECT_NEAR(b.y1, 4.0, 0.01);
}

TEST(SgraphsRoomExtraction, CorridorLengthIsTheClustersExtent) {
  const std::vector<WallCandidate> walls = {wall(0, {0, 0}, {0, 1}, {0, 0}, {10, 0}),
                                            wall(1, {0, 2}, {0, -1}, {0, 2}, {10, 2})};
  const std::vector<Eigen::Vector3d> cluster = grid(2.0, 8.0, 0.4, 1.6);
  const auto room = extract_room_sgraphs(cluster, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::corridor);
  EXPECT_EQ(room->wall_ids, (std::vector<int>{0, 1}));
  EXPECT_NEAR(room->rect.yaw, M_PI / 2.0, 1e-12);  // rect x axis along the pair's normals: map y
  double centroid_x = 0.0;
  for (const Eigen::Vector3d& p : cluster) centroid_x += p.x();
  centroid_x /= static_cast<double>(cluster.size());
  EXPECT_NEAR(room->rect.center.x(), centroid_x, 1e-9);
  EXPECT_NEAR(room->rect.center.y(), 1.0, 0.01);
  EXPECT_NEAR(room->rect.size.x(), 2.0, 0.01);  // across: the planes
  EXPECT_NEAR(room->rect.size.y(), 6.0, 1e-9);  // along: the cluster's min..max, not the 10 m walls
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 2.0, 0.01);
  EXPECT_NEAR(b.x1, 8.0, 0.01);
}

TEST(SgraphsRoomExtraction, PlaneWithMorePointsNearItWins) {
  // A second x+ plane 0.5 m behind wall 0: 3 cluster columns lie within 1.5 m of it, 6 of wall 0.
  std::vector<WallCandidate> walls = room_walls();
  walls.push_back(wall(4, {-0.5, 0}, {1, 0}, {-0.5, 0}, {-0.5, 4}));
  const auto room = extract_room_sgraphs(room_cluster(), walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->wall_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_NEAR(bounds(room->rect).x0, 0.0, 0.01);
  // Without wall 0 the farther plane has enough points and bounds the room.
  walls.erase(walls.begin());
  const auto without = extract_room_sgraphs(room_cluster(), walls);
  ASSERT_TRUE(without.has_value());
  EXPECT_EQ(without->wall_ids, (std::vector<int>{4, 1, 2, 3}));
  EXPECT_NEAR(bounds(without->rect).x0, -0.5, 0.01);
}

TEST(SgraphsRoomExtraction, PlaneTheClusterCrossesWinsByCount) {
  // Points count on either side of a plane: an x+ plane the cluster crosses at x = 3.8 has 12
  // columns within 1.5 m (only 4 on its room side), the real wall 0 has 6; it wins and cuts the
  // room down to x = 3.8..5.
  std::vector<WallCandidate> walls = room_walls();
  walls.push_back(wall(5, {3.8, 0}, {1, 0}, {3.8, -3}, {3.8, 6}));
  const auto room = extract_room_sgraphs(room_cluster(), walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::room);
  EXPECT_EQ(room->wall_ids, (std::vector<int>{5, 1, 2, 3}));
  const Bounds b = bounds(room->rect);
  EXPECT_NEAR(b.x0, 3.8, 0.01);
  EXPECT_NEAR(b.x1, 5.0, 0.01);
}

TEST(SgraphsRoomExtraction, RotatedRoomIsClassifiedByMapAxes) {
  // The room [0, 5] x [0, 4] turned by 30 degrees: each wall still falls in one map-axis class,
  // and the footprint is the axis-aligned box where the walls cross the centroid's axis lines.
  const double yaw = 30.0 * M_PI / 180.0;
  const Eigen::Rotation2Dd R(yaw);
  const Vec2 t(3.0, -2.0);
  const std::vector<WallCandidate> walls = test::moved_room_walls(R, t);
  std::vector<Eigen::Vector3d> cluster = room_cluster();
  for (Eigen::Vector3d& p : cluster) p.head<2>() = R * p.head<2>() + t;
  const auto room = extract_room_sgraphs(cluster, walls);
  ASSERT_TRUE(room.has_value());
  EXPECT_EQ(room->kind, RoomKind::room);
  EXPECT_EQ(room->wall_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_DOUBLE_EQ(room->rect.yaw, 0.0);
  OrientedRect truth;
  truth.center = R * Vec2(2.5, 2.0) + t;
  truth.size = Vec2(5.0, 4.0);
  truth.yaw = yaw;
  EXPECT_LT((room->rect.center - truth.center).norm(), 0.01);
  EXPECT_NEAR(room->rect.size.x(), 5.0 / std::cos(yaw), 0.01);  // 5.77 m, not 5
  EXPECT_NEAR(room->rect.size.y(), 4.0 / std::cos(yaw), 0.01);  // 4.62 m, not 4
  EXPECT_LT(dice(room->rect, truth), 0.85);
}

TEST(SgraphsRoomExtraction, NothingFromEmptyInput) {
  EXPECT_FALSE(extract_room_sgraphs({}, room_walls()).has_value());
  EXPECT_FALSE(extract_room_sgraphs(room_cluster(), {}).has_value());
  // Floor and ceiling are not walls.
  WallCandidate floor_plane;
  floor_plane.id = 7;
  floor_plane.plane = Plane::from_point_normal(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  WallCandidate ceiling = floor_plane;
  ceiling.id = 8;
  ceiling.plane = Plane::from_point_normal(Eigen::Vector3d(0, 0, 2.5), -Eigen::Vector3d::UnitZ());
  EXPECT_FALSE(extract_room_sgraphs(room_cluster(), {floor_plane, ceiling}).has_value());
  // One plane per axis is no pair.
  EXPECT_FALSE(extract_room_sgraphs(room_cluster(), {room_walls()[0], room_walls()[2]}).has_value());
}

TEST(SgraphsRoomExtraction, TooNarrowPairIsRejected) {
  const std::vector<WallCandidate> walls = {wall(0, {0, 0}, {0, 1}, {0, 0}, {6, 0}),
                                            wall(1, {0, 0.9}, {0, -1}, {0, 0.9}, {6, 0.9})};
  const std::vector<Eigen::Vector3d> cluster = grid(0.0, 6.0, 0.1, 0.7);
  EXPECT_FALSE(extract_room_sgraphs(cluster, walls).has_value());  // 0.9 m < min_width 1.0 m
  SgraphsRoomExtractionConfig narrow;
  narrow.min_width = 0.8;
  const auto corridor = extract_room_sgraphs(cluster, walls, narrow);
  ASSERT_TRUE(corridor.has_value());
  EXPECT_EQ(corridor->kind, RoomKind::corridor);
  EXPECT_NEAR(corridor->rect.size.x(), 0.9, 0.01);
  // A cluster one cell wide (extent 0 < min_cluster_extent) gives nothing, whatever the walls.
  EXPECT_FALSE(extract_room_sgraphs(grid(0.0, 6.0, 0.5, 0.5), walls, narrow).has_value());
}

TEST(SgraphsRoomExtraction, RoomWhoseCentreIsOutsideTheClusterIsDropped) {
  // Free space only around a 2 x 1.4 m block in the middle: the centre is 0.81 m from any cell.
  std::vector<Eigen::Vector3d> ring;
  for (const Eigen::Vector3d& p : room_cluster()) {
    const bool in_block = p.x() > 1.5 && p.x() < 3.5 && p.y() > 1.3 && p.y() < 2.7;
    if (!in_block) ring.push_back(p);
  }
  EXPECT_FALSE(extract_room_sgraphs(ring, room_walls()).has_value());
  SgraphsRoomExtractionConfig lenient;
  lenient.max_center_offset = 1.0;
  EXPECT_TRUE(extract_room_sgraphs(ring, room_walls(), lenient).has_value());
}

TEST(SgraphsRoomExtraction, TiesGoToTheLowerIdWhateverTheOrder) {
  std::vector<WallCandidate> walls = room_walls();
  walls.push_back(wall(9, {0, 0}, {1, 0}, {0, 0}, {0, 4}));  // a duplicate of wall 0
  std::vector<WallCandidate> reversed(walls.rbegin(), walls.rend());
  const auto a = extract_room_sgraphs(room_cluster(), walls);
  const auto b = extract_room_sgraphs(room_cluster(), reversed);
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_EQ(a->wall_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(b->wall_ids, a->wall_ids);
}

}  // namespace
}  // namespace tsgraphs::rooms
