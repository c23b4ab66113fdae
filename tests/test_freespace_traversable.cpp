// Free space on traversable ground (DESIGN.md step 6) on constructed scenes: a doorway cuts the
// free space exactly when lambda_th exceeds half its width, a railing bounds the walkway beside a
// void without splitting it, storeys stay apart, the robot's cluster is found, obstacles are the
// points between the configured heights above their own storey, the output is deterministic, and on
// the simulated office the free space built from real ground nodes stays in the robot's room.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <cmath>
#include <iterator>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "tsgraphs/freespace/obstacle_points.hpp"
#include "tsgraphs/freespace/traversable_free_space.hpp"
#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/ground/traversable_node_map.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;
using namespace tsgraphs::freespace;
using Points = std::vector<Eigen::Vector3d>;

namespace {

constexpr double kSpacing = 0.25;       // node spacing: the node map's cell size (m)
constexpr double kPointStep = 0.05;     // spacing of obstacle points along a wall (m)
constexpr double kSensorHeight = 0.55;  // robot position above the floor (m)

/// Nodes on a kSpacing lattice over [x0, x1] x [y0, y1] (multiples of kSpacing) at height z.
void add_nodes(Points& nodes, double x0, double x1, double y0, double y1, double z) {
  const int i0 = static_cast<int>(std::lround(x0 / kSpacing)),
            i1 = static_cast<int>(std::lround(x1 / kSpacing));
  const int j0 = static_cast<int>(std::lround(y0 / kSpacing)),
            j1 = static_cast<int>(std::lround(y1 / kSpacing));
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) nodes.emplace_back(i * kSpacing, j * kSpacing, z);
}

/// Obstacle points on the vertical strip over segment a-b (2-D) between heights z0 and z1.
void add_wall(Points& pts, Eigen::Vector2d a, Eigen::Vector2d b, double z0, double z1, double z_step = 0.2) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kPointStep)));
  for (double z = z0; z <= z1 + 1e-9; z += z_step)
    for (int s = 0; s <= n; ++s) {
      const Eigen::Vector2d p = a + (b - a) * (double(s) / n);
      pts.emplace_back(p.x(), p.y(), z);
    }
}

/// A 2.75 m corridor (y in [-2.75, 0]) and a room (y in [0, 4.25]) joined by a door of
/// `door_width` in the wall y = 0 centred on x = 0; floor at z = 0.
struct DoorwayScene {
  Points nodes;
  Points obstacles;
};

DoorwayScene doorway_scene(double door_width) {
  DoorwayScene s;
  add_nodes(s.nodes, -5.0, 5.0, -2.5, -0.25, 0.0);  // corridor
  add_nodes(s.nodes, -3.0, 3.0, 0.25, 4.0, 0.0);    // room
  add_nodes(s.nodes, -0.25, 0.25, 0.0, 0.0, 0.0);   // floor of the doorway
  const double h = door_width / 2.0;
  add_wall(s.obstacles, {-5.25, 0.0}, {-h, 0.0}, 0.3, 1.9);
  add_wall(s.obstacles, {h, 0.0}, {5.25, 0.0}, 0.3, 1.9);
  add_wall(s.obstacles, {-5.25, -2.75}, {5.25, -2.75}, 0.3, 1.9);
  add_wall(s.obstacles, {-5.25, -2.75}, {-5.25, 0.0}, 0.3, 1.9);
  add_wall(s.obstacles, {5.25, -2.75}, {5.25, 0.0}, 0.3, 1.9);
  add_wall(s.obstacles, {-3.25, 0.0}, {-3.25, 4.25}, 0.3, 1.9);
  add_wall(s.obstacles, {3.25, 0.0}, {3.25, 4.25}, 0.3, 1.9);
  add_wall(s.obstacles, {-3.25, 4.25}, {3.25, 4.25}, 0.3, 1.9);
  return s;
}

TraversableFreeSpaceConfig with_lambda(double lambda_th) {
  TraversableFreeSpaceConfig c;
  c.lambda_th = lambda_th;
  return c;
}

double min_horizontal_distance(const Eigen::Vector3d& p, const Points& obstacles) {
  double best = 1e9;
  for (const auto& o : obstacles) best = std::min(best, (o - p).head<2>().norm());
  return best;
}

}  // namespace

TEST(FreespaceTraversable, DoorwayCutsWhenLambdaExceedsHalfTheDoorWidth) {
  const double door_width = 1.0;
  const DoorwayScene s = doorway_scene(door_width);
  const Eigen::Vector3d robot_in_room(0.1, 2.0, kSensorHeight);

  // Just above half the door width: the doorway's vertices go, one cluster each side.
  for (const double lambda : {0.55, 0.6, 0.8}) {
    const FreeSpace fs = traversable_free_space(s.nodes, s.obstacles, robot_in_room, with_lambda(lambda));
    ASSERT_EQ(fs.clusters.size(), 2u) << "lambda_th " << lambda;
    int room = -1;
    for (int c = 0; c < 2; ++c) {
      const auto& pts = fs.clusters[static_cast<std::size_t>(c)].points;
      const bool all_room =
          std::all_of(pts.begin(), pts.end(), [](const Eigen::Vector3d& p) { return p.y() > 0.0; });
      const bool all_corridor =
          std::all_of(pts.begin(), pts.end(), [](const Eigen::Vector3d& p) { return p.y() < 0.0; });
      EXPECT_TRUE(all_room || all_corridor) << "a cluster crosses the doorway at lambda_th " << lambda;
      if (all_room) room = c;
      // Every kept vertex is at least lambda_th from every obstacle point.
      for (const auto& p : pts) EXPECT_GE(min_horizontal_distance(p, s.obstacles), lambda - 1e-9);
    }
    EXPECT_EQ(fs.robot_cluster, room) << "lambda_th " << lambda;
    ASSERT_NE(fs.robot(), nullptr);
  }
  // Below half the door width: one cluster through the doorway, holding its centre node.
  for (const double lambda : {0.3, 0.4, 0.45}) {
    const FreeSpace fs = traversable_free_space(s.nodes, s.obstacles, robot_in_room, with_lambda(lambda));
    ASSERT_EQ(fs.clusters.size(), 1u) << "lambda_th " << lambda;
    EXPECT_EQ(fs.robot_cluster, 0);
    const auto& pts = fs.clusters[0].points;
    EXPECT_TRUE(std::any_of(pts.begin(), pts.end(),
                            [](const Eigen::Vector3d& p) { return p.head<2>().norm() < 1e-9; }));
  }
}

TEST(FreespaceTraversable, PathDistanceGoesRoundTheWallThroughTheDoor) {
  // lambda_th 0.4 leaves the 1 m doorway open: one cluster. A vertex 1 m behind the wall,
  // 2.5 m east of the door, is 2.5 m from the robot in a straight line, and a detour via the
  // door away along the free space.
  const DoorwayScene s = doorway_scene(1.0);
  const Eigen::Vector3d robot(2.5, -1.5, kSensorHeight);
  const FreeSpace fs = traversable_free_space(s.nodes, s.obstacles, robot, with_lambda(0.4));
  ASSERT_EQ(fs.clusters.size(), 1u);
  ASSERT_EQ(fs.robot_path_distance.size(), s.nodes.size());
  const auto index_of = [&](double x, double y) {
    for (std::size_t i = 0; i < s.nodes.size(); ++i)
      if ((s.nodes[i].head<2>() - Eigen::Vector2d(x, y)).norm() < 1e-9) return i;
    return s.nodes.size();
  };
  const std::size_t at_robot = index_of(2.5, -1.5), behind_wall = index_of(2.5, 1.0),
                    along = index_of(0.0, -1.5);
  ASSERT_LT(behind_wall, s.nodes.size());
  EXPECT_NEAR(fs.robot_path_distance[at_robot], 0.0, 1e-9);
  EXPECT_NEAR(fs.robot_path_distance[along], 2.5, 1e-6);  // straight along the corridor
  // Via the doorway's centre (0, 0): at least |robot - door| + |door - vertex|.
  const double detour = Eigen::Vector2d(2.5, 1.5).norm() + Eigen::Vector2d(2.5, 1.0).norm();
  EXPECT_GE(fs.robot_path_distance[behind_wall], detour - 1e-6);
  EXPECT_LE(fs.robot_path_distance[behind_wall],
            1.15 * detour);  // 8-neighbour lattice steps: a little longer
  // A removed vertex (next to the wall) is not reached.
  EXPECT_TRUE(std::isinf(fs.robot_path_distance[index_of(2.5, -0.25)]));
}

TEST(FreespaceTraversable, RobotClusterIsTheOneUnderTheRobot) {
  const DoorwayScene s = doorway_scene(1.0);
  const TraversableFreeSpaceConfig config = with_lambda(0.6);
  const FreeSpace in_corridor =
      traversable_free_space(s.nodes, s.obstacles, {2.1, -1.4, kSensorHeight}, config);
  ASSERT_NE(in_corridor.robot(), nullptr);
  for (const auto& p : in_corridor.robot()->points) EXPECT_LT(p.y(), 0.0);
  // The robot's vertex is the kept node nearest to it.
  const auto& v = s.nodes[static_cast<std::size_t>(in_corridor.robot_vertex)];
  EXPECT_NEAR(v.x(), 2.0, 1e-9);
  EXPECT_NEAR(v.y(), -1.5, 1e-9);
  // Far from every node (beyond robot_radius), or on another storey: no robot cluster.
  EXPECT_EQ(traversable_free_space(s.nodes, s.obstacles, {20.0, 0.0, kSensorHeight}, config).robot_cluster,
            -1);
  EXPECT_EQ(
      traversable_free_space(s.nodes, s.obstacles, {0.0, 2.0, 3.0 + kSensorHeight}, config).robot_cluster,
      -1);
}

TEST(FreespaceTraversable, RailingBoundsTheWalkwayWithoutSplittingIt) {
  // A walkway (y in [0, 3]) with a wall at y = -0.25, a railing (one line of points 1 m up) at
  // y = 3.25, a void beyond it, and the far walkway (y in [7, 9]).
  Points nodes;
  add_nodes(nodes, 0.0, 6.0, 0.0, 3.0, 0.0);
  add_nodes(nodes, 0.0, 6.0, 7.0, 9.0, 0.0);
  Points raw;
  add_wall(raw, {-0.5, -0.25}, {6.5, -0.25}, 0.3, 2.9);  // up to the ceiling: above 2 m is not an obstacle
  add_wall(raw, {-0.5, 3.25}, {6.5, 3.25}, 1.0, 1.0);    // the railing
  add_nodes(raw, 0.0, 6.0, 0.0, 3.0, 0.0);               // floor points (ground, not obstacles)
  add_nodes(raw, 0.0, 6.0, 4.0, 6.0, -3.0);              // the storey below, seen through the void
  add_nodes(raw, 0.0, 6.0, 0.0, 3.0, 3.0);               // the ceiling

  const TraversableFreeSpaceConfig config = with_lambda(0.4);
  const Points obstacles = select_obstacles(raw, nodes, config);
  // Wall points from 0.3 to 1.9 m (9 heights) and the railing; nothing else.
  const std::size_t wall_points = 9 * (static_cast<std::size_t>(std::ceil(7.0 / kPointStep)) + 1);
  const std::size_t railing_points = static_cast<std::size_t>(std::ceil(7.0 / kPointStep)) + 1;
  EXPECT_EQ(obstacles.size(), wall_points + railing_points);
  for (const auto& o : obstacles) EXPECT_TRUE(o.z() > 0.2 && o.z() <= 2.0) << o.transpose();

  Points wall_only;
  std::copy_if(obstacles.begin(), obstacles.end(), std::back_inserter(wall_only),
               [](const Eigen::Vector3d& p) { return p.y() < 0.0; });
  const Eigen::Vector3d robot(3.0, 1.5, kSensorHeight);
  const FreeSpace with_railing = traversable_free_space(nodes, obstacles, robot, config);
  const FreeSpace without = traversable_free_space(nodes, wall_only, robot, config);

  // The void splits the walkways; the railing splits nothing.
  ASSERT_EQ(with_railing.clusters.size(), 2u);
  ASSERT_EQ(without.clusters.size(), 2u);
  ASSERT_EQ(with_railing.robot_cluster, 0);
  // Rows y = 0.25 .. 3.0 (12) without the railing, 0.25 .. 2.75 (11) with it; 25 columns.
  EXPECT_EQ(without.robot()->points.size(), 12u * 25u);
  EXPECT_EQ(with_railing.robot()->points.size(), 11u * 25u);
  double max_y = -1e9;
  for (const auto& p : with_railing.robot()->points) max_y = std::max(max_y, p.y());
  EXPECT_NEAR(max_y, 2.75, 1e-9);
  // The far walkway is untouched.
  EXPECT_EQ(with_railing.clusters[1].points.size(), 25u * 9u);
}

TEST(FreespaceTraversable, NoObstaclesOneCluster) {
  Points nodes;
  add_nodes(nodes, -2.0, 2.0, -1.0, 1.0, 0.0);
  const FreeSpace fs = traversable_free_space(nodes, {}, {0.0, 0.0, kSensorHeight});
  ASSERT_EQ(fs.clusters.size(), 1u);
  EXPECT_EQ(fs.clusters[0].points.size(), nodes.size());
  EXPECT_EQ(fs.robot_cluster, 0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    EXPECT_EQ(fs.cluster_of[i], 0);
    EXPECT_EQ(fs.clusters[0].vertices[i], static_cast<int>(i));
  }
  EXPECT_TRUE(traversable_free_space({}, {}, Eigen::Vector3d::Zero()).clusters.empty());
}

TEST(FreespaceTraversable, StoreysStayApartAndOnlyTheirOwnObstaclesCount) {
  // Two storeys over the same area, 3 m apart; a wall on the upper storey only.
  Points nodes;
  add_nodes(nodes, 0.0, 4.0, 0.0, 4.0, 0.0);
  add_nodes(nodes, 0.0, 4.0, 0.0, 4.0, 3.0);
  Points raw;
  add_wall(raw, {-0.5, 2.0}, {4.5, 2.0}, 3.3, 4.9);
  const Points obstacles = select_obstacles(raw, nodes);
  EXPECT_EQ(obstacles.size(), raw.size());  // 0.3 .. 1.9 m above the upper storey
  // Beyond ground_search_radius of every node: no known ground, not an obstacle.
  EXPECT_TRUE(select_obstacles({{5.0, 2.0, 1.0}, {-1.0, 2.0, 4.0}}, nodes).empty());

  const FreeSpace fs = traversable_free_space(nodes, obstacles, {1.0, 1.0, kSensorHeight}, with_lambda(0.4));
  // Lower storey whole; the upper one cut in two by its wall.
  ASSERT_EQ(fs.clusters.size(), 3u);
  EXPECT_EQ(fs.clusters[0].points.size(), 17u * 17u);
  EXPECT_EQ(fs.robot_cluster, 0);
  for (std::size_t c = 1; c < 3; ++c)
    for (const auto& p : fs.clusters[c].points) EXPECT_NEAR(p.z(), 3.0, 1e-9);

  // The ground-height-function variant: a flat floor at z = 0 and no ground elsewhere.
  const GroundHeight floor = [](const Eigen::Vector3d& p) -> std::optional<double> {
    return p.x() >= 0.0 ? std::optional<double>(0.0) : std::nullopt;
  };
  const Points probe = {{1.0, 0.0, 0.1}, {1.0, 0.0, 0.5}, {1.0, 0.0, 2.0}, {1.0, 0.0, 2.5}, {-1.0, 0.0, 1.0}};
  const Points selected = select_obstacles(probe, floor);
  ASSERT_EQ(selected.size(), 2u);
  EXPECT_DOUBLE_EQ(selected[0].z(), 0.5);
  EXPECT_DOUBLE_EQ(selected[1].z(), 2.0);
}

TEST(FreespaceTraversable, ObstacleSelectionAgreesWithASearchOverEveryNode) {
  // Rough ground on two storeys and a ramp between them, points at every height: the indexed
  // selection (nodes highest first, points above the ceiling or at the floor not searched)
  // picks what the highest node below each point within ground_search_radius, found by a
  // search over every node, makes an obstacle.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Points nodes, raw;
  for (int k = 0; k < 600; ++k) {
    const double x = 8.0 * u(rng), y = 6.0 * u(rng);
    const double storey = k % 3 == 0 ? 3.0 : 0.0;
    nodes.emplace_back(x, y, storey + (x > 6.0 ? 0.4 * (x - 6.0) : 0.0) + 0.05 * u(rng));
  }
  for (int k = 0; k < 3000; ++k) {
    // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
    const double z = 7.0 * u(rng) - 1.0, y = 7.0 * u(rng) - 0.5, x = 9.0 * u(rng) - 0.5;
    raw.emplace_back(x, y, z);
  }
  const TraversableFreeSpaceConfig config;
  const GroundHeight every_node = [&](const Eigen::Vector3d& p) -> std::optional<double> {
    std::optional<double> ground;
    for (const Eigen::Vector3d& n : nodes)
      if ((n - p).head<2>().norm() < config.ground_search_radius && n.z() <= p.z() &&
          (!ground || n.z() > *ground))
        ground = n.z();
    return ground;
  };
  const Points expected = select_obstacles(raw, every_node, config);
  EXPECT_GT(expected.size(), 100u);
  EXPECT_EQ(select_obstacles(raw, nodes, config), expected);
}

TEST(FreespaceTraversable, DeterministicAndValidated) {
  const DoorwayScene s = doorway_scene(1.0);
  const Eigen::Vector3d robot(0.0, 2.0, kSensorHeight);
  const FreeSpace a = traversable_free_space(s.nodes, s.obstacles, robot, with_lambda(0.6));
  const FreeSpace b = traversable_free_space(s.nodes, s.obstacles, robot, with_lambda(0.6));
  EXPECT_EQ(a.cluster_of, b.cluster_of);
  EXPECT_EQ(a.robot_vertex, b.robot_vertex);
  ASSERT_EQ(a.clusters.size(), b.clusters.size());
  for (std::size_t c = 0; c < a.clusters.size(); ++c)
    EXPECT_EQ(a.clusters[c].vertices, b.clusters[c].vertices);
  // Obstacles in another order: the same free space.
  Points reversed(s.obstacles.rbegin(), s.obstacles.rend());
  EXPECT_EQ(traversable_free_space(s.nodes, reversed, robot, with_lambda(0.6)).cluster_of, a.cluster_of);

  TraversableFreeSpaceConfig bad;
  bad.edge_length = 0.0;
  EXPECT_THROW(traversable_free_space(s.nodes, s.obstacles, robot, bad), std::invalid_argument);
}

TEST(FreespaceTraversable, OfficeRoomFromSimulatedGroundNodes) {
  // The office scene: traversable nodes of every 10th scan of the first 200 fused into the
  // global node map (true poses), obstacles selected from the last of those scans, which is
  // taken in room_d. The robot's cluster must stay in room_d (ground truth polygon).
  const scene::Scene scene = scene::load_scene(std::string(TSGRAPHS_SCENES_DIR) + "/office.yaml");
  const sim::Simulator sim(scene, 1);
  constexpr std::size_t kScans = 200, kStep = 10;
  constexpr double kRadius = 10.0;  // nodes_near radius around the robot (m)
  ground::TraversableNodeMap map;
  const ground::GroundConfig ground_config;
  Points scan_points;
  std::size_t last = 0;
  for (std::size_t k = 0; k < kScans && k < sim.num_scans(); k += kStep) {
    const Pose3& T = sim.true_poses()[k];
    const PointCloud cloud = sim.scan(k);
    const ground::GroundScan g = ground::segment_ground(cloud, T.linear(), ground_config);
    const Eigen::Matrix3d R_sensor_level = g.R_level_sensor.transpose();
    std::vector<ground::NodeObservation> observations;
    for (const ground::GroundNode& n : g.nodes)
      if (n.traversable)
        observations.push_back({R_sensor_level * n.centre.cast<double>(),
                                R_sensor_level * n.normal.cast<double>(),
                                static_cast<double>(n.probability)});
    map.fuse(static_cast<int>(k), T, observations);
    scan_points.clear();
    for (const auto& p : cloud.points)
      if (p.allFinite()) scan_points.push_back(T * p.cast<double>());
    last = k;
  }
  const Eigen::Vector3d robot = sim.true_poses()[last].translation();
  const Eigen::Vector3d floor_under_robot = robot - Eigen::Vector3d(0.0, 0.0, scene.sensor.mount_height);
  Points nodes;
  for (const ground::GlobalNode* n : map.nodes_near(floor_under_robot, kRadius)) nodes.push_back(n->position);
  const Points obstacles = select_obstacles(scan_points, nodes);
  const auto in_room_d = [](const Eigen::Vector3d& p) {
    return p.x() > 0.1 && p.x() < 10.9 && p.y() > 7.3 && p.y() < 12.9;
  };
  ASSERT_TRUE(in_room_d(robot));
  const auto room_nodes = static_cast<std::size_t>(std::count_if(nodes.begin(), nodes.end(), in_room_d));

  const FreeSpace open = traversable_free_space(nodes, {}, robot);
  ASSERT_NE(open.robot(), nullptr);
  const auto start = std::chrono::steady_clock::now();
  const FreeSpace fs = traversable_free_space(nodes, obstacles, robot);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_NE(fs.robot(), nullptr);
  const auto inside = static_cast<std::size_t>(
      std::count_if(fs.robot()->points.begin(), fs.robot()->points.end(), in_room_d));
  std::printf(
      "office: %zu nodes within %.0f m, %zu in room_d; %zu obstacle points of %zu; without obstacles the "
      "robot's "
      "cluster holds %zu; with them %zu, %zu of them in room_d (%.1f ms)\n",
      nodes.size(), kRadius, room_nodes, obstacles.size(), scan_points.size(), open.robot()->points.size(),
      fs.robot()->points.size(), inside, ms);
  // Measured: 1846 nodes, 1726 in the open cluster; 654 in the room, all in room_d (812 nodes).
  // The nodes outside the open cluster are far floor rings seen through doors, stripes metres
  // apart that one visit does not join up.
  EXPECT_GE(open.robot()->points.size(), nodes.size() * 90 / 100);
  EXPECT_EQ(inside, fs.robot()->points.size()) << "the free space leaks out of room_d";
  EXPECT_GE(fs.robot()->points.size(), room_nodes * 3 / 4);
}
