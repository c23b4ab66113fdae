// Unsupported rooms (docs/metrics.md) on a toy scene: a good room, a room over a void, one
// off the slab, one across a wall, one through a door and one on a ramp; and the same judged by
// the ground-truth rooms when there is no scene.
#include <gtest/gtest.h>

#include "tsgraphs/eval/room_support.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

using namespace tsgraphs;
using namespace tsgraphs::eval;

namespace {

// L0: a 20 m x 10 m slab with a void [14,18] x [2,8], a ramp up to L1 over its east half
// [16,18] x [2,8], a 1 m thick wall on x = 6 with a door at y 7..8, a railing along the
// void's west edge.
const char* kScene = R"(
name: support
levels:
  - {name: L0, elevation: 0.0, slab: [[0, 0], [20, 0], [20, 10], [0, 10]],
     voids: [[[14, 2], [18, 2], [18, 8], [14, 8]]]}
  - {name: L1, elevation: 1.5, slab: [[18, 0], [30, 0], [30, 10], [18, 10]]}
ramps:
  - {from_level: L0, to_level: L1, polygon: [[16, 2], [18, 2], [18, 8], [16, 8]], axis: [1, 0]}
walls:
  - level: L0
    from: [6, 0]
    to: [6, 10]
    thickness: 1.0
    openings:
      - {at: 7.5, width: 1.0, height: 2.1, sill: 0.0}
railings:
  - {level: L0, from: [14, 2], to: [14, 8], height: 1.0, style: solid}
trajectory:
  level: L0
  waypoints: [[2, 5], [4, 5]]
)";

Polygon2 box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

}  // namespace

TEST(RoomSupport, ScenesVoidsSlabsWallsDoorsAndRamps) {
  const scene::Scene scene = scene::parse_scene(kScene, "support.yaml", ".");
  const std::vector<LevelFootprint> rooms = {
      {box(1, 1, 5, 9), "L0"},        // good: on the slab, clear of the wall
      {box(12, 3, 16, 5), "L0"},      // over the void: x 14..16 of 12..16 is void (the ramp starts at 16)
      {box(18, 0.5, 22, 1.5), "L0"},  // off the slab: x 20..22 of 18..22
      {box(5, 1, 7.5, 3), "L0"},      // across the wall: its footprint [5.5, 6.5] is 1.0 of 2.5 m
      {box(5, 7, 7.5, 8), "L0"},      // through the door: no floor-standing piece there
      {box(16, 3, 18, 7), "L0"},      // on the ramp, inside the void: walkable
      {box(16, 3, 18, 7), "L1"},      // the same footprint from the upper level: the ramp joins it too
      {box(1, 1, 5, 9), "attic"},     // a level the scene does not have
  };
  const std::vector<double> shares = unwalkable_shares(rooms, scene);
  ASSERT_EQ(shares.size(), rooms.size());
  EXPECT_EQ(shares[0], 0.0);
  EXPECT_NEAR(shares[1], 0.5, 1e-12);
  EXPECT_NEAR(shares[2], 0.5, 1e-12);
  EXPECT_NEAR(shares[3], 0.4, 1e-12);  // 20 of 50 columns
  EXPECT_EQ(shares[4], 0.0);
  EXPECT_EQ(shares[5], 0.0);
  EXPECT_EQ(shares[6], 0.0);
  EXPECT_EQ(shares[7], 1.0);
  const RoomSupport s = room_support(shares);
  EXPECT_EQ(s.unsupported, 4);
  EXPECT_EQ(s.max_unwalkable_share, std::optional<double>(1.0));
}

TEST(RoomSupport, ARoomMayReachALittleIntoItsWalls) {
  const scene::Scene scene = scene::parse_scene(kScene, "support.yaml", ".");
  // [1, 5.7] x [1, 9]: 0.2 m of its 4.7 m width in the wall (x from 5.5), except over the door
  // (y 7..8): 4 columns x 140 rows of 94 x 160 cells, under 4 %.
  const std::vector<double> shares = unwalkable_shares({{box(1, 1, 5.7, 9), "L0"}}, scene);
  EXPECT_NEAR(shares[0], 560.0 / 15040.0, 1e-12);
  EXPECT_EQ(room_support(shares).unsupported, 0);
  // Exactly at the threshold is still supported: more than 20 % is needed.
  EXPECT_EQ(room_support({kMaxUnwalkableShare, 0.0}).unsupported, 0);
  EXPECT_EQ(room_support({kMaxUnwalkableShare + 1e-9}).unsupported, 1);
}

TEST(RoomSupport, WithoutASceneTheTrueRoomsAreTheWalkableSpace) {
  // Two true rooms either side of the wall, a corridor on L1 (another level).
  const std::vector<io::RoomTruth> truth = {{"west", "L0", box(0, 0, 5.5, 10), 0.0},
                                            {"east", "L0", box(6.5, 0, 14, 10), 0.0},
                                            {"upper", "L1", box(18, 0, 30, 10), 1.5}};
  const std::vector<LevelFootprint> rooms = {
      {box(1, 1, 5, 9), "L0"},    // inside west
      {box(5, 1, 7.5, 3), "L0"},  // across the wall: 1.0 m of 2.5 m between the rooms
      {box(12, 3, 16, 5), "L0"},  // half past east's edge (the void)
      {box(20, 1, 22, 3), "L0"},  // L1's room, but this footprint is on L0
      {box(20, 1, 22, 3), "L1"},  // inside upper
  };
  const std::vector<double> shares = unwalkable_shares(rooms, truth);
  EXPECT_EQ(shares[0], 0.0);
  EXPECT_NEAR(shares[1], 0.4, 1e-12);
  EXPECT_NEAR(shares[2], 0.5, 1e-12);
  EXPECT_EQ(shares[3], 1.0);
  EXPECT_EQ(shares[4], 0.0);
  EXPECT_EQ(room_support(shares).unsupported, 3);
}

TEST(RoomSupport, NoRoomsNothingUnsupportedAndNoMaximum) {
  const RoomSupport s = room_support({});
  EXPECT_EQ(s.unsupported, 0);
  EXPECT_FALSE(s.max_unwalkable_share.has_value());
  // A footprint that covers no cell centre counts as supported.
  const scene::Scene scene = scene::parse_scene(kScene, "support.yaml", ".");
  EXPECT_EQ(unwalkable_shares({{box(14.51, 4.51, 14.52, 4.52), "L0"}}, scene)[0], 0.0);
}
