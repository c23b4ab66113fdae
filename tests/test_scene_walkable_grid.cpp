// Walkable rasters: the exact distance transform, what blocks a walker, and the exact
// obstacle distance on the scene's geometry (ramps included).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/walkable_grid.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;

namespace {

// A 10 x 6 m room with a door in its north wall, a glass-thin railing and a desk.
const char* kScene = R"(name: grid
levels: [{name: L0, ceiling: 3.0, slab: [[0,0],[10,0],[10,6],[0,6]]}]
walls:
  - {level: L0, from: [0, 4], to: [10, 4], thickness: 0.2, openings: [{at: 5.0, width: 1.0, height: 2.1}]}
railings:
  - {level: L0, from: [2, 1], to: [2, 3], style: glass}
boxes:
  - {level: L0, min: [7, 1, 0], max: [8, 2, 0.75], label: desk}
  - {level: L0, min: [4, 1, 2.5], max: [5, 2, 2.9], label: "a shelf on the wall, above heads"}
trajectory: {waypoints: [[1, 2], [9, 3]]}
)";

bool free_at(const WalkableGrid& g, const Vec2& p) {
  int c, r;
  return g.frame.cell_of(p, &c, &r) && g.free[g.frame.index(c, r)] != 0;
}

}  // namespace

TEST(WalkableGrid, DistanceTransformIsExact) {
  WalkableGrid g;
  g.frame.resolution = 0.1;
  g.frame.cols = 23;
  g.frame.rows = 17;
  g.free.assign(g.frame.size(), 1);
  std::uint64_t x = 12345;
  for (std::uint8_t& f : g.free) {
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    f = (x >> 60) != 0;  // about one cell in sixteen blocked
  }
  compute_clearance(&g);
  for (int r = 0; r < g.frame.rows; ++r) {
    for (int c = 0; c < g.frame.cols; ++c) {
      // Brute force: the nearest blocked cell, or the ring of cells just outside the raster.
      double best = std::numeric_limits<double>::infinity();
      for (int rr = -1; rr <= g.frame.rows; ++rr) {
        for (int cc = -1; cc <= g.frame.cols; ++cc) {
          const bool blocked = !g.frame.inside(cc, rr) || !g.free[g.frame.index(cc, rr)];
          if (blocked) best = std::min(best, std::hypot(cc - c, rr - r) * 0.1);
        }
      }
      ASSERT_NEAR(g.clearance[g.frame.index(c, r)], best, 1e-5) << c << ", " << r;
    }
  }
}

TEST(WalkableGrid, WallsRailingsAndFurnitureBlockDoorsAndWhatHangsAboveDoNot) {
  const Scene s = parse_scene(kScene, "grid.yaml", ".");
  const WalkableGrid g = rasterise_walkable(s, 0, frame_covering(s, 0.05, 0.5));
  EXPECT_TRUE(free_at(g, {1.0, 2.0}));
  EXPECT_FALSE(free_at(g, {3.0, 4.0}));  // the wall
  EXPECT_TRUE(free_at(g, {5.0, 4.0}));   // its door
  EXPECT_FALSE(free_at(g, {2.0, 2.0}));  // the 4 cm railing, whichever cells it crosses
  EXPECT_FALSE(free_at(g, {2.02, 2.0}));
  EXPECT_FALSE(free_at(g, {7.5, 1.5}));   // the desk
  EXPECT_TRUE(free_at(g, {4.5, 1.5}));    // under the shelf that hangs at 2.5 m
  EXPECT_FALSE(free_at(g, {-0.2, 2.0}));  // off the slab
  // The door's middle is 0.5 m from its jambs (cell centres to cell centres, within a cell).
  EXPECT_NEAR(g.clearance_at({5.0, 4.0}), 0.5, 0.06);
}

TEST(WalkableGrid, ObstacleDistanceOnTheSceneGeometry) {
  const Scene s = parse_scene(kScene, "grid.yaml", ".");
  EXPECT_NEAR(obstacle_distance(s, {3.0, 3.0}, 0.0, 2.0), 0.9, 1e-9);   // the wall's face at y 3.9
  EXPECT_NEAR(obstacle_distance(s, {6.5, 1.5}, 0.0, 2.0), 0.5, 1e-9);   // the desk at x 7
  EXPECT_NEAR(obstacle_distance(s, {2.3, 2.0}, 0.0, 2.0), 0.28, 1e-9);  // the railing's half thickness 0.02
  EXPECT_NEAR(obstacle_distance(s, {5.0, 4.0}, 0.0, 2.0), 0.5, 1e-9);   // in the door, to its jambs
  EXPECT_NEAR(obstacle_distance(s, {0.2, 5.0}, 0.0, 0.4), 0.2, 1e-3);   // the slab's edge, probed
  EXPECT_EQ(obstacle_distance(s, {-1.0, 5.0}, 0.0, 0.4), 0.0);          // off the slab
}

TEST(WalkableGrid, OnARampTheStoreyBelowFallsAwayUnderTheWalker) {
  // A ramp from L0 to L1 (3 m up over 20 m along x); a wall of L0 across the ramp's top end
  // (3 m high) is under the feet of a walker who arrives there on L1.
  const char* text = R"(name: ramp
levels:
  - {name: L0, elevation: 0, ceiling: 2.7, slab: [[0,0],[30,0],[30,6],[0,6]]}
  - name: L1
    elevation: 3.0
    ceiling: 2.7
    slab: [[0,0],[30,0],[30,6],[0,6]]
    voids: [[[5,0],[25,0],[25,2],[5,2]]]
walls:
  - {level: L0, from: [25, 0], to: [25, 2], height: 2.7}
ramps:
  - {from_level: L0, to_level: L1, polygon: [[5,0],[25,0],[25,2],[5,2]], axis: [1, 0]}
trajectory: {waypoints: [[2, 1], [28, 1, L1]]}
)";
  const Scene s = parse_scene(text, "ramp.yaml", ".");
  // Half way up (1.5 m) the L0 wall 9.9 m ahead is far; near the top it would be 0.9 m away,
  // but the walker stands 2.9 m up, above it.
  EXPECT_GT(obstacle_distance(s, {15.0, 1.0}, 1.5, 0.5), 0.5);
  EXPECT_LT(obstacle_distance(s, {24.0, 1.0}, 1.2, 0.5), 1.0);  // a low walker would meet it
  EXPECT_GE(obstacle_distance(s, {24.0, 1.0}, 2.85, 0.5), 0.5);
}

TEST(WalkableGrid, AGlazedDoorIsShutAnOpenOneIsNot) {
  const auto grid_with = [](const std::string& pane) {
    const Scene s = parse_scene(std::string(R"(name: glass door
levels: [{name: L0, ceiling: 3.0, slab: [[0,0],[10,0],[10,6],[0,6]]}]
walls: [{level: L0, from: [0, 4], to: [10, 4], thickness: 0.2, openings: [{at: 5.0, width: 1.0, height: 2.1)") +
                                    pane + R"(}]}]
trajectory: {waypoints: [[1, 2], [9, 2]]}
)",
                                "door.yaml", ".");
    return rasterise_walkable(s, 0, GridFrame::around({0, 0}, {10, 6}, 0.05, 0.0));
  };
  EXPECT_TRUE(free_at(grid_with(""), {5.0, 4.0}));
  EXPECT_FALSE(free_at(grid_with(", transmission: 0.8"), {5.0, 4.0}));
}
