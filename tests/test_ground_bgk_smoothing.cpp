// BGK smoothing on constructed input: the sparse kernel's shape; a node with a steep plane of
// its own among traversable ones is not restored; a lone traversable blip among non-ground is
// removed; a node whose own height is far off the smoothed surface (the storey below, seen
// through a void) or that is cut off from the robot's region is never made traversable.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "tsgraphs/ground/bgk_smoothing.hpp"
#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/ground/traversable_search.hpp"
#include "tsgraphs/ground/tri_grid_ground.hpp"

using namespace tsgraphs;
using namespace tsgraphs::ground;

namespace {

constexpr double kSensorHeight = 0.55;  // the floor is at z = -0.55 (m)
constexpr double kSpacing = 0.04;       // of the constructed points (m)
constexpr double kBlind = 1.3;          // no points nearer than this (m)
constexpr double kHalfSide = 5.0;       // the constructed floor covers [-5, 5] x [-5, 5] (m)

// Floor points, with z = height(x, y) for the points of node `special` (height may be NaN for none).
template <class Height>
PointCloud make_floor(const TriGrid& grid, int special, Height height) {
  PointCloud cloud;
  for (double x = -kHalfSide; x <= kHalfSide; x += kSpacing) {
    for (double y = -kHalfSide; y <= kHalfSide; y += kSpacing) {
      if (std::hypot(x, y) < kBlind) continue;
      const double z = grid.node_at(x, y) == special ? height(x, y) : -kSensorHeight;
      if (std::isfinite(z)) cloud.points.emplace_back(x, y, z);
    }
  }
  return cloud;
}

struct Smoothed {
  TriGridField field;
  std::vector<int> seeds;
  std::vector<std::uint8_t> reached;
  std::vector<SmoothedNode> smoothed;
  std::vector<std::uint8_t> traversable;
};

Smoothed run(TriGridField field, const GroundConfig& config) {
  Smoothed s;
  s.field = std::move(field);
  s.seeds = find_seed_nodes(s.field, config);
  s.reached = search_traversable(&s.field, s.seeds, config);
  s.smoothed = bgk_smooth(s.field, s.reached, config);
  s.traversable = decide_traversable(s.field, s.smoothed, s.seeds, config);
  return s;
}

TEST(SparseKernel, OneAtZeroFallingSmoothlyToZeroAtTheLengthScale) {
  constexpr double l = 1.0;
  EXPECT_DOUBLE_EQ(sparse_kernel(0.0, l), 1.0);
  EXPECT_NEAR(sparse_kernel(l, l), 0.0, 1e-12);
  EXPECT_EQ(sparse_kernel(1.5 * l, l), 0.0);
  EXPECT_NEAR(sparse_kernel(0.999 * l, l), 0.0, 1e-6);  // smooth at the support's edge
  double previous = 1.0;
  for (double d = 0.05; d < l; d += 0.05) {
    const double k = sparse_kernel(d, l);
    EXPECT_LT(k, previous);
    EXPECT_GT(k, 0.0);
    previous = k;
  }
  EXPECT_NEAR(sparse_kernel(0.5, 2.0), sparse_kernel(0.25, 1.0), 1e-12);  // a function of d / l
}

TEST(BgkSmoothing, ASteepNodeAmongGroundIsNotRestored) {
  const GroundConfig config;
  const TriGrid grid(config.resolution, config.max_range);
  const int steep = grid.node_at(3.4, 0.25);
  const double cx = grid.centroid(steep).x();
  // The node's points rise 0.5 m per m (27 degrees): a chair's legs, a mat, or a glass railing
  // at a void's edge, whose neighbours on the slab would vote it traversable.
  const PointCloud cloud =
      make_floor(grid, steep, [&](double x, double) { return -kSensorHeight + 0.5 * (x - cx); });
  const Smoothed s = run(build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config), config);
  ASSERT_EQ(s.field.nodes[steep].state, NodeState::kModelled);
  EXPECT_FALSE(s.field.nodes[steep].ground_like);
  EXPECT_FALSE(s.reached[steep]);
  EXPECT_GE(s.smoothed[steep].probability, config.th_traversable);  // the neighbours vote for it...
  EXPECT_NEAR(s.smoothed[steep].height, -kSensorHeight, 0.01);
  EXPECT_FALSE(s.traversable[steep]);  // ...but its own plane is not a floor's
}

TEST(BgkSmoothing, ALoneTraversableBlipAmongNonGroundIsRemoved) {
  GroundConfig config;
  // Smoothing alone: the nodes around are made non-ground below, but their points still lie on
  // the floor's level, which the search's adoption (traversable_search.hpp) would join.
  config.sparse_min_pts = std::numeric_limits<int>::max();
  const TriGrid grid(config.resolution, config.max_range);
  const PointCloud cloud = make_floor(grid, -1, [](double, double) { return 0.0; });
  TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  const int blip = grid.node_at(2.4, 0.25);
  {
    const Smoothed all = run(field, config);
    ASSERT_TRUE(all.traversable[blip]);  // on a plain floor it is ground
  }
  // Everything around it is non-ground (say, clutter); only the blip is a ground-like seed.
  for (int n = 0; n < static_cast<int>(field.nodes.size()); ++n)
    if (n != blip) field.nodes[n].ground_like = false;
  const Smoothed s = run(field, config);
  ASSERT_EQ(s.seeds, std::vector<int>{blip});
  EXPECT_TRUE(s.reached[blip]);
  EXPECT_LT(s.smoothed[blip].probability, config.th_traversable);
  EXPECT_FALSE(s.traversable[blip]);
}

TEST(BgkSmoothing, TheStoreyBelowSeenThroughAVoidIsNotRestored) {
  const GroundConfig config;
  const TriGrid grid(config.resolution, config.max_range);
  const int hole = grid.node_at(3.4, 0.25);
  // The node's returns come from a floor 4 m below (a void's footprint amid the floor).
  const PointCloud cloud = make_floor(grid, hole, [](double, double) { return -kSensorHeight - 4.0; });
  const Smoothed s = run(build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config), config);
  ASSERT_EQ(s.field.nodes[hole].state, NodeState::kModelled);
  EXPECT_TRUE(s.field.nodes[hole].ground_like);                    // flat...
  EXPECT_FALSE(s.reached[hole]);                                   // ...not reached...
  EXPECT_GE(s.smoothed[hole].probability, config.th_traversable);  // ...amid ground...
  EXPECT_FALSE(s.traversable[hole]);                               // ...but far below the smoothed surface
}

TEST(BgkSmoothing, NodesCutOffFromTheRobotStayOff) {
  const GroundConfig config;
  const TriGrid grid(config.resolution, config.max_range);
  const PointCloud cloud = make_floor(grid, -1, [](double, double) { return 0.0; });
  const TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  const std::vector<int> seeds = find_seed_nodes(field, config);
  // Smoothing says "ground" everywhere except on a band of non-ground nodes across the floor
  // at x in [3, 3.5] (a wall) and round the floor's edge (walls, so that no link goes round
  // the band's ends across empty nodes): the nodes beyond the band must stay off.
  std::vector<SmoothedNode> smoothed(field.nodes.size());
  for (std::size_t n = 0; n < field.nodes.size(); ++n) {
    const Eigen::Vector3f& c = field.nodes[n].centre;
    const bool wall = (c.x() > 3.0f && c.x() < 3.5f) || std::abs(c.x()) > 4.5f || std::abs(c.y()) > 4.5f;
    smoothed[n].has_surface = true;
    smoothed[n].height = static_cast<float>(-kSensorHeight);
    smoothed[n].probability = wall ? 0.0f : 0.9f;
  }
  const std::vector<std::uint8_t> traversable = decide_traversable(field, smoothed, seeds, config);
  int near = 0, beyond = 0;
  for (std::size_t n = 0; n < field.nodes.size(); ++n) {
    if (!traversable[n]) continue;
    (field.nodes[n].centre.x() > 3.5f ? beyond : near)++;
  }
  EXPECT_GT(near, 1000);
  EXPECT_EQ(beyond, 0);
}

}  // namespace
