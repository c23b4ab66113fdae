// Room segmentation on constructed levels, one rule each: a void between facing walls, a
// corridor at the outer wall, doors, an L-shaped room, a diagonal corridor (and its ends at the
// facades), a ring, a T-junction, a step in a corridor's width, a bay beside a gallery, shelves,
// a wall whose top no ray saw (and a pier in its line), rays over a ramp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "tsgraphs/freespace/sight_map.hpp"
#include "tsgraphs/freespace/wall_top_rays.hpp"
#include "tsgraphs/rooms/room_segmentation.hpp"

namespace tsgraphs::rooms {
namespace {

constexpr double kNode = 0.25;   // the node map's cell (m)
constexpr double kLambda = 0.4;  // the free space's lambda_th (m)
constexpr double kWallZ1 = 2.8;  // a storey's walls reach this (m)

/// A wall along a -> b whose normal points to `inside` (the side it is seen from).
WallCandidate wall(int id, Vec2 a, Vec2 b, Vec2 inside, double top = kWallZ1) {
  WallCandidate w;
  w.id = id;
  Vec2 n(-(b - a).y(), (b - a).x());
  n.normalize();
  if (n.dot(inside - a) < 0.0) n = -n;
  w.plane = Plane::from_point_normal(Eigen::Vector3d(a.x(), a.y(), 0.0), Eigen::Vector3d(n.x(), n.y(), 0.0));
  w.end_a = a;
  w.end_b = b;
  w.z0 = 0.0;
  w.z1 = top;
  w.height = top;
  return w;
}

double distance_to_outline(const Polygon2& poly, const Vec2& p) {
  double d = 1e9;
  for (std::size_t i = 0; i < poly.size(); ++i)
    d = std::min(d, distance_to_segment(p, poly[i], poly[(i + 1) % poly.size()]));
  return d;
}

/// Adds the nodes of `area` (a simple polygon) to a level: ground on a kNode grid, free space
/// where the node is at least lambda inside its outline (walls and obstacles bound the area).
void add_area(const Polygon2& area, SegmentationInput* in) {
  Vec2 lo = area.front(), hi = area.front();
  for (const Vec2& p : area) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (double x = std::floor(lo.x() / kNode) * kNode + 0.5 * kNode; x < hi.x(); x += kNode) {
    for (double y = std::floor(lo.y() / kNode) * kNode + 0.5 * kNode; y < hi.y(); y += kNode) {
      const Vec2 p(x, y);
      if (!contains(area, p)) continue;
      in->ground.push_back(p);
      if (distance_to_outline(area, p) >= kLambda) in->free_space.push_back(p);
    }
  }
}

Polygon2 box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

/// Adds the nodes of the box `outer` with wall pieces `inside` it: ground on a kNode grid
/// everywhere, free space where the node is at least lambda from the outline and every piece.
void add_area_with_walls(const Polygon2& outer, const std::vector<std::pair<Vec2, Vec2>>& inside,
                         SegmentationInput* in) {
  const Vec2 lo = outer[0], hi = outer[2];
  for (double x = lo.x() + 0.5 * kNode; x < hi.x(); x += kNode) {
    for (double y = lo.y() + 0.5 * kNode; y < hi.y(); y += kNode) {
      const Vec2 p(x, y);
      double clear = distance_to_outline(outer, p);
      for (const auto& [a, b] : inside) clear = std::min(clear, distance_to_segment(p, a, b));
      in->ground.push_back(p);
      if (clear >= kLambda) in->free_space.push_back(p);
    }
  }
}

SegmentationInput level() {
  SegmentationInput in;
  in.free_radius = kLambda;
  in.ground_radius = kNode;
  return in;
}

/// The walls round the box, ids from `id`, seen from inside.
void box_walls(double x0, double y0, double x1, double y1, int id, SegmentationInput* in) {
  const Vec2 c(0.5 * (x0 + x1), 0.5 * (y0 + y1));
  in->walls.push_back(wall(id, {x0, y0}, {x1, y0}, c));
  in->walls.push_back(wall(id + 1, {x1, y0}, {x1, y1}, c));
  in->walls.push_back(wall(id + 2, {x1, y1}, {x0, y1}, c));
  in->walls.push_back(wall(id + 3, {x0, y1}, {x0, y0}, c));
}

/// The value of `cells` (one per cell of f) at (x, y), which must lie on f.
std::uint8_t cell_at(const std::vector<std::uint8_t>& cells, const GridFrame& f, double x, double y) {
  int c, r;
  EXPECT_TRUE(f.cell_of({x, y}, &c, &r));
  return cells[f.index(c, r)];
}

double footprint_area(const SegmentedSpace& s) { return area(footprint_of(s.room.rect, s.room.outline)); }

TEST(RoomSegmentation, FourWallRoomIsItsRectangleOnItsWalls) {
  SegmentationInput in = level();
  add_area(box(0, 0, 5, 4), &in);
  box_walls(0, 0, 5, 4, 0, &in);
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 1u);
  const SegmentedSpace& s = seg.spaces[0];
  EXPECT_EQ(s.room.kind, RoomKind::room);
  EXPECT_TRUE(s.room.outline.empty());  // a rectangle
  EXPECT_NEAR(s.room.rect.area(), 20.0, 0.5);
  EXPECT_NEAR(s.centroid.x(), 2.5, 0.1);
  EXPECT_NEAR(s.centroid.y(), 2.0, 0.1);
  EXPECT_EQ(s.room.wall_ids.size(), 4u);  // the room-planes factor's four walls
  EXPECT_EQ(seg.space_at({2.5, 2.0}), 0);
  EXPECT_EQ(seg.space_at({6.0, 2.0}), -1);
}

TEST(RoomSegmentation, AVoidBetweenTwoFacingWallsGivesNoRoom) {
  // Two aisles, y in [0, 2] and [6, 8], their walls facing each other across a void with no
  // floor: each aisle is a space of its own and nothing covers the void.
  SegmentationInput in = level();
  add_area(box(0, 0, 10, 2), &in);
  add_area(box(0, 6, 10, 8), &in);
  in.walls.push_back(wall(0, {0, 0}, {10, 0}, {5, 1}));
  in.walls.push_back(wall(1, {0, 8}, {10, 8}, {5, 7}));
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 2u);
  for (const SegmentedSpace& s : seg.spaces) {
    EXPECT_LT(footprint_area(s), 23.0);  // 20 m^2 and what grows past the open side
    EXPECT_FALSE(contains(footprint_of(s.room.rect, s.room.outline), Vec2(5, 4)));
  }
  EXPECT_EQ(seg.space_at({5, 4}), -1);
}

TEST(RoomSegmentation, ACorridorStopsAtTheOuterWall) {
  // A corridor x in [0, 12] against the outer wall at x = 12; rays or no, nothing lies beyond.
  SegmentationInput in = level();
  add_area(box(0, 0, 12, 2), &in);
  box_walls(0, 0, 12, 2, 0, &in);
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 1u);
  const OrientedRect& r = seg.spaces[0].room.rect;
  EXPECT_EQ(seg.spaces[0].room.kind, RoomKind::corridor);
  for (const Vec2& c : r.corners()) EXPECT_LE(c.x(), 12.0 + 0.05);
  EXPECT_NEAR(std::max(r.size.x(), r.size.y()), 12.0, 0.3);
}

TEST(RoomSegmentation, ADoorInAWallSeparatesTheRoomsItJoins) {
  // Two rooms side by side; the wall between them (x = 5) has a 1.2 m door; its plane's extent
  // spans the door, as the mapper sees it.
  SegmentationInput in = level();
  add_area(box(0, 0, 5, 4), &in);
  add_area(box(5, 0, 10, 4), &in);
  add_area(box(4.6, 1.4, 5.4, 2.6), &in);  // the doorway's ground
  box_walls(0, 0, 10, 4, 0, &in);
  in.walls.push_back(wall(4, {5, 0}, {5, 4}, {2, 2}));
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 2u);
  EXPECT_NE(seg.space_at({2.5, 2}), seg.space_at({7.5, 2}));
  for (const SegmentedSpace& s : seg.spaces) EXPECT_NEAR(footprint_area(s), 20.0, 1.5);
}

TEST(RoomSegmentation, ADoorBesideACornerIsClosedToTheWallItMeets) {
  // The wall between the rooms ends 1 m short of the outer wall: the door is the gap.
  SegmentationInput in = level();
  add_area(box(0, 0, 5, 4), &in);
  add_area(box(5, 0, 10, 4), &in);
  add_area(box(4.6, 3.0, 5.4, 4.0), &in);
  box_walls(0, 0, 10, 4, 0, &in);
  in.walls.push_back(wall(4, {5, 0}, {5, 3}, {2, 2}));
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 2u);
  EXPECT_NE(seg.space_at({2.5, 2}), seg.space_at({7.5, 2}));
}

TEST(RoomSegmentation, TwoDoorsBesideAPierSeparateTheRoomsTheyJoin) {
  // The wall between two rooms has two doors (1.3 m and 1.5 m) with a 0.6 m pier between them:
  // the opening from one long piece to the other is wider than a door, the pier closes it.
  SegmentationInput in = level();
  const std::vector<std::pair<Vec2, Vec2>> pieces = {
      {{5, 0}, {5, 1.2}}, {{5, 2.5}, {5, 3.1}}, {{5, 4.6}, {5, 6}}};
  add_area_with_walls(box(0, 0, 10, 6), pieces, &in);
  box_walls(0, 0, 10, 6, 0, &in);
  int id = 4;
  for (const auto& [a, b] : pieces) in.walls.push_back(wall(id++, a, b, {2, 3}));
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 2u);
  EXPECT_NE(seg.space_at({2.5, 3}), seg.space_at({7.5, 3}));
  for (const SegmentedSpace& s : seg.spaces) EXPECT_NEAR(footprint_area(s), 30.0, 2.0);
}

TEST(RoomSegmentation, APierSeenOnlyBelowItsLintelStillSeparatesTheRooms) {
  // The same two doors, seen by a low sensor: the pier is mapped only up to 1.6 m (its lintel
  // unseen, and no ray above it). It lies in the wall's line a door's width from its pieces: it
  // is the same wall and closes the opening. The same plane 0.5 m off the line (something
  // standing in the room) joins nothing: the opening is wider than a door, one space.
  SegmentationInput in = level();
  const std::vector<std::pair<Vec2, Vec2>> pieces = {
      {{5, 0}, {5, 1.2}}, {{5, 2.5}, {5, 3.1}}, {{5, 4.6}, {5, 6}}};
  add_area_with_walls(box(0, 0, 10, 6), pieces, &in);
  box_walls(0, 0, 10, 6, 0, &in);
  in.walls.push_back(wall(4, pieces[0].first, pieces[0].second, {2, 3}));
  in.walls.push_back(wall(5, pieces[2].first, pieces[2].second, {2, 3}));
  WallCandidate pier = wall(6, pieces[1].first, pieces[1].second, {2, 3}, 1.6);
  pier.top_seen = false;
  in.walls.push_back(pier);
  RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 2u);
  EXPECT_NE(seg.space_at({2.5, 3}), seg.space_at({7.5, 3}));
  in.walls.back() = wall(6, {4.5, 2.5}, {4.5, 3.1}, {2, 3}, 1.6);
  in.walls.back().top_seen = false;
  seg = segment_rooms(in);
  EXPECT_EQ(seg.space_at({2.5, 3}), seg.space_at({7.5, 3}));
}

TEST(RoomSegmentation, ADoorBesideAJointOfTheRoomsBelowStaysClosed) {
  // A wall between a room to the north and two rooms to the south has a 1 m door; the wall
  // between the two southern rooms meets it 0.3 m past the door's east post. The door is
  // closed from its east post to the 0.6 m piece of wall across it, not to that joint behind
  // the post.
  SegmentationInput in = level();
  const std::vector<std::pair<Vec2, Vec2>> inner = {
      {{2, 0}, {10, 0}}, {{0.4, 0}, {1, 0}}, {{2.3, -4}, {2.3, -0.05}}};
  add_area_with_walls(box(0.4, -4, 10, 4), inner, &in);
  box_walls(0.4, -4, 10, 4, 0, &in);
  in.walls.push_back(wall(4, inner[0].first, inner[0].second, {5, 2}));
  in.walls.push_back(wall(5, inner[1].first, inner[1].second, {0.7, 2}));
  in.walls.push_back(wall(6, inner[2].first, inner[2].second, {1, -2}));
  const RoomSegmentation seg = segment_rooms(in);
  const int north = seg.space_at({5, 2}), south_west = seg.space_at({1.3, -2}),
            south_east = seg.space_at({6, -2});
  ASSERT_GE(north, 0);
  ASSERT_GE(south_west, 0);
  EXPECT_NE(north, south_west);
  EXPECT_NE(north, south_east);
  EXPECT_NE(south_west, south_east);
}

TEST(RoomSegmentation, AnLShapedRoomIsOneRoomWithItsOutline) {
  const Polygon2 l = {{0, 0}, {6, 0}, {6, 3}, {3, 3}, {3, 6}, {0, 6}};
  SegmentationInput in = level();
  add_area(l, &in);
  for (std::size_t i = 0; i < l.size(); ++i)
    in.walls.push_back(wall(static_cast<int>(i), l[i], l[(i + 1) % l.size()], {1, 1}));
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 1u);
  const SegmentedSpace& s = seg.spaces[0];
  EXPECT_EQ(s.room.kind, RoomKind::room);
  ASSERT_GE(s.room.outline.size(), 6u);  // no rectangle
  EXPECT_GT(iou(s.room.outline, l), 0.85);
  EXPECT_TRUE(s.room.wall_ids.empty());  // no four-plane factor for an L
}

TEST(RoomSegmentation, ADiagonalCorridorIsOneCorridorAlongItsAxis) {
  const double yaw = 40.0 * M_PI / 180.0;
  const Eigen::Rotation2Dd R(yaw);
  Polygon2 corridor;
  for (const Vec2& p : box(0, 0, 12, 2)) corridor.push_back(R * p);
  SegmentationInput in = level();
  add_area(corridor, &in);
  for (std::size_t i = 0; i < 4; ++i)
    in.walls.push_back(wall(static_cast<int>(i), corridor[i], corridor[(i + 1) % 4], R * Vec2(6, 1)));
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 1u);
  const SegmentedSpace& s = seg.spaces[0];
  EXPECT_EQ(s.room.kind, RoomKind::corridor);
  EXPECT_TRUE(s.room.outline.empty());
  const OrientedRect& r = s.room.rect;
  const double length = std::max(r.size.x(), r.size.y());
  EXPECT_NEAR(length, 12.0, 0.4);
  // Its long axis runs at 40 degrees (either way round).
  const double long_yaw = r.size.x() >= r.size.y() ? r.yaw : r.yaw + M_PI / 2.0;
  EXPECT_NEAR(std::abs(std::sin(long_yaw - yaw)), 0.0, 0.05);
  EXPECT_GT(iou(r.corners(), corridor), 0.85);
}

TEST(RoomSegmentation, ADiagonalCorridorStopsAtTheFacadesItRunsInto) {
  // A corridor 2 m wide at 40 degrees between two facades, x = 0 and x = 16: its ends are
  // slanted, so its smallest rectangle (which it fills 0.89 of) runs past both facades.
  const double yaw = 40.0 * M_PI / 180.0;
  const Vec2 u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x());
  const double w = 2.0, x1 = 16.0;
  const Vec2 a0 = Vec2(0, 0), b0 = a0 + x1 / u.x() * u;          // its south side, facade to facade
  const Vec2 a1 = Vec2(0, w / u.x()), b1 = a1 + x1 / u.x() * u;  // its north side
  const Polygon2 corridor = {a0, b0, b1, a1};
  SegmentationInput in = level();
  add_area(corridor, &in);
  const Vec2 mid = 0.25 * (a0 + b0 + a1 + b1);
  in.walls.push_back(wall(0, a0, b0, mid));
  in.walls.push_back(wall(1, a1, b1, mid));
  in.walls.push_back(wall(2, {0, -2}, {0, 4}, mid));     // the west facade
  in.walls.push_back(wall(3, {x1, 10}, {x1, 18}, mid));  // the east facade
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 1u);
  const SegmentedSpace& s = seg.spaces[0];
  EXPECT_EQ(s.room.kind, RoomKind::corridor);
  const Polygon2 footprint = footprint_of(s.room.rect, s.room.outline);
  for (const Vec2& c : footprint) {
    EXPECT_GE(c.x(), -0.1);
    EXPECT_LE(c.x(), x1 + 0.1);
  }
  EXPECT_GT(iou(footprint, corridor), 0.85);
  // Its long sides still make the corridor's factor, along its own axis.
  EXPECT_EQ(s.room.wall_ids.size(), 2u);
  const OrientedRect& r = s.room.rect;
  const double long_yaw = r.size.x() >= r.size.y() ? r.yaw : r.yaw + M_PI / 2.0;
  EXPECT_NEAR(std::abs(std::sin(long_yaw - yaw)), 0.0, 0.05);
}

TEST(RoomSegmentation, ARingCorridorIsCutIntoItsLegs) {
  // A 2 m ring round a 10 x 6 m void with railings (obstacles, no walls) on its inner side.
  SegmentationInput in = level();
  const Polygon2 outer = box(0, 0, 14, 10), inner = box(2, 2, 12, 8);
  for (double x = 0.5 * kNode; x < 14.0; x += kNode) {
    for (double y = 0.5 * kNode; y < 10.0; y += kNode) {
      const Vec2 p(x, y);
      if (contains(inner, p)) continue;
      in.ground.push_back(p);
      if (distance_to_outline(outer, p) >= kLambda && distance_to_outline(inner, p) >= kLambda)
        in.free_space.push_back(p);
    }
  }
  box_walls(0, 0, 14, 10, 0, &in);
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 4u);
  for (const SegmentedSpace& s : seg.spaces) {
    EXPECT_EQ(s.room.kind, RoomKind::corridor);
    EXPECT_FALSE(contains(footprint_of(s.room.rect, s.room.outline), Vec2(7, 5)));  // never over the void
  }
  const int south = seg.space_at({7, 1}), north = seg.space_at({7, 9}), west = seg.space_at({1, 5}),
            east = seg.space_at({13, 5});
  EXPECT_EQ(std::set<int>({south, north, west, east}).size(), 4u);
}

/// The four mirror images a rule must hold in (x, y flipped or not): in two of them the
/// outline runs the other way round a corner.
const Vec2 kMirrors[4] = {{1, 1}, {-1, 1}, {1, -1}, {-1, -1}};

/// `shape` mirrored by `m` (its coordinates times m's), counter-clockwise again.
Polygon2 mirrored(const Polygon2& shape, const Vec2& m) {
  Polygon2 out;
  for (const Vec2& p : shape) out.push_back(p.cwiseProduct(m));
  if (m.x() * m.y() < 0.0) std::reverse(out.begin(), out.end());
  return out;
}

/// A level of `shape` (mirrored by m) with a wall along each of its edges.
SegmentationInput walled_level(const Polygon2& shape, const Vec2& m, const Vec2& inside) {
  const Polygon2 c = mirrored(shape, m);
  SegmentationInput in = level();
  add_area(c, &in);
  for (std::size_t i = 0; i < c.size(); ++i)
    in.walls.push_back(wall(static_cast<int>(i), c[i], c[(i + 1) % c.size()], inside.cwiseProduct(m)));
  return in;
}

TEST(RoomSegmentation, ALongHallWiderThanACorridorIsNotCutAtItsBend) {
  // An L of 6 m wide legs, 24 and 18 m long: long for its width, but a hall, not a passage.
  const Polygon2 l = {{0, 0}, {24, 0}, {24, 6}, {6, 6}, {6, 18}, {0, 18}};
  const SegmentationInput in = walled_level(l, {1, 1}, {1, 1});
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 1u);
  EXPECT_GT(iou(seg.spaces[0].room.outline, l), 0.85);
  RoomSegmentationConfig no_limit;
  no_limit.max_corridor_width = 1e6;  // what the width limit changes: the hall cut in two
  EXPECT_EQ(segment_rooms(in, no_limit).spaces.size(), 2u);
  // The same L at 2 m wide is a corridor: cut into its two legs.
  const Polygon2 narrow = {{0, 0}, {24, 0}, {24, 2}, {2, 2}, {2, 18}, {0, 18}};
  EXPECT_EQ(segment_rooms(walled_level(narrow, {1, 1}, {1, 1})).spaces.size(), 2u);
}

TEST(RoomSegmentation, ATJunctionKeepsItsThroughCorridorWhole) {
  // A 16 x 2 m corridor with a 2 m side corridor 6 m long off its middle: the through corridor
  // is one space, cut from the side corridor across its mouth.
  const Polygon2 t = {{0, 0}, {16, 0}, {16, 2}, {8, 2}, {8, 8}, {6, 8}, {6, 2}, {0, 2}};
  for (const Vec2& m : kMirrors) {
    const RoomSegmentation seg = segment_rooms(walled_level(t, m, {1, 1}));
    const auto at = [&](double x, double y) { return seg.space_at(Vec2(x, y).cwiseProduct(m)); };
    ASSERT_GE(at(1, 1), 0) << m.transpose();
    EXPECT_EQ(at(1, 1), at(15, 1)) << m.transpose();
    EXPECT_EQ(at(1, 1), at(7, 1)) << m.transpose();
    ASSERT_GE(at(7, 6), 0) << m.transpose();
    EXPECT_NE(at(7, 6), at(1, 1)) << m.transpose();
  }
}

TEST(RoomSegmentation, ACorridorThatWidensIsCutWhereItWidens) {
  // A 1.6 m corridor 10 m long running on as a 3 m one, one side straight (a library's two
  // corridors): two corridors, cut across the narrow one's end.
  const Polygon2 c = {{0, 0}, {20, 0}, {20, 3}, {10, 3}, {10, 1.6}, {0, 1.6}};
  for (const Vec2& m : kMirrors) {
    SegmentationInput in = level();
    add_area(mirrored(c, m), &in);
    // A wall along its straight side only, shelves along the other: no wall's end closes the step.
    in.walls.push_back(
        wall(0, Vec2(0, 0).cwiseProduct(m), Vec2(20, 0).cwiseProduct(m), Vec2(5, 0.8).cwiseProduct(m)));
    const RoomSegmentation seg = segment_rooms(in);
    const auto at = [&](double x, double y) { return seg.space_at(Vec2(x, y).cwiseProduct(m)); };
    ASSERT_GE(at(5, 0.8), 0) << m.transpose();
    ASSERT_GE(at(15, 1.5), 0) << m.transpose();
    EXPECT_NE(at(5, 0.8), at(15, 1.5)) << m.transpose();
    EXPECT_EQ(at(11, 0.5), at(15, 1.5)) << m.transpose();
  }
}

TEST(RoomSegmentation, ABayBesideAGalleryIsCutAlongTheGallerysSide) {
  // A 24 x 2 m gallery with a 5 x 2 m bay open along its side at one end (a landing beside a
  // gallery): the gallery's side runs on across the bay's opening.
  const Polygon2 c = {{0, 0}, {5, 0}, {5, 2}, {24, 2}, {24, 4}, {0, 4}};
  for (const Vec2& m : kMirrors) {
    const RoomSegmentation seg = segment_rooms(walled_level(c, m, {10, 3}));
    const auto at = [&](double x, double y) { return seg.space_at(Vec2(x, y).cwiseProduct(m)); };
    ASSERT_GE(at(1, 3), 0) << m.transpose();
    EXPECT_EQ(at(1, 3), at(23, 3)) << m.transpose();
    ASSERT_GE(at(2.5, 1), 0) << m.transpose();
    EXPECT_NE(at(2.5, 1), at(1, 3)) << m.transpose();
  }
}

TEST(RoomSegmentation, ABayWhoseMouthIsRaggedIsCutAlongTheGallerysSide) {
  // A 22 x 2 m gallery along a railing (no wall) that ends in a ragged slant where a ramp's
  // top meets a 4 x 1.5 m landing below the gallery's east end (the free space's outline
  // there: 1.6 m at 18 degrees). The slant is the raster's, the building's sides run along
  // its walls: the cut continues the gallery's side, not the slant.
  const Polygon2 c = {{0, 2}, {16.5, 2}, {18, 1.5}, {18, 0}, {22, 0}, {22, 4}, {0, 4}};
  for (const Vec2& m : kMirrors) {
    SegmentationInput in = level();
    add_area(mirrored(c, m), &in);
    const Vec2 inside(10, 3);
    for (const auto& [a, b] : std::vector<std::pair<Vec2, Vec2>>{
             {{0, 4}, {22, 4}}, {{0, 2}, {0, 4}}, {{22, 0}, {22, 4}}, {{18, 0}, {22, 0}}})
      in.walls.push_back(wall(static_cast<int>(in.walls.size()), a.cwiseProduct(m), b.cwiseProduct(m),
                              inside.cwiseProduct(m)));
    const RoomSegmentation seg = segment_rooms(in);
    const auto at = [&](double x, double y) { return seg.space_at(Vec2(x, y).cwiseProduct(m)); };
    ASSERT_GE(at(10, 3), 0) << m.transpose();
    ASSERT_GE(at(20, 0.7), 0) << m.transpose();
    EXPECT_NE(at(20, 0.7), at(10, 3)) << m.transpose();
    EXPECT_EQ(at(21.5, 3), at(10, 3)) << m.transpose();      // the gallery's east end stays the gallery's
    EXPECT_EQ(at(21.5, 1.2), at(20, 0.7)) << m.transpose();  // the landing's far corner is the landing's
  }
}

TEST(RoomSegmentation, ShelfRowsDoNotCutAHall) {
  // A 10 x 8 m hall with rows of 2.1 m shelves (planes that do not reach a wall's height).
  SegmentationInput in = level();
  add_area(box(0, 0, 10, 8), &in);
  box_walls(0, 0, 10, 8, 0, &in);
  for (int row = 0; row < 4; ++row) {
    const double y = 2.0 + 1.5 * row;
    in.walls.push_back(wall(10 + 2 * row, {1.5, y}, {8.5, y}, {5, y - 1}, 2.1));
    in.walls.push_back(wall(11 + 2 * row, {1.5, y + 0.5}, {8.5, y + 0.5}, {5, y + 1}, 2.1));
  }
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 1u);
  EXPECT_NEAR(footprint_area(seg.spaces[0]), 80.0, 4.0);
}

TEST(RoomSegmentation, PillarsDoNotMakeAHallACorridor) {
  // A 16 x 12 m hall with a 4 x 1.5 m desk island (an obstacle, no wall) and six 0.5 m pillars
  // on a 4 m grid, their sides mapped as walls: the pillars narrow the widest disc to ~5.6 m,
  // which would make the hall "long for its width" and cut it at the island's corners.
  SegmentationInput in = level();
  const Polygon2 hall = box(0, 0, 16, 12), island = box(9.5, 8.5, 13.5, 10);
  std::vector<Polygon2> pillars;
  for (double x : {4.0, 8.0, 12.0})
    for (double y : {4.0, 8.0})
      if (!(x == 12.0 && y == 8.0)) pillars.push_back(box(x - 0.25, y - 0.25, x + 0.25, y + 0.25));
  for (double x = 0.5 * kNode; x < 16.0; x += kNode) {
    for (double y = 0.5 * kNode; y < 12.0; y += kNode) {
      const Vec2 p(x, y);
      double clear =
          std::min(distance_to_outline(hall, p), contains(island, p) ? 0.0 : distance_to_outline(island, p));
      for (const Polygon2& q : pillars)
        clear = std::min(clear, contains(q, p) ? 0.0 : distance_to_outline(q, p));
      if (clear <= 0.0) continue;
      in.ground.push_back(p);
      if (clear >= kLambda) in.free_space.push_back(p);
    }
  }
  box_walls(0, 0, 16, 12, 0, &in);
  int id = 10;
  for (const Polygon2& q : pillars) {
    const Vec2 c = 0.5 * (q[0] + q[2]);
    for (std::size_t i = 0; i < 4; ++i) {
      const Vec2 a = q[i], b = q[(i + 1) % 4];
      in.walls.push_back(wall(id++, a, b, a + b - c));  // seen from outside the pillar
    }
  }
  const RoomSegmentation seg = segment_rooms(in);
  ASSERT_EQ(seg.spaces.size(), 1u);
  EXPECT_EQ(seg.spaces[0].room.kind, RoomKind::room);
  EXPECT_NEAR(seg.spaces[0].area, 16.0 * 12.0 - 6.0, 12.0);
}

TEST(RoomSegmentation, AWallWhoseTopNoRaySawDividesTheLevel) {
  // Two 3 x 4 m rooms side by side; a low sensor saw their shared wall only up to 1.6 m. No
  // ray passed above it, so it may reach the ceiling: it divides them. Had rays passed above
  // it (a 1.6 m partition), it would not.
  SegmentationInput in = level();
  add_area(box(0, 0, 6, 4), &in);
  box_walls(0, 0, 6, 4, 0, &in);
  WallCandidate shared = wall(10, {3, 0}, {3, 4}, {1, 2}, 1.6);
  shared.top_seen = false;
  in.walls.push_back(shared);
  EXPECT_EQ(segment_rooms(in).spaces.size(), 2u);
  in.walls.back().top_seen = true;
  EXPECT_EQ(segment_rooms(in).spaces.size(), 1u);
}

TEST(RoomSegmentation, AFreeStandingShelfWhoseTopNoRaySawDividesNothing) {
  // A 12 x 8 m hall with a 9 m shelf row down its middle, its ends 1.5 m from the walls (a door's
  // width: were it a wall, both gaps would be closed); a low sensor saw neither face's top. The
  // row joins no wall, one walks round it: one space. A plane of the same height that meets the
  // hall's wall at one end (a partition with a 1.5 m door) joins the walls: it divides the hall.
  SegmentationInput in = level();
  add_area(box(0, 0, 12, 8), &in);
  box_walls(0, 0, 12, 8, 0, &in);
  for (const double y : {3.75, 4.25}) {
    WallCandidate face = wall(in.walls.size(), {1.5, y}, {10.5, y}, {6, y < 4.0 ? 0.0 : 8.0}, 1.6);
    face.top_seen = false;
    in.walls.push_back(face);
  }
  EXPECT_EQ(segment_rooms(in).spaces.size(), 1u);
  in.walls.resize(4);
  WallCandidate partition = wall(4, {0, 4}, {10.5, 4}, {6, 0}, 1.6);
  partition.top_seen = false;
  in.walls.push_back(partition);
  EXPECT_EQ(segment_rooms(in).spaces.size(), 2u);
  // Its end 0.5 m short of the wall (more than wall_joint_gap): free-standing again.
  in.walls.back() = wall(4, {0.5, 4}, {10.5, 4}, {6, 0}, 1.6);
  in.walls.back().top_seen = false;
  EXPECT_EQ(segment_rooms(in).spaces.size(), 1u);
}

TEST(RoomSegmentation, WhatOnlyTheRaysSawIsARoomToo) {
  // A sensor 1.7 m up sees no floor in a 4 x 4 m room: the rays to its walls still show it.
  freespace::SightMap sight(0.0, {});
  const Eigen::Vector3d sensor(2.0, 2.0, 1.7);
  std::vector<Eigen::Vector3d> returns;
  for (int i = 0; i < 360; ++i) {
    const double a = i * M_PI / 180.0;
    const Vec2 d(std::cos(a), std::sin(a));
    // To the nearest wall of [0, 4]^2 along d, at 1.2 m height.
    double t = 1e9;
    if (d.x() > 1e-9) t = std::min(t, 2.0 / d.x());
    if (d.x() < -1e-9) t = std::min(t, -2.0 / d.x());
    if (d.y() > 1e-9) t = std::min(t, 2.0 / d.y());
    if (d.y() < -1e-9) t = std::min(t, -2.0 / d.y());
    returns.emplace_back(2.0 + t * d.x(), 2.0 + t * d.y(), 1.2);
  }
  sight.add_scan(sensor, returns);
  SegmentationInput in = level();
  RoomSegmentationConfig cfg;
  in.frame = GridFrame::around({0, 0}, {4, 4}, cfg.cell, 1.0);
  in.seen = sight.open_cells(in.frame);
  box_walls(0, 0, 4, 4, 0, &in);
  const RoomSegmentation seg = segment_rooms(in, cfg);
  ASSERT_EQ(seg.spaces.size(), 1u);
  EXPECT_NEAR(footprint_area(seg.spaces[0]), 16.0, 1.0);
}

TEST(RoomSegmentation, ACornerBothOfWhoseWallsStopShortOfItIsClosed) {
  // A 6 x 4 m room whose west and north walls were mapped 0.3 m short of their corner, and a
  // strip of cells 0.3 m wide outside the north wall that rays marked (past the face they ended
  // on): the room does not take the strip in through the gap at the corner.
  SegmentationInput in = level();
  RoomSegmentationConfig cfg;
  add_area(box(0, 0, 6, 4), &in);
  in.frame = GridFrame::around({0, 0}, {6, 4}, cfg.cell, 1.0);
  in.seen.assign(in.frame.size(), 0);
  for (int r = 0; r < in.frame.rows; ++r) {
    for (int c = 0; c < in.frame.cols; ++c) {
      const Vec2 p = in.frame.center(c, r);
      if (p.x() > -0.3 && p.x() < 6.0 && p.y() > 4.0 && p.y() < 4.3) in.seen[in.frame.index(c, r)] = 1;
    }
  }
  in.walls.push_back(wall(0, {0, 0}, {6, 0}, {3, 2}));
  in.walls.push_back(wall(1, {6, 0}, {6, 4}, {3, 2}));
  in.walls.push_back(wall(2, {6, 4}, {0.3, 4}, {3, 2}));
  in.walls.push_back(wall(3, {0, 3.7}, {0, 0}, {3, 2}));
  const RoomSegmentation seg = segment_rooms(in, cfg);
  ASSERT_GE(seg.spaces.size(), 1u);
  const int room = seg.space_at({3, 2});
  ASSERT_GE(room, 0);
  EXPECT_NEAR(footprint_area(seg.spaces[static_cast<std::size_t>(room)]), 24.0, 1.0);
  EXPECT_NE(seg.space_at({3, 4.15}), room);
}

TEST(RoomSegmentation, WhatTheRaysSawOverARampIsNoFloorOfTheLevel) {
  // A 5 x 4 m landing open at x = 5 to a ramp rising east; the rays pass at walking height over
  // the ramp's first metres (seen), but the ramp's traversable nodes lie higher than the level.
  SegmentationInput in = level();
  RoomSegmentationConfig cfg;
  add_area(box(0, 0, 5, 4), &in);
  in.walls.push_back(wall(0, {0, 0}, {12, 0}, {2, 2}));
  in.walls.push_back(wall(1, {12, 4}, {0, 4}, {2, 2}));
  in.walls.push_back(wall(2, {0, 4}, {0, 0}, {2, 2}));
  in.frame = GridFrame::around({0, 0}, {12, 4}, cfg.cell, 1.0);
  in.seen.assign(in.frame.size(), 0);
  for (int r = 0; r < in.frame.rows; ++r)
    for (int c = 0; c < in.frame.cols; ++c) {
      const Vec2 p = in.frame.origin + cfg.cell * Vec2(c + 0.5, r + 0.5);
      if (p.x() > 0.0 && p.x() < 12.0 && p.y() > 0.0 && p.y() < 4.0) in.seen[in.frame.index(c, r)] = 1;
    }
  const double without = footprint_area(segment_rooms(in, cfg).spaces.at(0));
  EXPECT_GT(without, 40.0);  // the rays alone carry the space up the ramp
  for (double x = 5.0 + 0.5 * kNode; x < 12.0; x += kNode)
    for (double y = 0.5 * kNode; y < 4.0; y += kNode) in.raised.emplace_back(x, y);
  const RoomSegmentation seg = segment_rooms(in, cfg);
  ASSERT_EQ(seg.spaces.size(), 1u);
  EXPECT_NEAR(footprint_area(seg.spaces[0]), 20.0, 2.0);
}

TEST(SightMap, RaysThatGoBelowTheFloorMarkNoFloor) {
  // A sensor 1 m up looks across a floor x in [0, 3] into a void beyond, whose returns come
  // from 3 m below: the floor is open, the void (where the rays are below the floor) is not.
  freespace::SightMap sight(0.0, {});
  std::vector<Eigen::Vector3d> returns;
  for (int k = 0; k < 40; ++k) {
    const double y = -1.0 + 0.05 * k;
    returns.emplace_back(2.5, y, 0.0);  // the floor
    returns.emplace_back(12.0, y,
                         -3.0);  // the storey below, through the void (crossing the floor's height at x = 3)
  }
  sight.add_scan({0.0, 0.0, 1.0}, returns);
  const GridFrame f = GridFrame::around({-1, -1}, {7, 1}, 0.1, 0.0);
  const std::vector<std::uint8_t> open = sight.open_cells(f);
  const auto at = [&](double x, double y) { return cell_at(open, f, x, y); };
  EXPECT_EQ(at(1.0, 0.0), 1);
  EXPECT_EQ(at(2.45, 0.0), 1);
  EXPECT_EQ(at(5.5, 0.0), 0);
  EXPECT_EQ(at(-0.5, 0.9), 0);  // never seen
}

TEST(SightMap, ARayUnderTheFloorBeyondAVoidMarksNothingAboveIt) {
  // A sensor 1 m up on a floor x in [0, 3], a void x in [3, 5], a room's floor beyond. Rays to
  // the storey below cross the floor's height in the void (x = 3.5) and run on under the room;
  // rays to the room's floor pass above the void. The void is no floor, the room is open.
  freespace::SightMap sight(0.0, {});
  std::vector<Eigen::Vector3d> returns;
  for (int k = 0; k < 40; ++k) {
    const double y = -1.0 + 0.05 * k;
    for (double x : {6.0, 7.0, 8.0}) returns.emplace_back(x, y * x / 14.0, 0.0);
    for (int deep = 0; deep < 3; ++deep) returns.emplace_back(14.0, y, -3.0);
  }
  sight.add_scan({0.0, 0.0, 1.0}, returns);
  const GridFrame f = GridFrame::around({-1, -1}, {15, 1}, 0.1, 0.0);
  const std::vector<std::uint8_t> open = sight.open_cells(f);
  const auto at = [&](double x, double y) { return cell_at(open, f, x, y); };
  EXPECT_EQ(at(2.0, 0.0), 1);
  EXPECT_EQ(at(4.5, 0.0), 0);  // where the rays went down through the slab's thickness
  EXPECT_EQ(at(6.5, 0.0), 1);  // above the rays that ran on under the floor
}

TEST(SightMap, RaysMarkOnlyWhereTheyAreAtWalkingHeight) {
  // A sensor 1 m up; rays rising to a ceiling 3 m up, 10 m out, pass the headroom (2 m) at
  // x = 5; rays from a sensor 2.5 m up (above the headroom) come down to a floor 10 m out,
  // entering it at x = 2. Cells are open where the ray is at walking height, not beyond.
  const GridFrame f = GridFrame::around({-1, -1}, {11, 1}, 0.1, 0.0);
  std::vector<Eigen::Vector3d> up, down;
  for (int k = 0; k < 40; ++k) {
    const double y = -0.5 + 0.025 * k;
    up.emplace_back(10.0, y, 3.0);
    down.emplace_back(10.0, y, 0.0);
  }
  freespace::SightMap rising(0.0, {});
  rising.add_scan({0.0, 0.0, 1.0}, up);
  std::vector<std::uint8_t> open = rising.open_cells(f);
  EXPECT_EQ(cell_at(open, f, 4.8, 0.0), 1);
  EXPECT_EQ(cell_at(open, f, 5.3, 0.0), 0);
  EXPECT_EQ(cell_at(open, f, 9.5, 0.0), 0);
  freespace::SightMap falling(0.0, {});
  falling.add_scan({0.0, 0.0, 2.5}, down);
  open = falling.open_cells(f);
  EXPECT_EQ(cell_at(open, f, 1.8, 0.0), 0);
  EXPECT_EQ(cell_at(open, f, 2.3, 0.0), 1);
  EXPECT_EQ(cell_at(open, f, 9.5, 0.0), 1);
}

TEST(SightMap, AScanTakenBackLeavesWhatTheOthersSaw) {
  // Two scans of a floor 1 m below the sensor: one from (0, 0) towards +x, one from (0, 3)
  // towards -x, with a return on a box. After the first is taken back the map is what the
  // second alone makes: the back-end moved the first one's keyframe and it is traced again.
  const auto scan = [](double y0, double dir) {
    std::vector<Eigen::Vector3d> returns;
    for (int k = 0; k < 30; ++k)
      returns.emplace_back(dir * (1.0 + 0.1 * k), y0 + 0.02 * k, k % 5 == 0 ? 0.4 : 0.0);
    return returns;
  };
  const Eigen::Vector3d s1(0.0, 0.0, 1.0), s2(0.0, 3.0, 1.0);
  freespace::SightMap both(0.0, {}), second(0.0, {});
  both.add_scan(s1, scan(0.0, 1.0));
  both.add_scan(s2, scan(3.0, -1.0));
  second.add_scan(s2, scan(3.0, -1.0));
  const GridFrame f = GridFrame::around({-5, -1}, {5, 4}, 0.1, 0.0);
  ASSERT_NE(both.known_cells(f), second.known_cells(f));
  both.remove_scan(s1, scan(0.0, 1.0));
  EXPECT_EQ(both.known_cells(f), second.known_cells(f));
  EXPECT_EQ(both.open_cells(f), second.open_cells(f));
  EXPECT_FALSE(both.return_near({2.0, 0.2}, 0.5));  // the first scan's box return is gone
  EXPECT_TRUE(both.return_near({-2.0, 3.2}, 0.5));  // the second's stays
  both.remove_scan(s2, scan(3.0, -1.0));
  const std::vector<std::uint8_t> none(f.size(), 0);
  EXPECT_EQ(both.known_cells(f), none);
}

/// The rays from `sensor` to `returns` recorded for `wall` (a margin and a reach past it of 0.2 m).
freespace::WallTopRays rays_over(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& returns,
                                 const freespace::WallTopRays::Wall& wall) {
  freespace::SightMap sight(0.0, {});
  sight.add_scan(sensor, returns);
  freespace::WallTopRays tops(0.1);
  tops.add_scan(sensor, returns, {wall}, sight, 0.2, 0.2);
  return tops;
}

TEST(WallTopRays, RaysOverAPlaneShowItsTop) {
  // A sensor 1.7 m up; a block's face at x = 3 (its top 0.8 m) stops the rays aimed at it, at
  // 0.5 m; the others pass over it, at 1.04-1.06 m, to the floor 8 m out.
  std::vector<Eigen::Vector3d> returns;
  for (int k = 0; k < 40; ++k) {
    const double y = -1.0 + 0.05 * k;  // where the ray crosses x = 3
    returns.emplace_back(3.0, y, 0.5);
    returns.emplace_back(8.0, y * 8.0 / 3.0, 0.0);
  }
  const freespace::WallTopRays::Wall block{7, {3.0, -0.9}, {3.0, 0.9}, 0.8};
  const freespace::WallTopRays tops = rays_over({0.0, 0.0, 1.7}, returns, block);
  EXPECT_GT(tops.share_above(block, 0.2), 0.9);
  // Seen higher later (its top at 1.0 m), no ray passed 0.2 m above it.
  freespace::WallTopRays::Wall taller = block;
  taller.top = 1.0;
  EXPECT_LT(tops.share_above(taller, 0.2), 0.1);
  freespace::WallTopRays::Wall far = block;
  far.id = 8;
  EXPECT_EQ(tops.share_above(far, 0.2), 0.0);  // never seen
}

TEST(WallTopRays, PlanesRecordedTogetherGetWhatEachGetsAlone) {
  // A low sensor (0.5 m) and three planes: a low block ahead (top 0.3 m), whose rays end at
  // 0.9 m on a wall 8 m out, a taller one to the side (top 0.8 m), whose rays end on the
  // ceiling (3 m), and one beyond every return. Recording them in one call (which filters the
  // points once for all planes) gives each what recording it alone gives.
  std::vector<Eigen::Vector3d> returns;
  for (int k = 0; k < 40; ++k) {
    const double y = -1.0 + 0.05 * k;
    returns.emplace_back(3.0, y, 0.25);             // the low block's face
    returns.emplace_back(8.0, y * 8.0 / 3.0, 0.9);  // over it (at 0.65 m), to a wall
    returns.emplace_back(y, 3.0, 0.5);              // the taller one's face
    returns.emplace_back(y * 8.0 / 3.0, 8.0, 3.0);  // over it (at 1.44 m), to the ceiling
  }
  const freespace::WallTopRays::Wall low{1, {3.0, -0.9}, {3.0, 0.9}, 0.3};
  const freespace::WallTopRays::Wall tall{2, {-0.9, 3.0}, {0.9, 3.0}, 0.8};
  const freespace::WallTopRays::Wall beyond{3, {20.0, -1.0}, {20.0, 1.0}, 0.3};
  const Eigen::Vector3d sensor(0.0, 0.0, 0.5);
  freespace::SightMap sight(0.0, {});
  sight.add_scan(sensor, returns);
  freespace::WallTopRays together(0.1);
  together.add_scan(sensor, returns, {low, tall, beyond}, sight, 0.2, 0.2);
  for (const freespace::WallTopRays::Wall& w : {low, tall, beyond}) {
    freespace::WallTopRays alone(0.1);
    alone.add_scan(sensor, returns, {w}, sight, 0.2, 0.2);
    EXPECT_EQ(together.share_above(w, 0.2), alone.share_above(w, 0.2)) << "plane " << w.id;
  }
  EXPECT_GT(together.share_above(low, 0.2), 0.9);
  EXPECT_GT(together.share_above(tall, 0.2), 0.9);
  EXPECT_EQ(together.share_above(beyond, 0.2), 0.0);
}

TEST(WallTopRays, RaysInTheRoomBesideAWallDoNotShowItsTop) {
  // A low sensor (0.5 m) near a wall whose face is at x = 3.05, seen up to 1.8 m; rays to the
  // ceiling (3 m) just short of the wall run along its face, high above 1.8 m, through the
  // raster cells its line lies in (x in [3.0, 3.1)), but never cross it: its top is unseen.
  std::vector<Eigen::Vector3d> returns;
  for (int k = 0; k < 60; ++k) {
    const double y = -3.0 + 0.1 * k;
    for (const double z : {0.2, 1.0, 1.8}) returns.emplace_back(3.05, y, z);
    if (y > -1.0) returns.emplace_back(3.03, y, 3.0);
  }
  const freespace::WallTopRays::Wall wall{1, {3.05, -3.0}, {3.05, 3.0}, 1.8};
  EXPECT_EQ(rays_over({2.5, -3.0, 0.5}, returns, wall).share_above(wall, 0.2), 0.0);
}

TEST(WallTopRays, RaysThroughADoorDoNotShowAWallsTop) {
  // A low sensor (0.5 m) sees a wall at x = 3 up to 0.8 m, a 1 m door in it and the door's
  // lintel from 2.1 m; the rays through the door pass the wall's line above 0.8 m. Nothing as
  // low as the wall's top is in the door, so the rays there saw no top: the wall's is unseen.
  std::vector<Eigen::Vector3d> returns;
  for (int k = 0; k < 60; ++k) {
    const double y = -1.5 + 0.05 * k;
    if (std::abs(y) > 0.5) {
      for (const double z : {0.2, 0.5, 0.8}) returns.emplace_back(3.0, y, z);
    } else {
      returns.emplace_back(3.0, y, 2.1);              // the lintel
      returns.emplace_back(7.0, y * 7.0 / 3.0, 2.0);  // through the door, crossing its line at 1.14 m
    }
  }
  const freespace::WallTopRays::Wall wall{1, {3.0, -1.5}, {3.0, 1.5}, 0.8};
  EXPECT_LT(rays_over({0.0, 0.0, 0.5}, returns, wall).share_above(wall, 0.2), 0.25);
}

TEST(RoomSegmentation, ConfigOutOfRangeIsRefused) {
  RoomSegmentationConfig c;
  c.cell = 0.0;
  EXPECT_THROW(check_config(c, "c"), std::invalid_argument);
  c = {};
  c.rect_fill = 1.5;
  EXPECT_THROW(check_config(c, "c"), std::invalid_argument);
  EXPECT_THROW(freespace::SightMap(0.0, freespace::SightMapConfig{0.1, 0.2, 0.1, 12.0}),
               std::invalid_argument);
}

/// A 24 x 2.5 m corridor above a 24 x 6 m hall, the wall between them in two pieces along one
/// line with an opening of `opening` m in the middle.
SegmentationInput corridor_over_hall(double opening) {
  SegmentationInput in = level();
  add_area(box(0, -6, 24, 2.5), &in);
  const double a = 12.0 - 0.5 * opening, b = 12.0 + 0.5 * opening;
  in.walls = {wall(0, {0, -6}, {24, -6}, {12, -3}),   wall(1, {24, -6}, {24, 2.5}, {12, -3}),
              wall(2, {24, 2.5}, {0, 2.5}, {12, -3}), wall(3, {0, 2.5}, {0, -6}, {12, -3}),
              wall(4, {0, 0}, {a, 0}, {6, 1}),        wall(5, {b, 0}, {24, 0}, {18, 1})};
  return in;
}

TEST(RoomSegmentation, AWideOpeningInALongWallIsClosedAlongIt) {
  // 4 m open in a wall of 20 m on one line (a corridor's side past a bay), and 10 m open in 14 m
  // of wall: closed, the corridor and the hall are two spaces; 14 m open in 10 m of wall: more
  // opening than wall, no wall there, one space.
  for (double opening : {4.0, 10.0}) {
    const RoomSegmentation closed = segment_rooms(corridor_over_hall(opening));
    ASSERT_GE(closed.space_at({12, 1.2}), 0) << opening;
    EXPECT_NE(closed.space_at({12, 1.2}), closed.space_at({12, -3})) << opening;
  }
  const RoomSegmentation open = segment_rooms(corridor_over_hall(14.0));
  ASSERT_GE(open.space_at({12, 1.2}), 0);
  EXPECT_EQ(open.space_at({12, 1.2}), open.space_at({12, -3}));
}

TEST(RoomSegmentation, PartitionsFacingOverACorridorDoNotCutIt) {
  // A 24 x 3 m corridor between two rows of three rooms (5 m deep, doors of 1 m): the rows'
  // partitions at x = 8 and 16 lie on one line, 10 m of wall with a 3 m gap across the corridor,
  // whose ends lie on the corridor's walls passing through the line. That gap is the corridor,
  // no opening in a wall: the corridor stays one space, its rooms apart from it.
  SegmentationInput in = level();
  std::vector<std::pair<Vec2, Vec2>> inside;
  for (const double y : {0.0, 3.0})
    for (const auto& [x0, x1] : {std::pair{0.0, 3.0}, {4.0, 11.0}, {12.0, 19.0}, {20.0, 24.0}})
      inside.emplace_back(Vec2(x0, y), Vec2(x1, y));
  for (const double x : {8.0, 16.0}) {
    inside.emplace_back(Vec2(x, 3), Vec2(x, 8));
    inside.emplace_back(Vec2(x, -5), Vec2(x, 0));
  }
  add_area_with_walls(box(0, -5, 24, 8), inside, &in);
  box_walls(0, -5, 24, 8, 0, &in);
  for (const auto& [a, b] : inside)
    in.walls.push_back(wall(static_cast<int>(in.walls.size()), a, b, {a.x() + 0.5, a.y() + 0.5}));
  const RoomSegmentation seg = segment_rooms(in);
  const int corridor = seg.space_at({2, 1.5});
  ASSERT_GE(corridor, 0);
  EXPECT_EQ(seg.space_at({22, 1.5}), corridor);
  for (const Vec2& room : {Vec2(4, 5), Vec2(12, 5), Vec2(12, -2.5)}) EXPECT_NE(seg.space_at(room), corridor);
  EXPECT_NE(seg.space_at({4, 5}), seg.space_at({12, 5}));

  // The same line's gap in a facade, its ends on partitions that end on it (10 m open in 14 m
  // of wall, the hall behind it in three): closed, the corridor apart from the hall's rooms.
  SegmentationInput facade = corridor_over_hall(10.0);
  for (const double x : {7.0, 17.0})
    facade.walls.push_back(wall(static_cast<int>(facade.walls.size()), {x, 0}, {x, -6}, {x + 0.5, -3}));
  const RoomSegmentation closed = segment_rooms(facade);
  ASSERT_GE(closed.space_at({12, 1.2}), 0);
  EXPECT_NE(closed.space_at({12, 1.2}), closed.space_at({12, -3}));
}

}  // namespace
}  // namespace tsgraphs::rooms

namespace tsgraphs::rooms {
namespace {

TEST(RoomSegmentation, AThinSpaceWithAShelfAlongItsMiddleKeepsAPositiveRectangle) {
  // A 6 x 1.1 m space (no wall along it) and a shelf's side along its middle (its top seen, so
  // it bounds nothing), with a snap distance wider than half the space: both long sides find
  // the shelf; snapping both would leave a rectangle of no width (or a negative one), which no
  // run folder may hold.
  SegmentationInput in = level();
  add_area(box(0, 0, 6, 1.1), &in);
  WallCandidate shelf = wall(0, Vec2(0, 0.55), Vec2(6, 0.55), Vec2(3, 0.0), 1.5);
  shelf.top_seen = true;
  in.walls.push_back(shelf);
  RoomSegmentationConfig cfg;
  cfg.wall_snap = 1.0;
  const RoomSegmentation seg = segment_rooms(in, cfg);
  ASSERT_FALSE(seg.spaces.empty());
  for (const SegmentedSpace& s : seg.spaces) {
    EXPECT_GT(s.room.rect.size.x(), 0.0);
    EXPECT_GT(s.room.rect.size.y(), 0.0);
  }
}

}  // namespace
}  // namespace tsgraphs::rooms

namespace tsgraphs::rooms {
namespace {

TEST(RoomSegmentation, WithEveryCellLabelledARayOutOfARoomJoinsIt) {
  // A 5 x 4 m room seen whole and a ray out of its corner, a diagonal chain of cells (no two of
  // them share an edge): labelling every cell, the ray is the room's; without, it is no space's.
  GridFrame f;
  f.resolution = 0.1;
  f.cols = 100;
  f.rows = 80;
  SegmentationInput in;
  in.frame = f;
  in.seen.assign(f.size(), 0);
  for (int r = 10; r < 50; ++r)
    for (int c = 10; c < 60; ++c) in.seen[f.index(c, r)] = 1;
  std::vector<std::size_t> ray;
  for (int k = 0; k < 20; ++k) ray.push_back(f.index(60 + k, 50 + k));
  for (std::size_t i : ray) in.seen[i] = 1;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (in.seen[i]) in.ground.push_back(f.center(i));
  in.free_radius = 0.2;
  in.ground_radius = 0.5 * f.resolution;
  RoomSegmentationConfig cfg;
  const RoomSegmentation apart = segment_rooms(in, cfg);
  in.label_every_cell = true;
  const RoomSegmentation joined = segment_rooms(in, cfg);
  const int room = joined.label[f.index(30, 30)];
  ASSERT_GE(room, 0);
  ASSERT_EQ(joined.spaces.size(), 1u);
  for (std::size_t i : ray) {
    EXPECT_EQ(joined.label[i], room);
    EXPECT_EQ(apart.label[i], -1);
  }
}

}  // namespace
}  // namespace tsgraphs::rooms
