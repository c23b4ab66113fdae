// Room-based loop candidates: the kept keyframes of an earlier pass inside the re-detected
// room, on its level, nearest first; and the walls a re-detection must share.
#include <gtest/gtest.h>

#include <vector>

#include "tsgraphs/graph/room_loop_closure.hpp"

using namespace tsgraphs;
using namespace tsgraphs::graph;

namespace {

// Keyframes at (x, y, z) with their travel.
SituationalGraph graph_of(const std::vector<Eigen::Vector4d>& xyz_travel) {
  SituationalGraph g;
  for (const Eigen::Vector4d& v : xyz_travel) {
    KeyframeNode k;
    k.pose = make_pose(v.head<3>(), 0.0);
    k.accum_distance = v[3];
    g.add_keyframe(k);
  }
  return g;
}

const Polygon2 kRoom{{0, 0}, {4, 0}, {4, 3}, {0, 3}};

}  // namespace

TEST(RoomLoopClosure, CandidatesAreTheEarlierPassesKeyframesInTheRoomNearestFirst) {
  const SituationalGraph g = graph_of({
      {1, 1, 0.5, 0},       // 0: in the room, first pass
      {3, 2, 0.5, 3},       // 1: in the room, first pass
      {6, 1, 0.5, 6},       // 2: outside it
      {2, 1, 3.5, 9},       // 3: in its footprint a storey up
      {3.5, 2.5, 0.5, 12},  // 4: in the room, but only 6 m of travel before the current one
      {4.5, 2, 0.5, 18},    // 5: the current keyframe, at the door
  });
  RoomLoopClosureConfig config;
  EXPECT_EQ(room_loop_candidates(g, 5, kRoom, 8.0, config), (std::vector<int>{1, 0}));
  config.max_candidates = 1;
  EXPECT_EQ(room_loop_candidates(g, 5, kRoom, 8.0, config), (std::vector<int>{1}));
  EXPECT_TRUE(room_loop_candidates(g, 5, Polygon2{}, 8.0, config).empty());
  EXPECT_THROW(room_loop_candidates(g, 6, kRoom, 8.0, config), std::out_of_range);
}

TEST(RoomLoopClosure, RetiredKeyframesAreNoCandidates) {
  SituationalGraph g = graph_of({{1, 1, 0.5, 0}, {2, 1, 0.5, 1}, {3, 1, 0.5, 2}, {4.5, 2, 0.5, 20}});
  g.add_odometry_edge({0, 1, make_pose({1, 0, 0}, 0.0)});
  g.add_odometry_edge({1, 2, make_pose({1, 0, 0}, 0.0)});
  g.add_odometry_edge({2, 3, make_pose({1.5, 1, 0}, 0.0)});
  g.retire_keyframe(2, 0, {0.05, 0.5}, {0.05, 0.5});
  EXPECT_EQ(room_loop_candidates(g, 3, kRoom, 8.0, {}), (std::vector<int>{1, 0}));
}

TEST(RoomLoopClosure, ARedetectionMustShareItsWalls) {
  const RoomLoopClosureConfig config;  // two walls in common
  EXPECT_TRUE(walls_match({3, 7, 9, 12}, {7, 12, 40}, config));
  EXPECT_FALSE(walls_match({3, 7, 9, 12}, {7, 40, 41}, config));
  EXPECT_FALSE(walls_match({}, {7, 12}, config));
}
