// The S-Graphs+ baseline's free space on constructed voxel maps: the ESDF is the exact Euclidean
// distance between voxel centres (one voxel from a wall: 0.2 m, three: 0.6 m, diagonal and
// vertical offsets included), capped at max_distance; free-space vertices in a 4 m corridor are
// the band farther than 0.8 m from both walls; the robot's cluster is found; the output does not
// depend on the order of the points.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "tsgraphs/freespace/esdf_free_space.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;
using namespace tsgraphs::freespace;
using Points = std::vector<Eigen::Vector3d>;

namespace {

constexpr double kVoxel = 0.2;          // EsdfFreeSpaceConfig's default voxel size (m)
constexpr double kSensorHeight = 0.55;  // robot position above the floor (m)

/// Centre of voxel (i, j, k).
Eigen::Vector3d voxel_centre(int i, int j, int k) {
  return Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5) * kVoxel;
}

/// Occupied points at the centres of the voxels i in [i0, i1], j in [j0, j1], k in [0, 14]
/// (floor to 3 m).
void add_block(Points& pts, int i0, int i1, int j0, int j1) {
  for (int k = 0; k < 15; ++k)
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) pts.push_back(voxel_centre(i, j, k));
}

/// Walls along x at voxel rows 0 and 20 (centres 4 m apart), voxel columns 0 .. 49.
Points corridor() {
  Points pts;
  add_block(pts, 0, 49, 0, 0);
  add_block(pts, 0, 49, 20, 20);
  return pts;
}

}  // namespace

TEST(FreespaceEsdf, DistanceIsVoxelDistanceToTheNearestWallCapped) {
  // Walls x = voxel column 0 and column 60 (12 m apart), rows 0 .. 99.
  Points pts;
  add_block(pts, 0, 0, 0, 99);
  add_block(pts, 60, 60, 0, 99);
  const EsdfFreeSpace e = esdf_free_space(pts, 0.0, voxel_centre(30, 50, 2));
  const EsdfSlice& s = e.slice;
  ASSERT_EQ(s.width, 61);
  ASSERT_EQ(s.height, 100);
  const auto at = [&](int i, int j) {
    const int cell = s.cell_at(voxel_centre(i, j, s.layer));
    EXPECT_GE(cell, 0);
    return s.distance[static_cast<std::size_t>(cell)];
  };
  EXPECT_DOUBLE_EQ(at(0, 50), 0.0);
  EXPECT_NEAR(at(1, 50), 0.2, 1e-12);   // next to the wall: one voxel
  EXPECT_NEAR(at(3, 50), 0.6, 1e-12);   // three voxels
  EXPECT_NEAR(at(57, 50), 0.6, 1e-12);  // three from the other wall
  EXPECT_NEAR(at(24, 50), 4.8, 1e-12);
  EXPECT_DOUBLE_EQ(at(30, 50), 5.0);  // 6 m from both: capped at max_distance
  // The free band: distance > 0.8 m, columns 5 .. 55, every row: one cluster.
  ASSERT_EQ(e.free_space.clusters.size(), 1u);
  EXPECT_EQ(e.free_space.clusters[0].points.size(), 51u * 100u);
  EXPECT_EQ(e.free_space.robot_cluster, 0);
}

TEST(FreespaceEsdf, DistanceIsExactEuclideanIn3D) {
  // One occupied voxel two layers above the slice, and one far away to span the slice.
  const int layer = static_cast<int>(std::floor(1.0 / kVoxel));  // slice_height 1 m above a floor at 0
  const Points pts = {voxel_centre(0, 0, layer + 2), voxel_centre(10, 10, layer)};
  const EsdfFreeSpace e = esdf_free_space(pts, 0.0, Eigen::Vector3d::Zero());
  const EsdfSlice& s = e.slice;
  ASSERT_EQ(s.layer, layer);
  const auto at = [&](int i, int j) {
    return s.distance[static_cast<std::size_t>(s.cell_at(voxel_centre(i, j, layer)))];
  };
  EXPECT_NEAR(at(0, 0), 2 * kVoxel, 1e-12);                            // straight below it
  EXPECT_NEAR(at(3, 4), std::sqrt(9.0 + 16.0 + 4.0) * kVoxel, 1e-12);  // not a city-block or chamfer distance
  EXPECT_NEAR(at(10, 7), 3 * kVoxel, 1e-12);                           // nearer the other one
  // Occupied voxels more than max_distance from the slice do not count (nor widen the slice).
  const Points far_above = {voxel_centre(-20, -20, layer + 30), voxel_centre(5, 0, layer),
                            voxel_centre(0, 5, layer)};
  const EsdfSlice f = esdf_free_space(far_above, 0.0, Eigen::Vector3d::Zero()).slice;
  EXPECT_EQ(f.width, 6);
  EXPECT_EQ(f.height, 6);
  EXPECT_NEAR(f.distance[0], 5 * kVoxel, 1e-12);
}

TEST(FreespaceEsdf, CorridorVerticesAreTheBandFartherThanTheThreshold) {
  const Points pts = corridor();
  const EsdfFreeSpace e = esdf_free_space(pts, 0.0, {5.0, 2.0, kSensorHeight});
  ASSERT_EQ(e.free_space.clusters.size(), 1u);
  const FreeSpaceCluster& c = e.free_space.clusters[0];
  // Rows 5 .. 15 (centres 1.1 .. 3.1 m): farther than 0.8 m from both walls; 50 columns.
  EXPECT_EQ(c.points.size(), 11u * 50u);
  double min_y = 1e9, max_y = -1e9;
  for (const auto& p : c.points) {
    min_y = std::min(min_y, p.y());
    max_y = std::max(max_y, p.y());
    EXPECT_NEAR(p.z(), (e.slice.layer + 0.5) * kVoxel, 1e-12);
  }
  EXPECT_NEAR(min_y, 1.1, 1e-9);
  EXPECT_NEAR(max_y, 3.1, 1e-9);
  // Free-band width (outer cell edges): 11 voxels = 4 m between wall centres - 2 x 0.8 m - 1 voxel.
  EXPECT_NEAR(max_y - min_y + kVoxel, 2.2, 1e-9);
  EXPECT_EQ(e.free_space.robot_cluster, 0);
  const Eigen::Vector3d v = e.free_space.clusters[0].points[0];
  EXPECT_NEAR(e.slice.distance[static_cast<std::size_t>(e.slice.cell_at(v))], 1.0, 1e-12);
}

TEST(FreespaceEsdf, WallAcrossTheCorridorSplitsIt) {
  Points pts = corridor();
  add_block(pts, 25, 25, 1, 19);  // a closed wall across at column 25
  const EsdfFreeSpace e = esdf_free_space(pts, 0.0, {8.0, 2.0, kSensorHeight});
  ASSERT_EQ(e.free_space.clusters.size(), 2u);
  EXPECT_EQ(e.free_space.robot_cluster,
            1);  // the cluster at larger x: its first cell comes later in row order
  for (const auto& p : e.free_space.robot()->points) EXPECT_GT(p.x(), 25 * kVoxel);
  // No occupied voxel near the slice: nothing.
  const EsdfFreeSpace none = esdf_free_space({{0.0, 0.0, 20.0}}, 0.0, Eigen::Vector3d::Zero());
  EXPECT_EQ(none.slice.width, 0);
  EXPECT_TRUE(none.free_space.clusters.empty());
  EXPECT_EQ(none.free_space.robot_cluster, -1);
}

TEST(FreespaceEsdf, DeterministicOrderIndependentAndValidated) {
  Points pts = corridor();
  add_block(pts, 25, 25, 1, 8);  // a partial wall: the corridor narrows, still one cluster
  const Eigen::Vector3d robot(5.0, 2.0, kSensorHeight);
  const EsdfFreeSpace a = esdf_free_space(pts, 0.0, robot);
  const Points reversed(pts.rbegin(), pts.rend());
  const EsdfFreeSpace b = esdf_free_space(reversed, 0.0, robot);
  EXPECT_EQ(a.slice.distance, b.slice.distance);
  EXPECT_EQ(a.free_space.cluster_of, b.free_space.cluster_of);
  EXPECT_EQ(a.free_space.robot_vertex, b.free_space.robot_vertex);
  ASSERT_EQ(a.free_space.clusters.size(), 1u);

  EsdfFreeSpaceConfig bad;
  bad.voxel_size = 0.0;
  EXPECT_THROW(esdf_free_space(pts, 0.0, robot, bad), std::invalid_argument);
}

TEST(FreespaceEsdf, MatchesBruteForceOnRandomVoxels) {
  // Scattered occupied voxels (fixed seed) in and around the slice; every slice cell's distance
  // equals the brute-force minimum over the occupied voxel centres, capped at max_distance.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> horizontal(0, 39), vertical(-30, 30);
  const int layer = static_cast<int>(std::floor(1.0 / kVoxel));
  Points pts;
  for (int n = 0; n < 60; ++n) {
    // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
    const int k = layer + vertical(rng), j = horizontal(rng), i = horizontal(rng);
    pts.push_back(voxel_centre(i, j, k));
  }
  EsdfFreeSpaceConfig config;
  config.max_distance = 2.0;  // small enough that some cells are capped
  const EsdfFreeSpace e = esdf_free_space(pts, 0.0, Eigen::Vector3d::Zero(), config);
  const EsdfSlice& s = e.slice;
  ASSERT_GT(s.width * s.height, 0);
  int capped = 0;
  for (int c = 0; c < s.width * s.height; ++c) {
    double best = config.max_distance;
    for (const auto& p : pts) best = std::min(best, (p - s.centre(c)).norm());
    ASSERT_NEAR(s.distance[static_cast<std::size_t>(c)], best, 1e-9) << "cell " << c;
    if (best == config.max_distance) ++capped;
  }
  EXPECT_GT(capped, 0);
}

TEST(FreespaceEsdf, OfficeRoomFromSimulatedScans) {
  // The office scene: every point of every 10th scan of the first 200 (true poses) is occupied
  // (S-Graphs+ integrates whole scans; the floor is 1 m below the slice, farther than 0.8 m);
  // the last scan is taken in room_d. Its free space is room_d's interior, doors closed off.
  const scene::Scene scene = scene::load_scene(std::string(TSGRAPHS_SCENES_DIR) + "/office.yaml");
  const sim::Simulator sim(scene, 1);
  constexpr std::size_t kScans = 200, kStep = 10;
  Points pts;
  std::size_t last = 0;
  for (std::size_t k = 0; k < kScans && k < sim.num_scans(); k += kStep) {
    const Pose3& T = sim.true_poses()[k];
    for (const auto& p : sim.scan(k).points)
      if (p.allFinite()) pts.push_back(T * p.cast<double>());
    last = k;
  }
  const Eigen::Vector3d robot = sim.true_poses()[last].translation();
  const auto start = std::chrono::steady_clock::now();
  const EsdfFreeSpace e = esdf_free_space(pts, robot.z() - scene.sensor.mount_height, robot);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_NE(e.free_space.robot(), nullptr);
  const auto in_room_d = [](const Eigen::Vector3d& p) {
    return p.x() > 0.1 && p.x() < 10.9 && p.y() > 7.3 && p.y() < 12.9;
  };
  const auto& cluster = e.free_space.robot()->points;
  const auto inside = static_cast<std::size_t>(std::count_if(cluster.begin(), cluster.end(), in_room_d));
  std::printf(
      "office ESDF: %zu points, slice %d x %d, %zu clusters, robot's %zu cells, %zu in room_d, %.1f ms\n",
      pts.size(), e.slice.width, e.slice.height, e.free_space.clusters.size(), cluster.size(), inside, ms);
  EXPECT_EQ(inside, cluster.size());
}
