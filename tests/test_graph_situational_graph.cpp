// SituationalGraph bookkeeping: node ids, edge lists and plane merging.
#include <gtest/gtest.h>

#include <stdexcept>

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
