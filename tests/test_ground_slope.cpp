// The ground's slope round each traversable node: a noisy floor reads level, and so do a
// floor whose normals are all biased one way and a step; a ramp reads as steep as it is away
// from its foot; one tilted node does not tilt the floor round it; bad arguments are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "tsgraphs/ground/ground_slope.hpp"

using namespace tsgraphs::ground;

namespace {

constexpr double kCell = 0.25;           // the node map's default cell: one node per cell
constexpr double kRadius = 1.0;          // half the room layer's default floor_window
constexpr double kMaxFloorSlope = 0.05;  // the room layer's default: 1:20, where a walk becomes a ramp
constexpr double kRampSlope = 0.16;      // 9 degrees, the generator's gentlest ramp

/// The unit normal of a surface rising `gx` per metre along x and `gy` along y.
Eigen::Vector3d normal_of(double gx, double gy) { return Eigen::Vector3d(-gx, -gy, 1.0).normalized(); }

struct Nodes {
  std::vector<Eigen::Vector3d> positions, normals;
  void add(double x, double y, double z, const Eigen::Vector3d& n) {
    positions.emplace_back(x, y, z);
    normals.push_back(n);
  }
};

/// Node centres of the cells of [x0, x1) x [y0, y1).
template <class F>
void for_cells(double x0, double x1, double y0, double y1, F f) {
  for (double x = x0 + 0.5 * kCell; x < x1; x += kCell)
    for (double y = y0 + 0.5 * kCell; y < y1; y += kCell) f(x, y);
}

}  // namespace

TEST(GroundSlope, ANoisyFloorIsLevel) {
  // Each node's normal tilts by up to 0.08 (the 99th percentile measured on a simulated
  // storey), in a random direction: more than max_floor_slope for many single nodes; heights
  // off by up to 3 cm.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> tilt(-0.08, 0.08), height(-0.03, 0.03);
  Nodes nodes;
  int steep_nodes = 0;
  for_cells(0.0, 8.0, 0.0, 6.0, [&](double x, double y) {
    const double gx = tilt(rng), gy = tilt(rng);
    if (std::hypot(gx, gy) > kMaxFloorSlope) ++steep_nodes;
    nodes.add(x, y, height(rng), normal_of(gx, gy));
  });
  ASSERT_GT(steep_nodes, 100);
  const std::vector<double> slopes = ground_slopes(nodes.positions, nodes.normals, kCell, kRadius);
  ASSERT_EQ(slopes.size(), nodes.positions.size());
  for (std::size_t i = 0; i < slopes.size(); ++i) EXPECT_LE(slopes[i], kMaxFloorSlope) << "node " << i;
}

TEST(GroundSlope, AFloorWhoseNormalsAllTiltOneWayIsLevel) {
  // A sparse sensor's ring of nodes: each normal fitted to an arc, all tilted 0.1 outwards
  // along x, while the heights are those of a level floor.
  Nodes nodes;
  for_cells(0.0, 6.0, 0.0, 6.0, [&](double x, double y) { nodes.add(x, y, 0.0, normal_of(0.1, 0.0)); });
  for (double s : ground_slopes(nodes.positions, nodes.normals, kCell, kRadius)) EXPECT_LE(s, kMaxFloorSlope);
}

TEST(GroundSlope, AStepIsNoRamp) {
  // Level on either side of a 0.2 m step (within the room layer's level_band).
  Nodes nodes;
  for_cells(0.0, 6.0, 0.0, 4.0,
            [&](double x, double y) { nodes.add(x, y, x < 3.0 ? 0.0 : 0.2, normal_of(0.0, 0.0)); });
  for (double s : ground_slopes(nodes.positions, nodes.normals, kCell, kRadius)) EXPECT_LE(s, kMaxFloorSlope);
}

TEST(GroundSlope, ARampReadsSteepAwayFromItsFoot) {
  // Floor for x < 4, a ramp rising along x from x = 4 to 10.
  Nodes nodes;
  for_cells(0.0, 10.0, 0.0, 2.0, [&](double x, double y) {
    const bool ramp = x >= 4.0;
    nodes.add(x, y, ramp ? kRampSlope * (x - 4.0) : 0.0, normal_of(ramp ? kRampSlope : 0.0, 0.0));
  });
  const std::vector<double> slopes = ground_slopes(nodes.positions, nodes.normals, kCell, kRadius);
  for (std::size_t i = 0; i < slopes.size(); ++i) {
    const double x = nodes.positions[i].x();
    if (x < 4.0 - kRadius) {
      EXPECT_NEAR(slopes[i], 0.0, 1e-9) << "floor node at x " << x;
    } else if (x > 4.0 + kRadius) {
      EXPECT_NEAR(slopes[i], kRampSlope, 1e-9) << "ramp node at x " << x;
    } else if (x > 4.0) {
      EXPECT_GT(slopes[i], 0.0) << "near the foot the window holds both; at x " << x;
    }
  }
}

TEST(GroundSlope, OneTiltedNodeDoesNotTiltTheFloorRoundIt) {
  // A node at the ground segmentation's steepest (normal z 0.94: a slope of 0.36), alone in a
  // level floor (a step's edge, a cable).
  Nodes nodes;
  for_cells(0.0, 4.0, 0.0, 4.0, [&](double x, double y) {
    const bool tilted = std::abs(x - 2.125) < 1e-9 && std::abs(y - 2.125) < 1e-9;
    nodes.add(x, y, 0.0, normal_of(tilted ? 0.36 : 0.0, 0.0));
  });
  const std::vector<double> slopes = ground_slopes(nodes.positions, nodes.normals, kCell, kRadius);
  for (double s : slopes) EXPECT_LE(s, kMaxFloorSlope);
}

TEST(GroundSlope, BadArgumentsAreRefusedAndBadNodesCountForNothing) {
  Nodes nodes;
  nodes.add(0.0, 0.0, 0.0, normal_of(0.0, 0.0));
  EXPECT_THROW(ground_slopes(nodes.positions, nodes.normals, 0.0, kRadius), std::invalid_argument);
  EXPECT_THROW(ground_slopes(nodes.positions, nodes.normals, kCell, -1.0), std::invalid_argument);
  EXPECT_THROW(ground_slopes(nodes.positions, nodes.normals, std::nan(""), kRadius), std::invalid_argument);
  EXPECT_THROW(ground_slopes(nodes.positions, {}, kCell, kRadius), std::invalid_argument);
  EXPECT_TRUE(ground_slopes({}, {}, kCell, kRadius).empty());
  // A horizontal normal and a NaN position beside a level node: the level node stays level.
  nodes.add(0.1, 0.0, 0.0, Eigen::Vector3d::UnitX());
  nodes.add(std::nan(""), 0.0, 0.0, normal_of(1.0, 0.0));
  const std::vector<double> slopes = ground_slopes(nodes.positions, nodes.normals, kCell, kRadius);
  ASSERT_EQ(slopes.size(), 3u);
  EXPECT_EQ(slopes[0], 0.0);
  EXPECT_EQ(slopes[2], 0.0);
}
