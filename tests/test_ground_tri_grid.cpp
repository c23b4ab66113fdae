// The tri-grid field on constructed input: indexing and adjacency of the grid, the level
// frame, and the node planes: a flat floor, a floor with low outliers, a floor with a wall
// standing in the node, a wall alone, and one scan line with and without a face above it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/ground/tri_grid_ground.hpp"

using namespace tsgraphs;
using namespace tsgraphs::ground;

namespace {

constexpr double kSensorHeight = 0.55;  // the floor is at z = -0.55 in the level frame (m)
constexpr double kSpacing = 0.03;       // of the constructed points (m)

// Floor points on a square grid over [x0, x1] x [y0, y1] at height z.
void add_floor(PointCloud* cloud, double x0, double x1, double y0, double y1, double z) {
  for (double x = x0; x <= x1; x += kSpacing)
    for (double y = y0; y <= y1; y += kSpacing) cloud->points.emplace_back(x, y, z);
}

// A vertical face along x = x_face, for y in [y0, y1] and z in [z0, z1].
void add_face(PointCloud* cloud, double x_face, double y0, double y1, double z0, double z1) {
  for (double y = y0; y <= y1; y += kSpacing)
    for (double z = z0; z <= z1; z += kSpacing) cloud->points.emplace_back(x_face, y, z);
}

const TriGridNode& node_at(const TriGridField& field, double x, double y) {
  return field.nodes[field.grid.node_at(x, y)];
}

TEST(TriGrid, EveryCentroidFallsInItsOwnNode) {
  const TriGrid grid(0.5, 15.0);
  EXPECT_EQ(grid.cells_per_side(), 60);
  for (int n = 0; n < grid.num_nodes(); ++n) {
    const Eigen::Vector2d c = grid.centroid(n);
    ASSERT_EQ(grid.node_at(c.x(), c.y()), n);
  }
  EXPECT_EQ(grid.node_at(15.5, 0.0), -1);
  EXPECT_EQ(grid.node_at(0.0, -15.5), -1);
}

TEST(TriGrid, AdjacencyIsSymmetricAndJoinsNeighbouringTriangles) {
  const TriGrid grid(0.5, 3.0);
  const double side_to_side = 0.5 / 3.0;                // centroids across a cell side
  const double same_cell = 0.5 / 3.0 * std::sqrt(2.0);  // centroids across a diagonal
  std::array<int, 3> adj{}, back{};
  for (int n = 0; n < grid.num_nodes(); ++n) {
    const int count = grid.adjacent(n, &adj);
    ASSERT_GE(count, 2);
    for (int k = 0; k < count; ++k) {
      const int m = adj[k];
      const double d = (grid.centroid(m) - grid.centroid(n)).norm();
      EXPECT_TRUE(std::abs(d - side_to_side) < 1e-9 || std::abs(d - same_cell) < 1e-9)
          << n << " " << m << " " << d;
      const int back_count = grid.adjacent(m, &back);
      EXPECT_NE(std::find(back.begin(), back.begin() + back_count, n), back.begin() + back_count);
    }
  }
}

TEST(TriGrid, LevelRotationKeepsRollAndPitchAndDropsYaw) {
  const Eigen::Matrix3d tilt =
      (Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(-0.05, Eigen::Vector3d::UnitY()))
          .toRotationMatrix();
  const Eigen::Matrix3d R_map_sensor =
      Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix() * tilt;
  const Eigen::Matrix3d R = level_rotation(R_map_sensor);
  // Gravity is the same in the level frame and the map frame...
  EXPECT_LT(((R * R_map_sensor.transpose()) * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(),
            1e-12);
  // ...and the sensor's heading is the level frame's x.
  const Eigen::Vector3d heading = R.col(0);
  EXPECT_NEAR(std::atan2(heading.y(), heading.x()), 0.0, 1e-12);
}

TEST(TriGridField, FlatFloorNodesAreGroundLikeAtTheFloorHeight) {
  PointCloud cloud;
  add_floor(&cloud, -4.0, 4.0, -4.0, 4.0, -kSensorHeight);
  const GroundConfig config;
  const TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  int modelled = 0;
  for (const TriGridNode& node : field.nodes) {
    if (node.state != NodeState::kModelled) continue;
    ++modelled;
    EXPECT_TRUE(node.ground_like);
    EXPECT_FALSE(node.face_foot);
    EXPECT_NEAR(node.centre.z(), -kSensorHeight, 1e-4);
    EXPECT_GT(node.normal.z(), 0.9999);
  }
  EXPECT_GT(modelled,
            16 * 16 * 4 - 40);  // every triangle of the 8 m x 8 m floor but the one under the sensor
}

TEST(TriGridField, PointsFarBelowTheLowestLevelDoNotMoveThePlane) {
  PointCloud cloud;
  add_floor(&cloud, 2.0, 2.5, 2.0, 2.5, -kSensorHeight);
  const Eigen::Vector3f centre(2.4f, 2.25f, 0.0f);  // in the cell's +x triangle
  for (int k = 0; k < 3; ++k)
    cloud.points.emplace_back(centre.x() + 0.02f * k, centre.y(), -kSensorHeight - 1.0f);
  const GroundConfig config;
  const TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  const TriGridNode& node = node_at(field, centre.x(), centre.y());
  ASSERT_EQ(node.state, NodeState::kModelled);
  EXPECT_NEAR(node.lowest, -kSensorHeight, 1e-4);
  EXPECT_NEAR(node.centre.z(), -kSensorHeight, 1e-3);
  EXPECT_GT(node.normal.z(), 0.999);
}

TEST(TriGridField, AWallStandingInTheNodeLeavesTheFloorPlane) {
  PointCloud cloud;
  add_floor(&cloud, 2.0, 2.3, 0.0, 0.5, -kSensorHeight);
  // A dense wall face across the cell, 1 m high: many more points than the floor strip.
  for (double y = 0.0; y <= 0.5; y += 0.005)
    for (double z = -kSensorHeight; z <= 0.45; z += 0.005) cloud.points.emplace_back(2.3, y, z);
  const GroundConfig config;
  const TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  const TriGridNode& node = node_at(field, 2.1, 0.25);  // the cell's -x triangle: floor and the wall's edge
  ASSERT_EQ(node.state, NodeState::kModelled);
  EXPECT_TRUE(node.ground_like);
  EXPECT_GT(node.normal.z(), 0.99);
  EXPECT_NEAR(node.centre.z(), -kSensorHeight, 0.01);
}

TEST(TriGridField, AWallAloneIsAtMostTheFootOfAFace) {
  PointCloud cloud;
  add_face(&cloud, 3.1, -0.25, 0.25, -0.3, 0.5);  // its foot hidden: it starts above the floor
  const GroundConfig config;
  const TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  const TriGridNode& node = node_at(field, 3.1, 0.0);
  ASSERT_EQ(node.state, NodeState::kModelled);
  // Only its lowest points are fitted: a line, whose plane is the prior's level one, flagged
  // as a face's foot (the search never reaches it across empty nodes).
  EXPECT_TRUE(!node.ground_like || node.face_foot);
  EXPECT_NEAR(node.lowest, -0.3, 1e-4);
}

TEST(TriGridField, OneScanLineIsLevelGroundUnlessAFaceStandsOnIt) {
  GroundConfig config;
  // One ring across a far triangle: a line of points, nothing across it.
  PointCloud ring;
  for (int k = 0; k < 12; ++k) ring.points.emplace_back(10.27f + 0.018f * k, 5.25f, -kSensorHeight);
  const TriGridField a = build_tri_grid_field(ring, Eigen::Matrix3d::Identity(), config);
  const TriGridNode& line = node_at(a, 10.35, 5.25);
  ASSERT_EQ(line.state, NodeState::kModelled);
  EXPECT_TRUE(line.ground_like);
  EXPECT_FALSE(line.face_foot);
  EXPECT_GT(line.normal.z(), 0.999);

  // The same line at the foot of a face rising from it.
  PointCloud foot = ring;
  for (int k = 0; k < 12; ++k)
    for (int h = 1; h <= 8; ++h)
      foot.points.emplace_back(10.27f + 0.018f * k, 5.25f, -kSensorHeight + 0.05f * h);
  const TriGridField b = build_tri_grid_field(foot, Eigen::Matrix3d::Identity(), config);
  const TriGridNode& face = node_at(b, 10.35, 5.25);
  ASSERT_EQ(face.state, NodeState::kModelled);
  EXPECT_TRUE(face.face_foot);
}

TEST(TriGridField, FewPointsMakeAnUnknownNodeAndOutOfRangePointsNoNode) {
  PointCloud cloud;
  for (int k = 0; k < 4; ++k) cloud.points.emplace_back(3.1f + 0.02f * k, 0.0f, -kSensorHeight);
  cloud.points.emplace_back(0.2f, 0.0f, -kSensorHeight);   // nearer than min_range
  cloud.points.emplace_back(16.0f, 0.0f, -kSensorHeight);  // farther than max_range
  cloud.points.emplace_back(std::nanf(""), 0.0f, 0.0f);
  const GroundConfig config;
  const TriGridField field = build_tri_grid_field(cloud, Eigen::Matrix3d::Identity(), config);
  EXPECT_EQ(node_at(field, 3.1, 0.0).state, NodeState::kUnknown);
  EXPECT_EQ(node_at(field, 3.1, 0.0).num_points, 4);
  EXPECT_EQ(field.point_node[4], -1);
  EXPECT_EQ(field.point_node[5], -1);
  EXPECT_EQ(field.point_node[6], -1);
}

}  // namespace
