// Room, corridor and floor nodes in the Ceres back-end, on synthetic ground truth: a row of three
// rooms driven out and back with drifting odometry, and a straight corridor at an angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include "tsgraphs/graph/graph_optimizer.hpp"

using namespace tsgraphs;
using namespace tsgraphs::graph;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kRoomLength = 6.0, kRoomWidth = 4.0;  // interior of each room (m)
constexpr double kWallThickness = 0.2;                 // between neighbouring rooms (m)
constexpr int kRooms = 3;
constexpr double kStep = 0.5;        // m between keyframes
constexpr double kFirstX = 1.0;      // the path runs along y = kRoomWidth / 2 from here
constexpr int kStepsOut = 33;        // to x = 17.5, in the third room, then back
constexpr double kWallMargin = 0.1;  // a keyframe this near a room's end wall sees no room
constexpr double kOdomSigmaTrans = 0.01, kOdomSigmaYawDeg = 0.3;  // per step
constexpr double kPlaneNoiseDeg = 0.2, kPlaneNoiseDist = 0.01;
constexpr unsigned kSeed = 7;

struct Building {
  std::vector<Pose3> truth;
  std::vector<Eigen::Vector2d> room_min;         ///< interior corner of each room
  std::vector<std::array<Plane, 4>> true_walls;  ///< left, right, bottom, top (into the room)
  std::vector<std::array<int, 4>> wall_ids;      ///< their graph plane ids
  std::vector<int> room_ids;                     ///< graph room id of each room
  SituationalGraph graph;
};

Eigen::Vector2d true_center(const Building& b, int room) {
  return b.room_min[room] + 0.5 * Eigen::Vector2d(kRoomLength, kRoomWidth);
}

Plane vertical_plane(const Eigen::Vector2d& point, const Eigen::Vector2d& normal) {
  return Plane::from_point_normal({point.x(), point.y(), 0.0}, {normal.x(), normal.y(), 0.0});
}

// Room containing the keyframe's position, -1 in a doorway.
int room_at(const Building& b, const Eigen::Vector3d& p) {
  for (int r = 0; r < kRooms; ++r) {
    const double x0 = b.room_min[r].x() + kWallMargin;
    const double x1 = b.room_min[r].x() + kRoomLength - kWallMargin;
    if (p.x() > x0 && p.x() < x1) return r;
  }
  return -1;
}

// Three rooms in a row; the path goes out along their middle and back to its start, a keyframe
// every 0.5 m, each seeing the four walls of the room it is in. Planes are mapped from their first
// sighting at the drifted odometry; rooms start at the midpoint of those planes plus `room_offset`.
Building building(bool with_rooms, const Eigen::Vector2d& room_offset = Eigen::Vector2d::Zero());

// The point halfway between the walls of each facing pair (the intersection of the mid-planes).
Eigen::Vector2d wall_midpoint(const SituationalGraph& g, const std::array<int, 4>& walls) {
  Eigen::Matrix2d A;
  Eigen::Vector2d b;
  for (int pair = 0; pair < 2; ++pair) {
    const Plane& p = g.planes().at(walls[2 * pair]).plane;
    const Plane& q = g.planes().at(walls[2 * pair + 1]).plane;
    const double np = p.n.head<2>().norm(), nq = q.n.head<2>().norm();
    A.row(pair) = (p.n.head<2>() / np - q.n.head<2>() / nq).transpose();
    b[pair] = -(p.d / np - q.d / nq);
  }
  return A.inverse() * b;
}

Building building(bool with_rooms, const Eigen::Vector2d& room_offset) {
  Building b;
  for (int r = 0; r < kRooms; ++r) {
    const Eigen::Vector2d lo(r * (kRoomLength + kWallThickness), 0.0);
    const Eigen::Vector2d hi = lo + Eigen::Vector2d(kRoomLength, kRoomWidth);
    b.room_min.push_back(lo);
    b.true_walls.push_back({vertical_plane(lo, {1, 0}), vertical_plane(hi, {-1, 0}),
                            vertical_plane(lo, {0, 1}), vertical_plane(hi, {0, -1})});
  }
  const double y = kRoomWidth / 2.0;
  for (int k = 0; k <= kStepsOut; ++k) b.truth.push_back(make_pose({kFirstX + kStep * k, y, 0}, 0.0));
  for (int k = 0; k <= kStepsOut; ++k)
    b.truth.push_back(make_pose({kFirstX + kStep * (kStepsOut - k), y, 0}, M_PI));

  std::mt19937 rng(kSeed);
  std::normal_distribution<double> trans(0.0, kOdomSigmaTrans), yaw(0.0, kOdomSigmaYawDeg * kDeg);
  std::normal_distribution<double> angle(0.0, kPlaneNoiseDeg * kDeg), dist(0.0, kPlaneNoiseDist);
  std::vector<Pose3> odom{b.truth[0]};
  for (std::size_t k = 1; k < b.truth.size(); ++k) {
    Pose3 step = b.truth[k - 1].inverse() * b.truth[k];
    const double sy = trans(rng), sx = trans(rng);  // the last first, as gcc drew them
    step.translation() += Eigen::Vector3d(sx, sy, 0);
    step.linear() = Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitZ()) * step.linear();
    odom.push_back(odom.back() * step);
  }
  b.wall_ids.assign(kRooms, {-1, -1, -1, -1});
  for (std::size_t k = 0; k < b.truth.size(); ++k) {
    KeyframeNode node;
    node.scan_index = k;
    node.pose = node.odom = odom[k];
    b.graph.add_keyframe(node);
    if (k > 0) b.graph.add_odometry_edge({int(k) - 1, int(k), odom[k - 1].inverse() * odom[k]});
    const int r = room_at(b, b.truth[k].translation());
    if (r < 0) continue;
    for (int w = 0; w < 4; ++w) {
      Plane measured = b.true_walls[r][w].transformed(b.truth[k].inverse());
      const double tz = angle(rng), ty = angle(rng), tx = angle(rng);  // the last first, as gcc drew them
      const Eigen::Vector3d tilt(tx, ty, tz);
      measured.n = Eigen::AngleAxisd(tilt.norm(), tilt.normalized()) * measured.n;
      measured.d += dist(rng);
      int& id = b.wall_ids[r][w];
      if (id < 0) id = b.graph.add_plane(measured.transformed(odom[k]), true);
      b.graph.add_plane_edge({int(k), id, measured, 100});
    }
  }
  const int last = int(b.truth.size()) - 1;
  b.graph.add_loop_edge({0, last, b.truth[0].inverse() * b.truth[last], 0.01});
  if (!with_rooms) return b;
  for (int r = 0; r < kRooms; ++r) {
    RoomNode room;
    room.center = wall_midpoint(b.graph, b.wall_ids[r]) + room_offset;
    b.room_ids.push_back(b.graph.add_room(room));
    const auto& w = b.wall_ids[r];
    b.graph.add_room_edge({b.room_ids[r], RoomKind::room, {w[0], w[1], w[2], w[3]}, {}});
  }
  return b;
}

double max_plane_change(const SituationalGraph& a, const SituationalGraph& b) {
  double worst = 0.0;
  for (const auto& [id, node] : a.planes())
    worst = std::max(worst, std::abs(node.plane.d - b.planes().at(id).plane.d));
  return worst;
}

bool same_bits(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 2) == 0;
}

// A straight corridor at 30 deg: walls 3 m apart, keyframes along it 0.2 m off its midline.
constexpr double kCorridorYaw = 30.0 * kDeg;
constexpr double kCorridorHalfWidth = 1.5;
constexpr int kCorridorKeyframes = 21;  // 1 m apart
const Eigen::Vector2d kCorridorOrigin(2.0, 1.0);

struct Corridor {
  Eigen::Vector2d along, across;  ///< unit directions
  std::array<int, 2> walls{};
  int room = -1;
  SituationalGraph graph;
};

Corridor corridor(const Eigen::Vector2d& initial, const Eigen::Vector2d& cluster_center) {
  Corridor c;
  c.along = Eigen::Vector2d(std::cos(kCorridorYaw), std::sin(kCorridorYaw));
  c.across = Eigen::Vector2d(-c.along.y(), c.along.x());
  constexpr double kRobotOffset = 0.2;  // m, across the corridor
  const std::array<Plane, 2> walls = {
      vertical_plane(kCorridorOrigin - kCorridorHalfWidth * c.across, c.across),
      vertical_plane(kCorridorOrigin + kCorridorHalfWidth * c.across, -c.across)};
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> angle(0.0, kPlaneNoiseDeg * kDeg), dist(0.0, kPlaneNoiseDist);
  for (int k = 0; k < kCorridorKeyframes; ++k) {
    const Eigen::Vector2d p = kCorridorOrigin + double(k) * c.along + kRobotOffset * c.across;
    KeyframeNode node;
    node.pose = node.odom = make_pose({p.x(), p.y(), 0.0}, kCorridorYaw);
    c.graph.add_keyframe(node);
    if (k > 0) c.graph.add_odometry_edge({k - 1, k, c.graph.keyframes()[k - 1].pose.inverse() * node.pose});
    for (int w = 0; w < 2; ++w) {
      Plane measured = walls[w].transformed(node.pose.inverse());
      const double tz = angle(rng), ty = angle(rng), tx = angle(rng);  // the last first, as gcc drew them
      const Eigen::Vector3d tilt(tx, ty, tz);
      measured.n = Eigen::AngleAxisd(tilt.norm(), tilt.normalized()) * measured.n;
      measured.d += dist(rng);
      if (k == 0) c.walls[w] = c.graph.add_plane(measured.transformed(node.pose), true);
      c.graph.add_plane_edge({k, c.walls[w], measured, 100});
    }
  }
  RoomNode room;
  room.kind = RoomKind::corridor;
  room.center = initial;
  c.room = c.graph.add_room(room);
  c.graph.add_room_edge({c.room, RoomKind::corridor, {c.walls[0], c.walls[1]}, cluster_center});
  return c;
}

}  // namespace

TEST(GraphRooms, RoomOffByHalfAMetreConvergesToTheMidpointOfItsWalls) {
  const Eigen::Vector2d kOffset(0.4, -0.3);  // 0.5 m
  Building b = building(true, kOffset), plain = building(false);
  GraphOptimizer optimizer;
  const OptimizationStats stats = optimizer.optimize(b.graph, true);
  optimizer.optimize(plain.graph, true);
  double worst_mid = 0.0, worst_truth = 0.0, worst_walls = 0.0;
  for (int r = 0; r < kRooms; ++r) {
    const Eigen::Vector2d c = b.graph.rooms().at(b.room_ids[r]).center;
    const Eigen::Vector2d mid = wall_midpoint(b.graph, b.wall_ids[r]);
    worst_mid = std::max(worst_mid, (c - mid).norm());
    worst_truth = std::max(worst_truth, (c - true_center(b, r)).norm());
    worst_walls = std::max(worst_walls, (mid - true_center(b, r)).norm());
  }
  const double plane_change = max_plane_change(b.graph, plain.graph);
  std::printf(
      "rooms 0.50 m off -> %.2e m from their walls' midpoint, %.4f m from the truth "
      "(the walls' midpoint: %.4f m); walls moved %.2e m by the room factors; %d vars "
      "%d factors %d its\n",
      worst_mid, worst_truth, worst_walls, plane_change, stats.n_variables, stats.n_factors,
      stats.iterations);
  EXPECT_LT(worst_mid, 1e-4);
  EXPECT_LT(worst_truth, 0.06);   // as good as the walls: the drift across doorways stays
  EXPECT_LT(plane_change, 1e-4);  // a consistent room does not bend its walls
  const int num_keyframes = int(b.graph.keyframes().size());
  EXPECT_EQ(stats.n_variables, num_keyframes - 1 + int(b.graph.planes().size()) + kRooms);
  EXPECT_EQ(stats.n_factors, int(b.graph.odometry_edges().size() + b.graph.loop_edges().size() +
                                 b.graph.plane_edges().size()) +
                                 kRooms);
}

TEST(GraphRooms, RoomsMoveWithTheirWalls) {
  // A solved map, then bent as drift would: everything past the first doorway (keyframes, the
  // walls and rooms they mapped) turned 3 deg about the doorway and shifted.
  Building b = building(true);
  GraphOptimizer optimizer;
  optimizer.optimize(b.graph, true);
  const SituationalGraph solved = b.graph;
  const double doorway = kRoomLength + 0.5 * kWallThickness;
  const Eigen::Vector3d pivot(doorway, 0.5 * kRoomWidth, 0.0);
  Pose3 bend = Pose3::Identity();
  bend.rotate(Eigen::AngleAxisd(3.0 * kDeg, Eigen::Vector3d::UnitZ()));
  bend.translation() = pivot - bend.linear() * pivot + Eigen::Vector3d(0.15, 0.2, 0.0);
  for (std::size_t k = 0; k < b.truth.size(); ++k)
    if (b.truth[k].translation().x() > doorway)
      b.graph.keyframes()[k].pose = bend * b.graph.keyframes()[k].pose;
  for (int r = 1; r < kRooms; ++r) {
    for (int id : b.wall_ids[r]) {
      Plane& p = b.graph.planes().at(id).plane;
      p = p.transformed(bend);
    }
    Eigen::Vector2d& c = b.graph.rooms().at(b.room_ids[r]).center;
    c = (bend * Eigen::Vector3d(c.x(), c.y(), 0.0)).head<2>();
  }
  const SituationalGraph bent = b.graph;
  optimizer.optimize(b.graph, true);
  double worst_follow = 0.0, worst_back = 0.0, smallest_move = 1e9;
  for (int r = 1; r < kRooms; ++r) {
    const Eigen::Vector2d c0 = bent.rooms().at(b.room_ids[r]).center;
    const Eigen::Vector2d c1 = b.graph.rooms().at(b.room_ids[r]).center;
    const Eigen::Vector2d wall_move =
        wall_midpoint(b.graph, b.wall_ids[r]) - wall_midpoint(bent, b.wall_ids[r]);
    worst_follow = std::max(worst_follow, ((c1 - c0) - wall_move).norm());
    worst_back = std::max(worst_back, (c1 - solved.rooms().at(b.room_ids[r]).center).norm());
    smallest_move = std::min(smallest_move, (c1 - c0).norm());
  }
  std::printf(
      "bent rooms moved at least %.3f m, %.2e m unlike their walls, and are %.2e m from "
      "the solved map\n",
      smallest_move, worst_follow, worst_back);
  EXPECT_GT(smallest_move, 0.2);
  EXPECT_LT(worst_follow, 1e-4);
  EXPECT_LT(worst_back, 1e-3);
}

TEST(GraphRooms, LocalSolveFreesTheRoomsOfTheWindowsWalls) {
  Building b = building(true);
  const int floor = b.graph.add_floor({});
  for (int room : b.room_ids) b.graph.add_floor_room_edge({floor, room});
  GraphOptimizer optimizer;
  optimizer.optimize(b.graph, true);
  // The last keyframes (back in the first room) arrive displaced.
  const int n = int(b.graph.keyframes().size());
  const int window = optimizer.config().local_window;
  const Eigen::Vector3d kDisplacement(0.2, -0.1, 0.0);
  for (int k = n - window; k < n; ++k) b.graph.keyframes()[k].pose.translation() += kDisplacement;
  std::set<int> window_planes;
  for (const PlaneEdge& e : b.graph.plane_edges())
    if (e.keyframe >= n - window) window_planes.insert(e.plane);
  ASSERT_EQ(window_planes, std::set<int>(b.wall_ids[0].begin(), b.wall_ids[0].end()));
  const SituationalGraph before = b.graph;
  const OptimizationStats stats = optimizer.optimize(b.graph, false);
  // The window, the first room's walls, the first room and the floor.
  EXPECT_EQ(stats.n_variables, window + 4 + 1 + 1);
  for (int r = 1; r < kRooms; ++r)
    EXPECT_TRUE(same_bits(b.graph.rooms().at(b.room_ids[r]).center, before.rooms().at(b.room_ids[r]).center))
        << r;
  const Eigen::Vector2d c = b.graph.rooms().at(b.room_ids[0]).center;
  EXPECT_LT((c - wall_midpoint(b.graph, b.wall_ids[0])).norm(), 1e-4);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int room : b.room_ids) mean += b.graph.rooms().at(room).center / kRooms;
  EXPECT_LT((b.graph.floors().at(floor).center - mean).norm(), 1e-6);
}

TEST(GraphRooms, CorridorConvergesToItsMidlineAtTheMeasuredPlaceAlongIt) {
  Corridor probe = corridor(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  const Eigen::Vector2d truth = kCorridorOrigin + 10.0 * probe.along;
  const Eigen::Vector2d cluster = truth + 0.25 * probe.across;  // the cluster is off the midline
  const Eigen::Vector2d initial = truth - 0.5 * probe.along + 0.6 * probe.across;
  Corridor c = corridor(initial, cluster);
  GraphOptimizer().optimize(c.graph, true);
  const Eigen::Vector2d error = c.graph.rooms().at(c.room).center - truth;
  // The midline of the estimated walls, across the corridor.
  const Plane& a = c.graph.planes().at(c.walls[0]).plane;
  const Plane& bw = c.graph.planes().at(c.walls[1]).plane;
  const Eigen::Vector2d centre = c.graph.rooms().at(c.room).center;
  const double to_midline = 0.5 * ((a.n.head<2>().dot(centre) + a.d) / a.n.head<2>().norm() -
                                   (bw.n.head<2>().dot(centre) + bw.d) / bw.n.head<2>().norm());
  std::printf(
      "corridor started 0.50 m back and 0.60 m across: now %.4f m along, %.4f m across "
      "from the truth, %.2e m off its walls' midline\n",
      error.dot(c.along), error.dot(c.across), to_midline);
  EXPECT_LT(std::abs(to_midline), 1e-4);
  EXPECT_LT(std::abs(error.dot(c.across)), 0.01);
  EXPECT_LT(std::abs(error.dot(c.along)), 0.01);  // the measured position along it
}

TEST(GraphRooms, FloorConvergesToTheMeanOfItsRoomsWithoutPullingThem) {
  Building with_floor = building(true), without = building(true);
  const int floor = with_floor.graph.add_floor({0, 0, Eigen::Vector2d(-3.0, 5.0)});
  for (int room : with_floor.room_ids) with_floor.graph.add_floor_room_edge({floor, room});
  GraphOptimizer optimizer;
  const OptimizationStats stats = optimizer.optimize(with_floor.graph, true);
  optimizer.optimize(without.graph, true);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero(), true_mean = Eigen::Vector2d::Zero();
  double room_change = 0.0;
  for (int r = 0; r < kRooms; ++r) {
    const Eigen::Vector2d c = with_floor.graph.rooms().at(with_floor.room_ids[r]).center;
    mean += c / kRooms;
    true_mean += true_center(with_floor, r) / kRooms;
    const Eigen::Vector2d alone = without.graph.rooms().at(without.room_ids[r]).center;
    room_change = std::max(room_change, (c - alone).norm());
  }
  const Eigen::Vector2d f = with_floor.graph.floors().at(floor).center;
  std::printf(
      "floor started %.2f m off: now %.2e m from its rooms' mean, %.4f m from the truth; "
      "rooms moved %.2e m by it\n",
      (Eigen::Vector2d(-3.0, 5.0) - true_mean).norm(), (f - mean).norm(), (f - true_mean).norm(),
      room_change);
  EXPECT_LT((f - mean).norm(), 1e-6);
  EXPECT_LT((f - true_mean).norm(), 0.03);
  EXPECT_LT(room_change, 1e-4);
  EXPECT_EQ(
      stats.n_factors,
      int(with_floor.graph.odometry_edges().size() + 1 + with_floor.graph.plane_edges().size()) + kRooms + 1);
}

TEST(GraphRooms, WrongRoomAssociationIsDownWeightedByHuber) {
  // The first room's node is also (wrongly) given the second room's walls, 6.2 m away.
  struct Errors {
    double room = 0.0, walls = 0.0;  ///< the first room's centre, the worst wall offset (m)
  };
  const auto solve = [](bool wrong_edge, double huber_room) {
    Building b = building(true);
    const auto& w = b.wall_ids[1];
    if (wrong_edge) b.graph.add_room_edge({b.room_ids[0], RoomKind::room, {w[0], w[1], w[2], w[3]}, {}});
    GraphOptimizerConfig config;
    config.huber_room = huber_room;
    GraphOptimizer(config).optimize(b.graph, true);
    Errors e;
    e.room = (b.graph.rooms().at(b.room_ids[0]).center - true_center(b, 0)).norm();
    for (int r = 0; r < kRooms; ++r)
      for (int i = 0; i < 4; ++i)
        e.walls =
            std::max(e.walls, std::abs(b.graph.planes().at(b.wall_ids[r][i]).plane.d - b.true_walls[r][i].d));
    return e;
  };
  const double huber = GraphOptimizerConfig{}.huber_room;
  const Errors clean = solve(false, huber), robust = solve(true, huber);
  constexpr double kNoRobustKernel = 1e6;  // the largest delta declared, none reached: least squares
  const Errors plain = solve(true, kNoRobustKernel);
  std::printf(
      "first room / worst wall error: right association %.3f / %.4f m; wrong one with "
      "Huber %.3f / %.4f m, least squares %.3f / %.4f m\n",
      clean.room, clean.walls, robust.room, robust.walls, plain.room, plain.walls);
  const double room_sigma = GraphOptimizerConfig{}.room_sigma;
  EXPECT_LT(robust.room, clean.room + 2.0 * room_sigma);
  EXPECT_LT(robust.walls, clean.walls + room_sigma);
  EXPECT_GT(plain.room, 1.0);
  EXPECT_GT(plain.walls, 1.0);
}

TEST(GraphRooms, MergedRoomKeepsBothEdgesAndConverges) {
  Building b = building(true);
  RoomNode duplicate;
  duplicate.center = true_center(b, 2) + Eigen::Vector2d(0.3, 0.3);
  const int dup = b.graph.add_room(duplicate);
  const auto& w = b.wall_ids[2];
  b.graph.add_room_edge({dup, RoomKind::room, {w[0], w[1], w[2], w[3]}, {}});
  b.graph.merge_rooms(b.room_ids[2], dup);
  const OptimizationStats stats = GraphOptimizer().optimize(b.graph, true);
  EXPECT_EQ(b.graph.rooms().size(), std::size_t(kRooms));
  EXPECT_EQ(stats.n_variables, int(b.graph.keyframes().size()) - 1 + int(b.graph.planes().size()) + kRooms);
  EXPECT_LT((b.graph.rooms().at(b.room_ids[2]).center - wall_midpoint(b.graph, w)).norm(), 1e-4);
}

TEST(GraphRooms, SameInputGivesBitIdenticalOutput) {
  const auto make = [] {
    Building b = building(true, Eigen::Vector2d(0.2, 0.1));
    const int floor = b.graph.add_floor({});
    for (int room : b.room_ids) b.graph.add_floor_room_edge({floor, room});
    return b;
  };
  Building a = make(), b = make();
  Corridor ca = corridor({1.0, 2.0}, {10.0, 6.0}), cb = corridor({1.0, 2.0}, {10.0, 6.0});
  GraphOptimizer optimizer;
  for (bool full : {true, false}) {
    EXPECT_EQ(optimizer.optimize(a.graph, full).final_cost, optimizer.optimize(b.graph, full).final_cost);
    EXPECT_EQ(optimizer.optimize(ca.graph, full).final_cost, optimizer.optimize(cb.graph, full).final_cost);
  }
  for (const auto& [id, room] : a.graph.rooms())
    EXPECT_TRUE(same_bits(room.center, b.graph.rooms().at(id).center)) << id;
  for (const auto& [id, floor] : a.graph.floors())
    EXPECT_TRUE(same_bits(floor.center, b.graph.floors().at(id).center)) << id;
  EXPECT_TRUE(same_bits(ca.graph.rooms().at(ca.room).center, cb.graph.rooms().at(cb.room).center));
}

TEST(GraphRooms, RejectsBadRoomsAndConfig) {
  GraphOptimizerConfig config;
  config.room_sigma = 0.0;
  EXPECT_THROW(GraphOptimizer{config}, std::invalid_argument);
  config = {};
  config.huber_floor = -1.0;
  EXPECT_THROW(GraphOptimizer{config}, std::invalid_argument);

  GraphOptimizer optimizer;
  {
    Building b = building(true);
    b.graph.planes().at(b.wall_ids[0][1]).vertical = false;
    EXPECT_THROW(optimizer.optimize(b.graph, true), std::invalid_argument);
  }
  {
    Building b = building(true);  // a pair whose normals do not face each other
    Plane& p = b.graph.planes().at(b.wall_ids[0][1]).plane;
    p.n = -p.n;
    p.d = -p.d;
    EXPECT_THROW(optimizer.optimize(b.graph, true), std::invalid_argument);
  }
  {
    Building b = building(true);  // a room removed behind the graph's back
    b.graph.rooms().erase(b.room_ids[1]);
    EXPECT_THROW(optimizer.optimize(b.graph, true), std::invalid_argument);
  }
}
