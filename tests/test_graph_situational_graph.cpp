// SituationalGraph bookkeeping: node ids, edge lists and plane merging.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "tsgraphs/graph/situational_graph.hpp"

using namespace tsgraphs;
using namespace tsgraphs::graph;

namespace {

Plane wall_at(double x) { return Plane::from_point_normal({x, 0.0, 0.0}, {-1.0, 0.0, 0.0}); }

// Three keyframes, planes 0 (x = 5), 1 (x = 5.05, the same wall seen again) and 2 (x = 9),
// with plane edges 0-0, 1-1, 2-1, 2-2.
SituationalGraph three_planes() {
  SituationalGraph g;
  for (int k = 0; k < 3; ++k) g.add_keyframe({});
  g.add_plane(wall_at(5.0), true);
  g.add_plane(wall_at(5.05), true);
  g.add_plane(wall_at(9.0), true);
  g.add_plane_edge({0, 0, wall_at(5.0), 10});
  g.add_plane_edge({1, 1, wall_at(4.0), 20});
  g.add_plane_edge({2, 1, wall_at(3.0), 30});
  g.add_plane_edge({2, 2, wall_at(7.0), 40});
  return g;
}

}  // namespace

TEST(SituationalGraph, KeyframeIdsAreTheirIndices) {
  SituationalGraph g;
  KeyframeNode node;
  node.id = 42;  // ignored: the graph assigns ids
  node.scan_index = 7;
  node.pose = make_pose({1.0, 2.0, 0.0}, 0.3);
  EXPECT_EQ(g.add_keyframe(node), 0);
  node.scan_index = 9;
  EXPECT_EQ(g.add_keyframe(node), 1);
  ASSERT_EQ(g.keyframes().size(), 2u);
  EXPECT_EQ(g.keyframes()[0].id, 0);
  EXPECT_EQ(g.keyframes()[1].id, 1);
  EXPECT_EQ(g.keyframes()[1].scan_index, 9u);
  EXPECT_TRUE(g.keyframes()[0].pose.isApprox(node.pose));
}

TEST(SituationalGraph, PlaneIdsAreNeverReused) {
  SituationalGraph g = three_planes();
  EXPECT_EQ(g.planes().size(), 3u);
  for (const auto& [id, node] : g.planes()) EXPECT_EQ(node.id, id);
  EXPECT_TRUE(g.planes().at(2).vertical);
  g.merge_planes(0, 2);
  const int next = g.add_plane(wall_at(1.0), false);
  EXPECT_EQ(next, 3);  // not the freed id 2
  EXPECT_FALSE(g.planes().at(3).vertical);
  EXPECT_DOUBLE_EQ(g.planes().at(3).plane.d, 1.0);
}

TEST(SituationalGraph, EdgesKeepTheirOrder) {
  SituationalGraph g;
  for (int k = 0; k < 4; ++k) g.add_keyframe({});
  g.add_odometry_edge({0, 1, Pose3::Identity(), 0.0});
  g.add_odometry_edge({1, 2, Pose3::Identity(), 0.0});
  g.add_loop_edge({0, 3, make_pose({0.5, 0.0, 0.0}, 0.0), 0.02});
  ASSERT_EQ(g.odometry_edges().size(), 2u);
  EXPECT_EQ(g.odometry_edges()[1].from, 1);
  EXPECT_EQ(g.odometry_edges()[1].to, 2);
  ASSERT_EQ(g.loop_edges().size(), 1u);
  EXPECT_EQ(g.loop_edges()[0].to, 3);
  EXPECT_DOUBLE_EQ(g.loop_edges()[0].fitness, 0.02);
  EXPECT_DOUBLE_EQ(g.loop_edges()[0].measurement.translation().x(), 0.5);
}

TEST(SituationalGraph, MergeRepointsEdgesAndRemovesThePlane) {
  SituationalGraph g = three_planes();
  g.merge_planes(0, 1);
  EXPECT_EQ(g.planes().size(), 2u);
  EXPECT_EQ(g.planes().count(1), 0u);
  EXPECT_DOUBLE_EQ(g.planes().at(0).plane.d, wall_at(5.0).d);  // the kept estimate is unchanged
  ASSERT_EQ(g.plane_edges().size(), 4u);                       // no observation is lost
  const int expected_plane[] = {0, 0, 0, 2};
  const int expected_inliers[] = {10, 20, 30, 40};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(g.plane_edges()[i].plane, expected_plane[i]) << i;
    EXPECT_EQ(g.plane_edges()[i].num_inliers, expected_inliers[i]) << i;  // measurements kept
  }
  EXPECT_DOUBLE_EQ(g.plane_edges()[2].measurement.d, wall_at(3.0).d);
}

TEST(SituationalGraph, BadMergeThrowsAndChangesNothing) {
  SituationalGraph g = three_planes();
  EXPECT_THROW(g.merge_planes(1, 1), std::invalid_argument);
  EXPECT_THROW(g.merge_planes(0, 7), std::invalid_argument);
  EXPECT_THROW(g.merge_planes(7, 0), std::invalid_argument);
  g.merge_planes(0, 1);
  EXPECT_THROW(g.merge_planes(2, 1), std::invalid_argument);  // 1 is gone
  EXPECT_EQ(g.planes().size(), 2u);
  EXPECT_EQ(g.plane_edges()[3].plane, 2);
  EXPECT_EQ(g.plane_edges()[1].plane, 0);
}

namespace {

Plane wall_y(double y, double normal_y) {
  return Plane::from_point_normal({0.0, y, 0.0}, {0.0, normal_y, 0.0});
}

// three_planes() (x = 5, 5.05 facing -x, x = 9 facing -x) plus plane 3 (x = 1, facing +x) and
// planes 4, 5 (y = 0 facing +y, y = 4 facing -y); rooms 0 (planes 3, 0, 4, 5) and 1 (planes 3, 1,
// 4, 5) on floor 0.
SituationalGraph with_rooms() {
  SituationalGraph g = three_planes();
  g.add_plane(Plane::from_point_normal({1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}), true);
  g.add_plane(wall_y(0.0, 1.0), true);
  g.add_plane(wall_y(4.0, -1.0), true);
  RoomNode room;
  room.center = {3.0, 2.0};
  g.add_room(room);
  room.center = {3.2, 2.1};
  g.add_room(room);
  FloorNode floor;
  floor.level = 0;
  g.add_floor(floor);
  g.add_room_edge({0, RoomKind::room, {3, 0, 4, 5}, {}});
  g.add_room_edge({1, RoomKind::room, {3, 1, 4, 5}, {}});
  g.add_floor_room_edge({0, 0});
  g.add_floor_room_edge({0, 1});
  return g;
}

}  // namespace

TEST(SituationalGraph, RoomAndFloorIdsAreNeverReused) {
  SituationalGraph g = with_rooms();
  EXPECT_EQ(g.rooms().size(), 2u);
  for (const auto& [id, node] : g.rooms()) EXPECT_EQ(node.id, id);
  g.remove_room(1);
  RoomNode corridor;
  corridor.id = 0;  // ignored: the graph assigns ids
  corridor.kind = RoomKind::corridor;
  corridor.level = 1;
  EXPECT_EQ(g.add_room(corridor), 2);
  EXPECT_EQ(g.rooms().at(2).kind, RoomKind::corridor);
  EXPECT_EQ(g.rooms().at(2).level, 1);
  EXPECT_EQ(g.floor_of_level(0), 0);
  EXPECT_EQ(g.floor_of_level(1), -1);
  FloorNode second;
  second.level = 0;
  EXPECT_THROW(g.add_floor(second), std::invalid_argument);  // one floor per level
  second.level = 1;
  EXPECT_EQ(g.add_floor(second), 1);
  EXPECT_EQ(g.floor_of_level(1), 1);
  g.remove_floor(0);
  second.level = 0;
  EXPECT_EQ(g.add_floor(second), 2);
  EXPECT_EQ(planes_of(RoomKind::room), 4u);
  EXPECT_EQ(planes_of(RoomKind::corridor), 2u);
}

TEST(SituationalGraph, RoomEdgesAreChecked) {
  SituationalGraph g = with_rooms();
  EXPECT_THROW(g.add_room_edge({7, RoomKind::room, {3, 0, 4, 5}, {}}), std::invalid_argument);
  EXPECT_THROW(g.add_room_edge({0, RoomKind::room, {3, 0}, {}}), std::invalid_argument);
  EXPECT_THROW(g.add_room_edge({0, RoomKind::corridor, {3, 0, 4, 5}, {}}), std::invalid_argument);
  EXPECT_THROW(g.add_room_edge({0, RoomKind::room, {3, 0, 4, 9}, {}}), std::invalid_argument);
  EXPECT_THROW(g.add_room_edge({0, RoomKind::room, {3, 0, 4, 3}, {}}), std::invalid_argument);
  EXPECT_THROW(g.add_floor_room_edge({3, 0}), std::invalid_argument);
  EXPECT_THROW(g.add_floor_room_edge({0, 3}), std::invalid_argument);
  g.add_floor_room_edge({0, 1});  // already there: not repeated
  EXPECT_EQ(g.floor_room_edges().size(), 2u);
  g.add_room_edge({1, RoomKind::corridor, {4, 5}, {2.0, 2.5}});
  ASSERT_EQ(g.room_edges().size(), 3u);
  EXPECT_EQ(g.room_edges()[2].kind, RoomKind::corridor);
  EXPECT_DOUBLE_EQ(g.room_edges()[2].cluster_center.y(), 2.5);
}

TEST(SituationalGraph, MergeRoomsRepointsEdges) {
  SituationalGraph g = with_rooms();
  g.merge_rooms(0, 1);
  EXPECT_EQ(g.rooms().size(), 1u);
  EXPECT_EQ(g.rooms().count(1), 0u);
  EXPECT_DOUBLE_EQ(g.rooms().at(0).center.x(), 3.0);  // the kept estimate is unchanged
  ASSERT_EQ(g.room_edges().size(), 2u);               // both detections kept
  EXPECT_EQ(g.room_edges()[0].room, 0);
  EXPECT_EQ(g.room_edges()[1].room, 0);
  EXPECT_EQ(g.room_edges()[1].planes, (std::vector<int>{3, 1, 4, 5}));
  ASSERT_EQ(g.floor_room_edges().size(), 1u);  // the floor edge is not repeated
  EXPECT_EQ(g.floor_room_edges()[0].room, 0);
  EXPECT_THROW(g.merge_rooms(0, 0), std::invalid_argument);
  EXPECT_THROW(g.merge_rooms(0, 1), std::invalid_argument);  // 1 is gone
}

TEST(SituationalGraph, RemoveRoomAndFloorDropTheirEdges) {
  SituationalGraph g = with_rooms();
  g.remove_room(0);
  ASSERT_EQ(g.room_edges().size(), 1u);
  EXPECT_EQ(g.room_edges()[0].room, 1);
  ASSERT_EQ(g.floor_room_edges().size(), 1u);
  EXPECT_EQ(g.floor_room_edges()[0].room, 1);
  g.remove_floor(0);
  EXPECT_TRUE(g.floor_room_edges().empty());
  EXPECT_TRUE(g.floors().empty());
  EXPECT_EQ(g.rooms().size(), 1u);
  EXPECT_THROW(g.remove_room(0), std::invalid_argument);
  EXPECT_THROW(g.remove_floor(0), std::invalid_argument);
}

TEST(SituationalGraph, MergePlanesRepointsRoomEdges) {
  SituationalGraph g = with_rooms();
  g.merge_planes(0, 1);  // room 1's wall at x = 5.05 is room 0's wall at x = 5
  ASSERT_EQ(g.room_edges().size(), 2u);
  EXPECT_EQ(g.room_edges()[1].planes, (std::vector<int>{3, 0, 4, 5}));
  // A merge that leaves a room edge naming one plane twice removes that edge.
  g.merge_planes(4, 5);
  EXPECT_TRUE(g.room_edges().empty());
  EXPECT_EQ(g.rooms().size(), 2u);  // the rooms themselves stay
}
