// The breadth-first traversable search on constructed input: the local convexity/concavity
// test; the seeds under the robot; a 0.45 m step's top is not reached, a 7 degree ramp is, and
// a floor patch 1 m lower across a gap is never traversable, not even after smoothing; far
// floor seen only on sparse scan rings is reached, a far platform and a far drop are not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/ground/traversable_search.hpp"
#include "tsgraphs/ground/tri_grid_ground.hpp"

using namespace tsgraphs;
using namespace tsgraphs::ground;

namespace {

constexpr double kSensorHeight = 0.55;  // the robot's floor is at z = -0.55 (m)
constexpr double kSpacing = 0.04;       // of the constructed points (m)
constexpr double kBlind = 1.3;     // no points nearer than this (as with a real sensor's lowest beam) (m)
constexpr double kHalfSide = 6.0;  // the constructed ground covers [-6, 6] x [-6, 6] (m)
constexpr double kDeg = M_PI / 180.0;

// Points on the surface z = height(x, y) over the square, where height returns a number (NaN: no surface).
template <class Height>
PointCloud make_ground(Height height) {
  PointCloud cloud;
  for (double x = -kHalfSide; x <= kHalfSide; x += kSpacing) {
    for (double y = -kHalfSide; y <= kHalfSide; y += kSpacing) {
      if (std::hypot(x, y) < kBlind) continue;
      const double z = height(x, y);
      if (std::isfinite(z)) cloud.points.emplace_back(x, y, z);
    }
  }
  return cloud;
}

TriGridNode plane_node(const Eigen::Vector3f& centre, const Eigen::Vector3f& normal) {
  TriGridNode n;
  n.state = NodeState::kModelled;
  n.ground_like = true;
  n.centre = centre;
  n.normal = normal.normalized();
  return n;
}

struct Searched {
  TriGridField field;
  std::vector<int> seeds;
  std::vector<std::uint8_t> reached;
};

Searched search(const PointCloud& cloud, const GroundConfig& config) {
  Searched s;
  s.field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  s.seeds = find_seed_nodes(s.field, config);
  s.reached = search_traversable(&s.field, s.seeds, config);
  return s;
}

TEST(LocalConvexity, CoplanarNodesPassAStepOrAKinkFails) {
  const GroundConfig config;
  const Eigen::Vector3f up = Eigen::Vector3f::UnitZ();
  const TriGridNode a = plane_node({0.0f, 0.0f, -0.55f}, up);
  EXPECT_TRUE(locally_convex(a, plane_node({0.17f, 0.0f, -0.55f}, up), config));
  EXPECT_TRUE(locally_convex(a, plane_node({0.17f, 0.0f, -0.545f}, up), config));  // noise
  EXPECT_FALSE(locally_convex(a, plane_node({0.17f, 0.0f, -0.10f}, up), config));  // 0.45 m step
  EXPECT_FALSE(locally_convex(
      a, plane_node({0.17f, 0.0f, -0.55f}, {std::sin(30 * kDeg), 0.0f, std::cos(30 * kDeg)}), config));
  // A long link (across empty nodes) may bend more, but not climb more than th_dist.
  EXPECT_TRUE(locally_convex(a, plane_node({1.5f, 0.0f, -0.52f}, up), config));
  EXPECT_FALSE(locally_convex(a, plane_node({1.5f, 0.0f, -0.40f}, up), config));
}

TEST(SeedNodes, FloorNodesNearTheRobotButNotAPlatform) {
  GroundConfig config;
  const PointCloud cloud = make_ground([](double x, double) { return x > 2.0 ? -0.10 : -kSensorHeight; });
  const TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  const std::vector<int> seeds = find_seed_nodes(field, config);
  ASSERT_GT(seeds.size(), 100u);
  for (int s : seeds) {
    EXPECT_LE(field.nodes[s].centre.head<2>().norm(), config.seed_radius);
    EXPECT_NEAR(field.nodes[s].centre.z(), -kSensorHeight, 0.01);
  }
}

// A ring crossing the face of a void's far edge, seen from across the void, is a line a little
// below the floor; its tilt is the prior's, and carried 6 m to the robot it can land on the
// robot's floor. A face's foot is a seed only at the floor's level where it stands. Any seed
// is no farther above or below the robot's floor than a ramp could take it.
TEST(SeedNodes, AFaceFootOrABoxEdgeIsNoSeedButARampIs) {
  GroundConfig config;
  config.seed_radius = 8.0;
  TriGridField field;
  field.grid = TriGrid(config.resolution, config.max_range);
  field.nodes.resize(static_cast<std::size_t>(field.grid.num_nodes()));
  const float floor = static_cast<float>(-kSensorHeight);
  const float tilt = 0.15f / 6.0f;  // makes a plane 0.15 m below the floor at x = 6 meet it at the robot
  const auto place = [&](double x, double y, float z, const Eigen::Vector3f& normal, bool face_foot) {
    const int k = field.grid.node_at(x, y);
    TriGridNode& n = field.nodes[k];
    n = plane_node({static_cast<float>(x), static_cast<float>(y), z}, normal);
    n.centre.head<2>() = field.grid.centroid(k).cast<float>();
    n.centre.z() = z;
    n.face_foot = face_foot;
    return k;
  };
  const int void_face = place(6.0, 0.0, floor - 0.15f, {tilt, 0.0f, 1.0f}, true);
  const int wall_foot = place(6.0, 2.0, floor + 0.02f, Eigen::Vector3f::UnitZ(), true);
  const int floor_patch = place(6.0, -2.0, floor - 0.15f, {tilt, 0.0f, 1.0f}, false);  // a measured slope
  // The edge of a box top 0.78 m high, 3 m away, whose plane the box's side tips by 15 degrees
  // towards the robot's floor; and an 11 degree ramp the robot stands at the foot of.
  const float box_tilt = 0.78f / 3.0f, ramp_tilt = std::tan(11.0f * static_cast<float>(kDeg));
  const int box_edge = place(-3.0, 0.0, floor + 0.78f, {box_tilt, 0.0f, 1.0f}, false);
  const int box_top = place(3.0, 3.0, floor + 0.78f, Eigen::Vector3f::UnitZ(), false);  // level, too high
  const int ramp = place(0.0, 4.0, floor + 4.0f * ramp_tilt, {0.0f, -ramp_tilt, 1.0f}, false);
  const std::vector<int> seeds = find_seed_nodes(field, config);
  EXPECT_EQ(std::count(seeds.begin(), seeds.end(), void_face), 0);
  EXPECT_EQ(std::count(seeds.begin(), seeds.end(), wall_foot), 1);
  EXPECT_EQ(std::count(seeds.begin(), seeds.end(), floor_patch), 1);
  EXPECT_EQ(std::count(seeds.begin(), seeds.end(), box_edge), 0);
  EXPECT_EQ(std::count(seeds.begin(), seeds.end(), box_top), 0);
  EXPECT_EQ(std::count(seeds.begin(), seeds.end(), ramp), 1);
}

TEST(TraversableSearch, TheTopOfA45cmStepIsNotReached) {
  const GroundConfig config;
  constexpr double kStepX = 3.0, kStepTop = -kSensorHeight + 0.45;
  PointCloud cloud = make_ground([](double x, double) { return x >= kStepX ? kStepTop : -kSensorHeight; });
  for (double y = -kHalfSide; y <= kHalfSide; y += kSpacing)  // the step's face
    for (double z = -kSensorHeight; z < kStepTop; z += kSpacing) cloud.points.emplace_back(kStepX, y, z);
  const Searched s = search(cloud, config);
  int floor_nodes = 0, floor_reached = 0, top_reached = 0;
  for (std::size_t n = 0; n < s.field.nodes.size(); ++n) {
    const TriGridNode& node = s.field.nodes[n];
    if (node.state != NodeState::kModelled) continue;
    if (node.centre.x() < kStepX - config.resolution) {
      ++floor_nodes;
      floor_reached += s.reached[n];
    }
    if (s.reached[n] && node.centre.z() > -0.3) ++top_reached;
  }
  EXPECT_GT(floor_reached, 0.95 * floor_nodes);
  EXPECT_EQ(top_reached, 0);

  // The whole segmentation: no point of the step's top is ground.
  const GroundScan result = segment_ground(cloud, Eigen::Matrix3d::Identity(), config);
  int top_ground = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (result.labels[i] == GroundLabel::kGround && cloud.points[i].z() > -0.3f) ++top_ground;
  EXPECT_EQ(top_ground, 0);
}

TEST(TraversableSearch, ASevenDegreeRampIsReached) {
  const GroundConfig config;
  constexpr double kFoot = 1.5;  // the ramp rises along x from here
  const double slope = std::tan(7.0 * kDeg);
  const PointCloud cloud =
      make_ground([&](double x, double) { return -kSensorHeight + std::max(0.0, x - kFoot) * slope; });
  const Searched s = search(cloud, config);
  int ramp_nodes = 0, ramp_reached = 0;
  for (std::size_t n = 0; n < s.field.nodes.size(); ++n) {
    const TriGridNode& node = s.field.nodes[n];
    if (node.state != NodeState::kModelled || node.centre.x() < kFoot + config.resolution) continue;
    ++ramp_nodes;
    ramp_reached += s.reached[n];
  }
  ASSERT_GT(ramp_nodes, 500);
  EXPECT_GE(ramp_reached, 0.98 * ramp_nodes);

  const GroundScan result = segment_ground(cloud, Eigen::Matrix3d::Identity(), config);
  int ramp_points = 0, ramp_ground = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cloud.points[i].x() < kFoot + 0.1f) continue;
    ++ramp_points;
    ramp_ground += result.labels[i] == GroundLabel::kGround;
  }
  EXPECT_GE(ramp_ground, 0.97 * ramp_points);
}

TEST(TraversableSearch, AFloorPatchOneMetreLowerAcrossAGapIsNeverTraversable) {
  const GroundConfig config;
  constexpr double kGapFrom = 3.0, kGapTo = 4.0;  // no returns in between (less than max_gap)
  const PointCloud cloud = make_ground([](double x, double) {
    if (x < kGapFrom) return -kSensorHeight;
    if (x < kGapTo) return std::nan("");
    return -kSensorHeight - 1.0;
  });
  const Searched s = search(cloud, config);
  int low_ground_like = 0, low_reached = 0;
  for (std::size_t n = 0; n < s.field.nodes.size(); ++n) {
    if (s.field.nodes[n].centre.x() < kGapTo || s.field.nodes[n].state != NodeState::kModelled) continue;
    low_ground_like += s.field.nodes[n].ground_like;
    low_reached += s.reached[n];
  }
  EXPECT_GT(low_ground_like, 300);  // flat, so ground-like...
  EXPECT_EQ(low_reached, 0);        // ...but not reached from the robot

  const GroundScan result = segment_ground(cloud, Eigen::Matrix3d::Identity(), config);
  int low_traversable = 0, high_traversable = 0, low_ground = 0;
  for (const GroundNode& node : result.nodes) {
    if (!node.traversable) continue;
    (node.centre.z() < -1.0f ? low_traversable : high_traversable)++;
  }
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (result.labels[i] == GroundLabel::kGround && cloud.points[i].z() < -1.0f) ++low_ground;
  EXPECT_GT(high_traversable, 500);
  EXPECT_EQ(low_traversable, 0);
  EXPECT_EQ(low_ground, 0);
}

// Scan rings of an os1-64 (beams 45/63 deg apart, 1024 columns) from kSensorHeight over a floor
// whose height at (x, y) is `height` (NaN: nothing there): far out, each ring crosses a node
// with a handful of points, fewer than num_min_pts, and rings are metres apart.
template <class Height>
PointCloud ring_scan(Height height) {
  PointCloud cloud;
  constexpr int kColumns = 1024;
  const double spacing = 45.0 / 63.0 * kDeg;
  for (int beam = 0; beam < 64; ++beam) {
    const double elevation = -22.5 * kDeg + beam * spacing;
    if (elevation >= 0.0) break;
    for (int c = 0; c < kColumns; ++c) {
      const double azimuth = 2.0 * M_PI * c / kColumns;
      const double r = kSensorHeight / std::tan(-elevation);  // on the robot's floor...
      const double x = r * std::cos(azimuth), y = r * std::sin(azimuth);
      const double z = height(x, y);
      if (!std::isfinite(z) || r > 16.0) continue;
      // ...or, where the floor is elsewhere, where the beam meets that height (it is level).
      const double range = -z / std::tan(-elevation);
      if (range > 16.0 || range < 0.0) continue;
      cloud.points.emplace_back(range * std::cos(azimuth), range * std::sin(azimuth), z);
    }
  }
  return cloud;
}

TEST(LinkGap, SpansTheGapToTheNextFloorRingWhereLongerThanMaxGap) {
  GroundConfig config;  // os1-64 at 0.55 m
  EXPECT_DOUBLE_EQ(link_gap(3.0, config), config.max_gap);
  // At 10 m the next ring out (a beam 0.71 deg flatter) meets the floor 12.9 m out.
  const double next =
      kSensorHeight / std::tan(std::atan2(kSensorHeight, 10.0) - config.ring_spacing_deg * kDeg);
  EXPECT_NEAR(next, 12.9, 0.1);
  EXPECT_DOUBLE_EQ(link_gap(10.0, config), next - 10.0 + config.resolution);
  // At 13 m the next ring is beyond max_range: nothing farther to link to.
  EXPECT_DOUBLE_EQ(link_gap(13.0, config), config.max_gap);
  config.sensor_height = 1.5;  // rings close up: max_gap covers them
  EXPECT_DOUBLE_EQ(link_gap(10.0, config), config.max_gap);
}

TEST(TraversableSearch, FarFloorSeenOnSparseRingsIsGroundButNotAFarPlatformOrDrop) {
  const GroundConfig config;
  constexpr double kPlatformX = 9.0;  // beyond: a 0.3 m platform
  constexpr double kDropX = -9.0;     // beyond: the storey below, 1 m lower
  const PointCloud cloud = ring_scan([](double x, double) {
    if (x > kPlatformX) return -kSensorHeight + 0.3;
    if (x < kDropX) return -kSensorHeight - 1.0;
    return -kSensorHeight;
  });
  const GroundScan result = segment_ground(cloud, Eigen::Matrix3d::Identity(), config);
  int far_floor = 0, far_ground = 0, sparse_nodes = 0, elsewhere_ground = 0;
  const TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    const bool ground = result.labels[i] == GroundLabel::kGround;
    const bool floor = std::abs(p.z() + kSensorHeight) < 0.01f;
    if (!floor) {
      elsewhere_ground += ground;
      continue;
    }
    const double r = p.head<2>().norm();
    if (r < 6.0 || r > config.max_range) continue;
    ++far_floor;
    far_ground += ground;
    const int node = field.point_node[i];
    sparse_nodes += node >= 0 && field.nodes[node].state == NodeState::kUnknown;
  }
  ASSERT_GT(far_floor, 2000);
  EXPECT_GT(sparse_nodes, far_floor / 2);  // the far rings are mostly in nodes without a plane of their own
  EXPECT_GE(far_ground, 0.95 * far_floor);
  EXPECT_EQ(elsewhere_ground, 0);
  for (const GroundNode& node : result.nodes)
    if (node.traversable) {
      EXPECT_LT(std::abs(node.centre.z() + kSensorHeight), 0.02) << node.centre.transpose();
    }
}

TEST(AdoptPlane, AFewPointsOnTheFloorYesAWallFootOrADropNo) {
  GroundConfig config;
  config.max_range = 3.0;
  const TriGridNode floor = plane_node({0.0f, 0.0f, -0.55f}, Eigen::Vector3f::UnitZ());
  // Points in one node 2 m out: a few on the floor's level...
  PointCloud cloud;
  for (int k = 0; k < 4; ++k) cloud.points.emplace_back(2.1f, 0.02f * k, -0.55f + 0.01f * (k % 2));
  const auto adopt = [&](const PointCloud& c, TriGridNode* out) {
    const TriGridField field = build_tri_grid_field(c, Eigen::Matrix3d::Identity(), config);
    const int node = field.point_node[0];
    EXPECT_EQ(field.nodes[node].state, NodeState::kUnknown);
    return adopt_plane(field, floor, node, config, out);
  };
  TriGridNode out;
  ASSERT_TRUE(adopt(cloud, &out));
  EXPECT_EQ(out.state, NodeState::kModelled);
  EXPECT_TRUE(out.ground_like);
  EXPECT_FLOAT_EQ(out.centre.z(), -0.55f);  // the reaching floor's level: chains of adoptions do not climb
  // ...with a ceiling 3 m above: still floor.
  PointCloud ceiling = cloud;
  for (int k = 0; k < 5; ++k) ceiling.points.emplace_back(2.1f, 0.02f * k, 2.45f);
  EXPECT_TRUE(adopt(ceiling, &out));
  // ...at the foot of something standing there: more points up to th_seeds above than on the floor.
  PointCloud foot = cloud;
  for (int k = 0; k < 5; ++k) foot.points.emplace_back(2.1f, 0.0f, -0.45f + 0.07f * k);
  EXPECT_FALSE(adopt(foot, &out));
  // ...at a drop: points 0.2 m below the floor's level.
  PointCloud drop = cloud;
  drop.points.emplace_back(2.15f, 0.0f, -0.75f);
  EXPECT_FALSE(adopt(drop, &out));
  // ...at a void's edge: a return from the storey below.
  PointCloud edge = cloud;
  edge.points.emplace_back(2.15f, 0.0f, -3.55f);
  EXPECT_FALSE(adopt(edge, &out));
  // Too few points on the floor's level.
  config.sparse_min_pts = 5;
  EXPECT_FALSE(adopt(cloud, &out));
}

}  // namespace
