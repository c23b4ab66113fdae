// The global traversable node map: one node per cell and height layer, revisits fuse, storeys
// and a ramp under a landing stay apart, nodes move with their anchor keyframe on update() and
// merge when they come to coincide, and the same input gives the same map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "tsgraphs/ground/traversable_node_map.hpp"

using namespace tsgraphs;
using namespace tsgraphs::ground;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSensorHeight = 0.55;  // sensor above the ground it stands on (m)
constexpr double kSpacing = 0.2;        // observation lattice in the sensor frame (m), finer than a cell
constexpr double kCell = 0.25;          // NodeMapConfig's default cell_size

/// Ground z = z0 + slope * x over a box of the map.
struct Surface {
  double z0 = 0.0;
  double slope = 0.0;
  double x_min = -kInf, x_max = kInf, y_min = -kInf, y_max = kInf;
};

/// The surface as seen from a sensor at true pose T_map_sensor: a lattice of kSpacing within
/// +-half of the sensor (in its frame, horizontally), as observations in the sensor frame.
std::vector<NodeObservation> observe(const Pose3& T_map_sensor, const Surface& s, double half,
                                     double probability = 1.0) {
  std::vector<NodeObservation> out;
  const int n = static_cast<int>(std::lround(2.0 * half / kSpacing));
  const Eigen::Vector3d normal_map = Eigen::Vector3d(-s.slope, 0.0, 1.0).normalized();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const Eigen::Vector3d offset(-half + i * kSpacing, -half + j * kSpacing, 0.0);
      Eigen::Vector3d p = T_map_sensor.translation() + T_map_sensor.linear() * offset;
      if (p.x() < s.x_min || p.x() > s.x_max || p.y() < s.y_min || p.y() > s.y_max) continue;
      p.z() = s.z0 + s.slope * p.x();
      NodeObservation obs;
      obs.position = T_map_sensor.inverse() * p;
      obs.normal = T_map_sensor.linear().transpose() * normal_map;
      obs.probability = probability;
      out.push_back(obs);
    }
  }
  return out;
}

/// The grid cells that the observations fall in, placed with pose T (as the map places them).
std::set<std::pair<std::int64_t, std::int64_t>> cells_of(
    const Pose3& T, const std::vector<NodeObservation>& obs,
    std::set<std::pair<std::int64_t, std::int64_t>> cells = {}) {
  for (const NodeObservation& o : obs) {
    const Eigen::Vector3d p = T * o.position;
    cells.emplace(static_cast<std::int64_t>(std::floor(p.x() / kCell)),
                  static_cast<std::int64_t>(std::floor(p.y() / kCell)));
  }
  return cells;
}

Pose3 standing_on(double x, double y, double ground_z, double yaw = 0.0) {
  return make_pose(Eigen::Vector3d(x, y, ground_z + kSensorHeight), yaw);
}

// The corridor of the lap tests: keyframes every 10/19 m along a 10 m path from (kStart, kStart)
// in +x, each seeing +-kHalf of floor. kStart keeps the floor's edges off cell borders, so pose
// noise does not open a new row of cells along them.
constexpr int kKeyframesPerLap = 20;
constexpr double kPathLength = 10.0, kStart = 0.1, kHalf = 3.0;
constexpr double kNoiseXY = 0.03, kNoiseZ = 0.01,
                 kNoiseYaw = 0.3 * M_PI / 180.0;  // pose estimate noise (m, rad)

Pose3 lap_pose(int i, bool reverse) {
  const double x = kStart + kPathLength * (reverse ? kKeyframesPerLap - 1 - i : i) / (kKeyframesPerLap - 1);
  return standing_on(x, kStart, 0.0, reverse ? M_PI : 0.0);
}

/// Fuses `laps` laps of the corridor (odd laps driven backwards), each keyframe at its true pose
/// perturbed by the noise above.
void drive_laps(TraversableNodeMap& map, int first_lap, int laps, std::mt19937& rng) {
  std::normal_distribution<double> unit(0.0, 1.0);
  for (int lap = first_lap; lap < first_lap + laps; ++lap) {
    for (int i = 0; i < kKeyframesPerLap; ++i) {
      const Pose3 truth = lap_pose(i, lap % 2 == 1);
      Pose3 estimate = truth;
      // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
      const double nz = kNoiseZ * unit(rng), ny = kNoiseXY * unit(rng), nx = kNoiseXY * unit(rng);
      estimate.translation() += Eigen::Vector3d(nx, ny, nz);
      estimate.linear() = Eigen::AngleAxisd(kNoiseYaw * unit(rng), Eigen::Vector3d::UnitZ()) * truth.linear();
      map.fuse(lap * kKeyframesPerLap + i, estimate, observe(truth, Surface{}, kHalf));
    }
  }
}

void expect_same_maps(const TraversableNodeMap& a, const TraversableNodeMap& b) {
  const auto na = a.nodes(), nb = b.nodes();
  ASSERT_EQ(na.size(), nb.size());
  for (std::size_t i = 0; i < na.size(); ++i) {
    EXPECT_EQ(na[i]->id, nb[i]->id);
    EXPECT_EQ(na[i]->anchor_keyframe, nb[i]->anchor_keyframe);
    EXPECT_EQ(na[i]->local, nb[i]->local);
    EXPECT_EQ(na[i]->local_normal, nb[i]->local_normal);
    EXPECT_EQ(na[i]->position, nb[i]->position);
    EXPECT_EQ(na[i]->normal, nb[i]->normal);
    EXPECT_EQ(na[i]->probability, nb[i]->probability);
    EXPECT_EQ(na[i]->observations, nb[i]->observations);
    EXPECT_EQ(na[i]->keyframes, nb[i]->keyframes);
  }
}

TEST(GroundNodeMap, FloorAlongAPathHasOneNodePerCell) {
  TraversableNodeMap map;
  std::set<std::pair<std::int64_t, std::int64_t>> cells;
  int observations = 0;
  for (int i = 0; i < kKeyframesPerLap; ++i) {
    const Pose3 T = lap_pose(i, false);
    const std::vector<NodeObservation> obs = observe(T, Surface{}, kHalf);
    cells = cells_of(T, obs, std::move(cells));
    observations += static_cast<int>(obs.size());
    map.fuse(i, T, obs);
  }
  const double area = (kPathLength + 2.0 * kHalf) * (2.0 * kHalf);
  const double expected = area / (kCell * kCell);  // 1536 cells
  EXPECT_EQ(map.size(),
            cells.size());  // one node per cell reached: 65 x 25 = 1625, the rim's cells are partial
  EXPECT_NEAR(static_cast<double>(map.size()), expected, 0.1 * expected);

  int fused = 0;
  for (const GlobalNode* n : map.nodes()) {
    EXPECT_NEAR(n->position.z(), 0.0, 1e-9);
    EXPECT_NEAR(n->normal.z(), 1.0, 1e-9);
    EXPECT_DOUBLE_EQ(n->probability, 1.0);
    EXPECT_LE(n->keyframes.size(), static_cast<std::size_t>(map.config().max_keyframes_per_node));
    EXPECT_NEAR((n->position - lap_pose(n->anchor_keyframe, false) * n->local).norm(), 0.0, 1e-12);
    fused += n->observations;
  }
  EXPECT_EQ(fused, observations);  // every observation went into exactly one node
}

TEST(GroundNodeMap, TenLapsKeepTheNodeCountOfTwoLaps) {
  TraversableNodeMap map;
  std::mt19937 rng(7);
  drive_laps(map, 0, 2, rng);
  const std::size_t two_laps = map.size();
  drive_laps(map, 2, 8, rng);
  const std::size_t ten_laps = map.size();
  RecordProperty("nodes_after_2_laps", static_cast<int>(two_laps));
  RecordProperty("nodes_after_10_laps", static_cast<int>(ten_laps));
  std::printf("nodes after 2 laps %zu, after 10 laps %zu (+%.1f %%)\n", two_laps, ten_laps,
              100.0 * (static_cast<double>(ten_laps) / static_cast<double>(two_laps) - 1.0));
  EXPECT_LE(static_cast<double>(ten_laps), 1.10 * static_cast<double>(two_laps));

  const double expected = (kPathLength + 2.0 * kHalf) * (2.0 * kHalf) / (kCell * kCell);
  EXPECT_NEAR(static_cast<double>(ten_laps), expected, 0.1 * expected);
  for (const GlobalNode* n : map.nodes()) {
    EXPECT_LT(std::abs(n->position.z()), 5.0 * kNoiseZ);  // yaw noise leaves heights alone
    ASSERT_LE(n->keyframes.size(), 8u);
    for (std::size_t k = 1; k < n->keyframes.size(); ++k) EXPECT_LT(n->keyframes[k - 1], n->keyframes[k]);
  }
}

TEST(GroundNodeMap, TwoStoreysInOneFootprintAreTwoLayers) {
  constexpr double kStorey = 3.0;
  const Surface ground{0.0, 0.0, 0.0, 4.0, 0.0, 4.0};
  const Surface upper{kStorey, 0.0, 0.0, 4.0, 0.0, 4.0};
  TraversableNodeMap map;
  std::set<std::pair<std::int64_t, std::int64_t>> cells;
  int id = 0;
  for (double x : {1.03, 2.03, 3.03}) {
    const Pose3 down = standing_on(x, 2.03, 0.0), up = standing_on(x, 2.03, kStorey);
    const auto seen_down = observe(down, ground, 3.0), seen_up = observe(up, upper, 3.0);
    cells = cells_of(down, seen_down, std::move(cells));
    map.fuse(id++, down, seen_down);
    map.fuse(id++, up, seen_up);
  }
  ASSERT_EQ(map.size(), 2 * cells.size());  // 16 x 16 cells, twice
  const auto lower_nodes = map.nodes_in_height_range(-0.5, 0.5);
  const auto upper_nodes = map.nodes_in_height_range(kStorey - 0.5, kStorey + 0.5);
  EXPECT_EQ(lower_nodes.size(), cells.size());
  EXPECT_EQ(upper_nodes.size(), cells.size());
  for (const GlobalNode* n : lower_nodes) {
    EXPECT_NEAR(n->position.z(), 0.0, 1e-9);
    // Straight above it, in the same cell, the upper storey's node and nothing else.
    const auto above = map.nodes_near(n->position + Eigen::Vector3d(0, 0, kStorey), 0.5 * kCell);
    ASSERT_GE(above.size(), 1u);
    for (const GlobalNode* a : above) EXPECT_NEAR(a->position.z(), kStorey, 1e-9);
  }
  for (const GlobalNode* n : upper_nodes) EXPECT_NEAR(n->position.z(), kStorey, 1e-9);
}

TEST(GroundNodeMap, RampUnderALandingKeepsBothSurfaces) {
  // A ramp rising 0.25 per metre over x in [0, 6], under a landing at 2.5 m over x in [3, 6]:
  // at least 1 m between them, more than level_tolerance.
  constexpr double kSlope = 0.25, kLanding = 2.5;
  const Surface ramp{0.0, kSlope, 0.0, 6.0, 0.0, 2.0};
  const Surface landing{kLanding, 0.0, 3.0, 6.0, 0.0, 2.0};
  TraversableNodeMap map;
  std::set<std::pair<std::int64_t, std::int64_t>> ramp_cells, landing_cells;
  int id = 0;
  for (double x : {0.53, 1.53, 2.53, 3.53, 4.53, 5.53}) {
    // On the ramp the sensor is pitched with it, so observations are not in a level frame.
    const Pose3 on_ramp =
        make_pose(Eigen::Vector3d(x, 1.03, kSlope * x + kSensorHeight), 0.0, -std::atan(kSlope));
    const auto seen = observe(on_ramp, ramp, 1.5);
    ramp_cells = cells_of(on_ramp, seen, std::move(ramp_cells));
    map.fuse(id++, on_ramp, seen);
  }
  for (double x : {3.53, 4.53, 5.53}) {
    const Pose3 on_landing = standing_on(x, 1.03, kLanding);
    const auto seen = observe(on_landing, landing, 1.5);
    landing_cells = cells_of(on_landing, seen, std::move(landing_cells));
    map.fuse(id++, on_landing, seen);
  }
  EXPECT_EQ(map.size(), ramp_cells.size() + landing_cells.size());
  const Eigen::Vector3d ramp_normal = Eigen::Vector3d(-kSlope, 0.0, 1.0).normalized();
  int ramp_nodes = 0, landing_nodes = 0;
  for (const GlobalNode* n : map.nodes()) {
    if (n->position.z() > 2.0) {
      ++landing_nodes;
      EXPECT_NEAR(n->position.z(), kLanding, 1e-9);
    } else {
      ++ramp_nodes;
      EXPECT_NEAR(n->position.z(), kSlope * n->position.x(), 1e-9);  // the mean of points of a plane is on it
      EXPECT_NEAR((n->normal - ramp_normal).norm(), 0.0, 1e-9);
    }
  }
  EXPECT_EQ(ramp_nodes, static_cast<int>(ramp_cells.size()));
  EXPECT_EQ(landing_nodes, static_cast<int>(landing_cells.size()));

  // Under the landing, a query on the ramp finds only the ramp, one on the landing only the landing.
  const Eigen::Vector3d on_ramp(4.5, 1.0, kSlope * 4.5);
  const auto near_ramp = map.nodes_near(on_ramp, 0.6);
  ASSERT_FALSE(near_ramp.empty());
  for (const GlobalNode* n : near_ramp) EXPECT_NEAR(n->position.z(), kSlope * n->position.x(), 1e-9);
  const auto near_landing = map.nodes_near(Eigen::Vector3d(4.5, 1.0, kLanding), 0.6);
  ASSERT_FALSE(near_landing.empty());
  for (const GlobalNode* n : near_landing) EXPECT_NEAR(n->position.z(), kLanding, 1e-9);
}

TEST(GroundNodeMap, UpdateMovesNodesWithTheirAnchor) {
  TraversableNodeMap map;
  const Pose3 T0 = standing_on(0.03, 0.03, 0.0), T1 = standing_on(5.03, 0.03, 0.0);
  map.fuse(0, T0, observe(T0, Surface{}, 1.0));
  map.fuse(1, T1, observe(T1, Surface{}, 1.0));
  // Keyframe 2 sees a part of keyframe 1's floor: it fuses into keyframe 1's nodes, adds none.
  const Pose3 T2 = standing_on(5.08, 0.08, 0.0, 0.3);
  const std::size_t before_2 = map.size();
  map.fuse(2, T2, observe(T2, Surface{}, 0.5));
  ASSERT_EQ(map.size(), before_2);

  std::vector<Eigen::Vector3d> before;
  for (const GlobalNode* n : map.nodes()) before.push_back(n->position);
  Pose3 T1_moved = T1;
  T1_moved.translation() += Eigen::Vector3d(1.0, 0.0, 0.0);
  map.update([&](int id) { return id == 0 ? T0 : id == 1 ? T1_moved : T2; });
  ASSERT_EQ(map.size(), before.size());

  int moved = 0, seen_by_2 = 0;
  for (const GlobalNode* n : map.nodes()) {
    const Eigen::Vector3d shift = n->position - before[static_cast<std::size_t>(n->id)];
    if (n->anchor_keyframe == 1) {
      ++moved;
      EXPECT_NEAR((shift - Eigen::Vector3d(1.0, 0.0, 0.0)).norm(), 0.0, 1e-9);
      if (n->keyframes == std::vector<int>{1, 2}) ++seen_by_2;
    } else {
      EXPECT_EQ(n->anchor_keyframe, 0);
      EXPECT_EQ(shift.norm(), 0.0);
    }
  }
  EXPECT_GT(moved, 0);
  EXPECT_GT(seen_by_2, 0);
  // The index follows: keyframe 1's floor is found at its new place, not at the old one.
  const auto at_new = map.nodes_near(Eigen::Vector3d(6.53, 0.0, 0.0), 0.3);
  ASSERT_FALSE(at_new.empty());
  for (const GlobalNode* n : at_new) EXPECT_EQ(n->anchor_keyframe, 1);
  EXPECT_TRUE(map.nodes_near(Eigen::Vector3d(4.3, 0.0, 0.0), 0.2).empty());

  // A rotation about the keyframe: every node is exactly the anchor pose times its local position.
  const Pose3 T1_turned = make_pose(T1_moved.translation(), 0.2);
  map.update([&](int id) { return id == 0 ? T0 : id == 1 ? T1_turned : T2; });
  for (const GlobalNode* n : map.nodes()) {
    const Pose3& T = n->anchor_keyframe == 1 ? T1_turned : T0;
    EXPECT_NEAR((n->position - T * n->local).norm(), 0.0, 1e-12);
    EXPECT_NEAR((n->normal - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  }
}

TEST(GroundNodeMap, NodesThatComeToCoincideMerge) {
  TraversableNodeMap map;
  const Pose3 truth = standing_on(1.03, 1.03, 0.0);
  const auto seen = observe(truth, Surface{}, 1.0);
  map.fuse(0, truth, seen);
  const std::size_t single = map.size();
  int first_ids_end = 0;
  for (const GlobalNode* n : map.nodes()) first_ids_end = std::max(first_ids_end, n->id + 1);

  // Keyframe 1 sees the same floor, but its pose estimate is 3 m off: a second copy of the floor.
  Pose3 wrong = truth;
  wrong.translation().x() += 3.0;
  map.fuse(1, wrong, seen);
  ASSERT_EQ(map.size(), 2 * single);

  // Corrected, the copies coincide cell by cell and merge into the lower ids.
  map.update([&](int) { return truth; });
  EXPECT_EQ(map.size(), single);
  int observations = 0;
  for (const GlobalNode* n : map.nodes()) {
    EXPECT_LT(n->id, first_ids_end);
    EXPECT_EQ(n->anchor_keyframe, 0);
    EXPECT_EQ(n->keyframes, (std::vector<int>{0, 1}));
    EXPECT_EQ(n->observations % 2, 0);
    EXPECT_NEAR(n->position.z(), 0.0, 1e-9);
    observations += n->observations;
  }
  EXPECT_EQ(observations, 2 * static_cast<int>(seen.size()));

  // Merged ids are holes, never reused: a new node takes the next id after every id ever given.
  const Pose3 elsewhere = standing_on(20.03, 0.03, 0.0);
  map.fuse(2, elsewhere, observe(elsewhere, Surface{}, 0.0));
  ASSERT_EQ(map.size(), single + 1);
  EXPECT_EQ(map.nodes().back()->id, static_cast<int>(2 * single));
}

TEST(GroundNodeMap, FuseAveragesAndSkipsUntraversableObservations) {
  TraversableNodeMap map;
  const Pose3 T = standing_on(0.03, 0.03, 0.0);
  std::vector<NodeObservation> mixed = observe(T, Surface{}, 1.0);
  int kept = 0;
  for (std::size_t i = 0; i < mixed.size(); ++i) {
    mixed[i].probability = i % 2 == 0 ? 0.3 : 0.9;  // below and above min_probability 0.5
    kept += i % 2 == 1 ? 1 : 0;
  }
  map.fuse(0, T, mixed);
  int observations = 0;
  for (const GlobalNode* n : map.nodes()) {
    EXPECT_DOUBLE_EQ(n->probability, 0.9);
    observations += n->observations;
  }
  EXPECT_EQ(observations, kept);

  TraversableNodeMap single;
  NodeObservation obs;
  obs.position = Eigen::Vector3d(0.05, 0.05, -kSensorHeight);
  obs.probability = 0.4;
  single.fuse(0, T, {obs});
  EXPECT_EQ(single.size(), 0u);
  obs.probability = 0.6;
  single.fuse(1, T, {obs});
  obs.probability = 1.0;
  obs.position.z() += 0.1;  // within level_tolerance: the same node, its height is the mean
  single.fuse(2, T, {obs});
  ASSERT_EQ(single.size(), 1u);
  const GlobalNode& n = *single.nodes().front();
  EXPECT_DOUBLE_EQ(n.probability, 0.8);
  EXPECT_NEAR(n.position.z(), 0.05, 1e-12);
  EXPECT_EQ(n.observations, 2);
  EXPECT_EQ(n.keyframes, (std::vector<int>{1, 2}));
}

TEST(GroundNodeMap, KeyframeListIsCappedMostRecentLastWithoutRepeats) {
  NodeMapConfig config;
  config.max_keyframes_per_node = 4;
  TraversableNodeMap map(config);
  const Pose3 T = standing_on(0.03, 0.03, 0.0);
  // Two observations in one cell from one keyframe: one node, seen twice, listed once.
  NodeObservation a, b;
  a.position = Eigen::Vector3d(0.05, 0.05, -kSensorHeight);
  b.position = Eigen::Vector3d(0.15, 0.15, -kSensorHeight);
  map.fuse(10, T, {a, b});
  ASSERT_EQ(map.size(), 1u);
  EXPECT_EQ(map.nodes().front()->observations, 2);
  EXPECT_EQ(map.nodes().front()->keyframes, std::vector<int>{10});
  for (int k = 11; k <= 16; ++k) map.fuse(k, T, {a});
  EXPECT_EQ(map.nodes().front()->keyframes, (std::vector<int>{13, 14, 15, 16}));
  map.fuse(14, T, {a});  // seen again by 14: it becomes the most recent
  EXPECT_EQ(map.nodes().front()->keyframes, (std::vector<int>{13, 15, 16, 14}));
  EXPECT_EQ(map.nodes().front()->observations, 9);

  // Keyframes 20 and 21 see it with a pose 3 m off: a second node. Corrected, it merges in, and the
  // merged list is the 4 most recently fused of both, in fusing order.
  Pose3 wrong = T;
  wrong.translation().x() += 3.0;
  map.fuse(20, wrong, {a});
  map.fuse(21, wrong, {a});
  ASSERT_EQ(map.size(), 2u);
  map.update([&](int) { return T; });
  ASSERT_EQ(map.size(), 1u);
  EXPECT_EQ(map.nodes().front()->keyframes, (std::vector<int>{16, 14, 20, 21}));
  EXPECT_EQ(map.nodes().front()->observations, 11);
}

TEST(GroundNodeMap, RefusingAKeyframeWithANewPoseMovesItsNodes) {
  TraversableNodeMap map;
  const Pose3 T = standing_on(0.03, 0.03, 0.0);
  map.fuse(0, T, observe(T, Surface{}, 0.5));
  std::vector<Eigen::Vector3d> before;
  for (const GlobalNode* n : map.nodes()) before.push_back(n->position);
  Pose3 moved = T;
  moved.translation().y() += 2.0;
  map.fuse(0, moved, {});
  for (const GlobalNode* n : map.nodes()) {
    const Eigen::Vector3d shift = n->position - before[static_cast<std::size_t>(n->id)];
    EXPECT_NEAR((shift - Eigen::Vector3d(0.0, 2.0, 0.0)).norm(), 0.0, 1e-12);
  }
}

TEST(GroundNodeMap, SameInputGivesTheSameMap) {
  auto build = [] {
    TraversableNodeMap map;
    std::mt19937 rng(3);
    drive_laps(map, 0, 3, rng);
    // A correction that makes nodes of different anchors share cells: merges happen.
    std::mt19937 pose_rng(5);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<Pose3> corrected;
    for (int k = 0; k < 3 * kKeyframesPerLap; ++k) {
      Pose3 T = lap_pose(k % kKeyframesPerLap, (k / kKeyframesPerLap) % 2 == 1);
      T.translation() += Eigen::Vector3d(0.1 * unit(pose_rng), 0.1 * unit(pose_rng), 0.0);
      corrected.push_back(T);
    }
    const std::size_t before = map.size();
    map.update([&](int id) { return corrected[static_cast<std::size_t>(id)]; });
    EXPECT_LT(map.size(), before);
    drive_laps(map, 3, 1, rng);
    return map;
  };
  const TraversableNodeMap a = build(), b = build();
  expect_same_maps(a, b);
}

TEST(GroundNodeMap, NodesNearAreNearestFirstWithinRadiusAndLevel) {
  TraversableNodeMap map;
  const Pose3 I = Pose3::Identity();
  auto at = [](double x, double y, double z) {
    NodeObservation o;
    o.position = Eigen::Vector3d(x, y, z);
    return o;
  };
  // Four nodes at the same distance from (0.25, 0.25), fused out of position order, then a farther
  // one, one a storey up and one in a far cell.
  map.fuse(0, I,
           {at(0.375, 0.375, 0.0), at(0.125, 0.375, 0.0), at(0.375, 0.125, 0.0), at(0.125, 0.125, 0.0),
            at(0.625, 0.125, 0.0), at(0.125, 0.125, 1.0), at(5.0, 5.0, 0.0)});
  ASSERT_EQ(map.size(), 7u);
  auto ids = [](const std::vector<const GlobalNode*>& v) {
    std::vector<int> out;
    for (const GlobalNode* n : v) out.push_back(n->id);
    return out;
  };
  const Eigen::Vector3d q(0.25, 0.25, 0.1);
  EXPECT_EQ(ids(map.nodes_near(q, 0.1)), std::vector<int>{});
  EXPECT_EQ(ids(map.nodes_near(q, 0.2)), (std::vector<int>{0, 1, 2, 3}));  // ties by id
  EXPECT_EQ(ids(map.nodes_near(q, 0.4)), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(ids(map.nodes_near(q, 100.0)), (std::vector<int>{0, 1, 2, 3, 4, 6}));  // more cells than nodes
  EXPECT_EQ(ids(map.nodes_near(Eigen::Vector3d(0.25, 0.25, 0.9), 0.2)), std::vector<int>{5});

  // On a real floor, against a brute-force search over every node.
  TraversableNodeMap floor;
  std::mt19937 rng(11);
  drive_laps(floor, 0, 2, rng);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(2.0, 0.3, 0.0), Eigen::Vector3d(9.9, -2.7, 0.2),
                                   Eigen::Vector3d(-3.2, 0.1, 0.0), Eigen::Vector3d(5.0, 0.0, 0.7)}) {
    for (double radius : {0.3, 1.0, 2.5}) {
      std::vector<std::pair<double, int>> brute;
      for (const GlobalNode* n : floor.nodes()) {
        const double d2 = (n->position.head<2>() - p.head<2>()).squaredNorm();
        if (d2 <= radius * radius && std::abs(n->position.z() - p.z()) <= floor.config().level_tolerance) {
          brute.emplace_back(d2, n->id);
        }
      }
      std::sort(brute.begin(), brute.end());
      std::vector<int> expected;
      for (const auto& [d2, id] : brute) expected.push_back(id);
      EXPECT_EQ(ids(floor.nodes_near(p, radius)), expected) << p.transpose() << " r " << radius;
    }
  }
}

}  // namespace
