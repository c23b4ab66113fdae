// Floor plans: spaces to walls, doors, railings, open joints and ground-truth rooms.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;
using namespace tsgraphs::generator;

namespace {

Scene one_level(const Polygon2& slab) {
  Scene s;
  Level l;
  l.name = "L0";
  l.ceiling = 3.0;
  l.slab = slab;
  s.levels.push_back(l);
  return s;
}

const Polygon2 kFootprint = {{0, 0}, {10, 0}, {10, 7}, {0, 7}};

// Two rooms (4 and 6 m wide, 5 m deep) below a 2 m corridor: x in [0, 10], y in [0, 7].
FloorPlan two_rooms_and_a_corridor() {
  FloorPlan p;
  p.rules.interior_wall = 0.1;
  p.rules.exterior_wall = 0.2;
  const int a = p.add_rect("room_a", SpaceKind::kRoom, {0, 0}, {4, 5});
  const int b = p.add_rect("room_b", SpaceKind::kRoom, {4, 0}, {10, 5});
  const int c = p.add_rect("corridor", SpaceKind::kCorridor, {0, 5}, {10, 7});
  p.doors.push_back({a, c, 1.0, 0.5});
  p.doors.push_back({b, c, 1.2, 0.5});
  return p;
}

int walls_between(const Scene& s, const Vec2& a, const Vec2& b) {
  int n = 0;
  for (const Wall& w : s.walls)
    n += ((w.from - a).norm() < 1e-9 && (w.to - b).norm() < 1e-9) ||
         ((w.from - b).norm() < 1e-9 && (w.to - a).norm() < 1e-9);
  return n;
}

}  // namespace

TEST(FloorPlan, WallsOnEveryBoundaryDoorsWhereWantedRoomsToTheWallFaces) {
  Scene s = one_level(kFootprint);
  const PlanResult r = add_floor_plan(two_rooms_and_a_corridor(), 0, &s);
  EXPECT_EQ(r.doors_made, 2);
  EXPECT_EQ(r.doors_dropped, 0);
  // The corridor's south side is two walls (one per room), the partition one, the facades
  // seven (one per space and side).
  EXPECT_EQ(walls_between(s, {0, 5}, {4, 5}), 1);
  EXPECT_EQ(walls_between(s, {4, 5}, {10, 5}), 1);
  EXPECT_EQ(walls_between(s, {4, 0}, {4, 5}), 1);
  EXPECT_EQ(s.walls.size(), 3u + 7u);
  int openings = 0;
  for (const Wall& w : s.walls) {
    openings += static_cast<int>(w.openings.size());
    const auto on_facade = [](const Vec2& p) {
      return p.x() == 0 || p.x() == 10 || p.y() == 0 || p.y() == 7;
    };
    const bool facade =
        on_facade(w.from) && on_facade(w.to) && (w.from.x() == w.to.x() ? w.from.x() != 4 : w.from.y() != 5);
    EXPECT_DOUBLE_EQ(w.thickness, facade ? 0.2 : 0.1);
  }
  EXPECT_EQ(openings, 2);
  // Ground truth measured to the faces: room_a from the facades (0.1 in) and the partition
  // and corridor walls (0.05 in).
  ASSERT_EQ(s.rooms.size(), 3u);
  EXPECT_EQ(s.rooms[0].name, "room_a");
  EXPECT_NEAR(area(s.rooms[0].polygon), (4 - 0.1 - 0.05) * (5 - 0.1 - 0.05), 1e-9);
  EXPECT_NEAR(area(s.rooms[2].polygon), (10 - 0.2) * (2 - 0.1 - 0.05), 1e-9);
}

TEST(FloorPlan, TheResultLoadsAsASceneWithoutWarnings) {
  Scene s = one_level(kFootprint);
  s.name = "plan";
  add_floor_plan(two_rooms_and_a_corridor(), 0, &s);
  s.trajectory.waypoints = {{{1, 6}, 0, 0}, {{9, 6}, 0, 0}};
  const Scene loaded = parse_scene(scene_yaml(s), "plan.yaml", ".");
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_EQ(loaded.walls.size(), s.walls.size());
  EXPECT_EQ(loaded.rooms.size(), 3u);
}

TEST(FloorPlan, OpenJointsHaveNoWallVoidsGetRailings) {
  FloorPlan p;
  const int a = p.add_rect("corridor_a", SpaceKind::kCorridor, {0, 0}, {6, 2});
  const int b = p.add_rect("corridor_b", SpaceKind::kCorridor, {6, 0}, {8, 6});
  p.add_rect("void", SpaceKind::kVoid, {0, 2}, {6, 6});
  p.open_joints.push_back({a, b});
  p.rules.railing = RailingStyle::kGlass;
  Scene s = one_level({{0, 0}, {8, 0}, {8, 6}, {0, 6}});
  add_floor_plan(p, 0, &s);
  EXPECT_EQ(walls_between(s, {6, 0}, {6, 2}), 0);  // the joint
  // Railings along the void's two edges with corridors; the void's outer edges are facades.
  ASSERT_EQ(s.railings.size(), 2u);
  for (const Railing& r : s.railings) EXPECT_EQ(r.style, RailingStyle::kGlass);
  ASSERT_EQ(s.levels[0].voids.size(), 1u);
  EXPECT_NEAR(area(s.levels[0].voids[0]), 24.0, 1e-9);
  ASSERT_EQ(s.rooms.size(), 2u);  // the void is no room
  // corridor_a: facades on the south (0.125) and west, the railing on the north (0.02), the joint (0) on the
  // east.
  EXPECT_NEAR(area(s.rooms[0].polygon), (6 - 0.125) * (2 - 0.125 - 0.02), 1e-9);
}

TEST(FloorPlan, OverlappingSpacesAreRefused) {
  FloorPlan p;
  p.add_rect("a", SpaceKind::kRoom, {0, 0}, {4, 4});
  p.add_rect("b", SpaceKind::kRoom, {0, 0}, {4, 4});
  Scene s = one_level({{0, 0}, {4, 0}, {4, 4}, {0, 4}});
  EXPECT_THROW(add_floor_plan(p, 0, &s), std::invalid_argument);
}

TEST(FloorPlan, ConnectSpacesJoinsEveryGroupAndDropsDoorsThatCannotBe) {
  FloorPlan p;
  const int c = p.add_rect("corridor", SpaceKind::kCorridor, {0, 0}, {10, 2});
  const int front = p.add_rect("front", SpaceKind::kRoom, {0, 2}, {10, 6});
  const int back = p.add_rect("back", SpaceKind::kRoom, {0, 6}, {10, 10});
  p.doors.push_back({front, c, 1.0, 0.5});
  p.doors.push_back({back, c, 1.0, 0.5});  // they share no wall: dropped, then joined through front
  Rng rng(1);
  connect_spaces(&p, rng);
  ASSERT_EQ(p.doors.size(), 2u);
  EXPECT_EQ(p.doors[0].a, front);
  EXPECT_TRUE((p.doors[1].a == back && p.doors[1].b == front) ||
              (p.doors[1].a == front && p.doors[1].b == back));
}

TEST(FloorPlan, StackedOutlinesMakeLAndTRooms) {
  // An L: a 4 m wide room below a 6 m wide one, left-aligned.
  const Polygon2 l = stacked_outline(0, 4, 0, 3, 0, 6, 5);
  EXPECT_EQ(l.size(), 6u);
  EXPECT_NEAR(area(l), 4 * 3 + 6 * 2, 1e-12);
  EXPECT_FALSE(find_self_intersection(l).has_value());
  // A T: a narrow room centred below a wide one.
  const Polygon2 t = stacked_outline(2, 4, 0, 3, 0, 6, 5);
  EXPECT_EQ(t.size(), 8u);
  EXPECT_NEAR(area(t), 2 * 3 + 6 * 2, 1e-12);
  // Aligned on both sides: a rectangle.
  EXPECT_EQ(stacked_outline(0, 4, 0, 3, 0, 4, 5).size(), 4u);
}

TEST(FloorPlan, InsetPolygonMovesEachEdgeByItsOffset) {
  const Polygon2 square = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  const Polygon2 in = inset_polygon(square, {0.1, 0.2, 0.3, 0.4});
  EXPECT_NEAR(area(in), (4 - 0.2 - 0.4) * (4 - 0.1 - 0.3), 1e-12);
  EXPECT_NEAR(in[0].x(), 0.4, 1e-12);
  EXPECT_NEAR(in[0].y(), 0.1, 1e-12);
  // A non-convex L keeps its shape.
  const Polygon2 l = stacked_outline(0, 4, 0, 3, 0, 6, 5);
  EXPECT_NEAR(area(inset_polygon(l, std::vector<double>(l.size(), 0.1))), area(l) - 0.1 * 22 + 0.01 * 4,
              1e-9);
}
