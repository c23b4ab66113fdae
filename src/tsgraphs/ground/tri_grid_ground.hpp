#pragma once
/// The tri-grid field (TRAVEL, url-kaist/TRAVEL): square cells of `resolution` around the
/// sensor in the level frame, each split by its diagonals into 4 triangles, the nodes. Per
/// node: outlier rejection, lowest-point representative, seeds and a few PCA rounds give a
/// plane; the node is ground-like when the plane is flat enough.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/ground/ground_segmentation.hpp"

namespace tsgraphs::ground {

/// Indexing and geometry of the tri-grid. Node index = (row * cells_per_side + column) * 4 +
/// triangle; rows run along x, columns along y; the sensor is at the origin.
class TriGrid {
 public:
  /// The triangles of a cell, named by the cell side they stand on.
  enum Triangle : int { kPlusX = 0, kPlusY = 1, kMinusX = 2, kMinusY = 3 };

  /// Cells of `resolution` covering [-half_extent, half_extent] in x and y.
  TriGrid(double resolution, double half_extent);

  double resolution() const { return resolution_; }
  int cells_per_side() const { return cells_; }
  int num_nodes() const { return cells_ * cells_ * 4; }
  int row(int node) const { return node / 4 / cells_; }
  int column(int node) const { return node / 4 % cells_; }
  static int triangle(int node) { return node % 4; }
  /// The node of cell (row, column), or -1 off the grid.
  int node(int row, int column, int triangle) const;

  /// The node holding (x, y), or -1 off the grid.
  int node_at(double x, double y) const;
  /// The low (x, y) corner of the node's cell.
  Eigen::Vector2d cell_corner(int node) const;
  /// Centroid of the node's triangle.
  Eigen::Vector2d centroid(int node) const;
  /// The nodes sharing an edge with `node` (the two others of its cell that touch it, and the
  /// one across the cell side); returns how many (2 on the grid's border, else 3).
  int adjacent(int node, std::array<int, 3>* out) const;

 private:
  double resolution_;
  double origin_;  ///< x (and y) of the grid's low corner
  int cells_;
};

enum class NodeState : std::uint8_t {
  kEmpty,     ///< no points
  kUnknown,   ///< fewer than num_min_pts points: no plane
  kModelled,  ///< a plane was fitted
};

/// One node's points and plane, in the level frame.
struct TriGridNode {
  NodeState state = NodeState::kEmpty;
  bool ground_like = false;  ///< modelled with normal z >= th_normal
  /// Ground-like only on one line (the plane's tilt is the prior's) with a steep face standing
  /// on it: the foot of a wall, or of a void's edge seen from above.
  bool face_foot = false;
  int num_points = 0;
  int num_inliers = 0;  ///< column-lowest points within th_dist of the plane
  float lowest = 0.0f;  ///< the robust lowest level (z) of the points
  /// Centroid (x, y) of the triangle; z: the plane's height there (modelled nodes) or the
  /// robust lowest level (unknown nodes).
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< plane normal, z >= 0

  /// Height of the plane through `centre` with `normal` at (x, y).
  float height_at(float x, float y) const;
  /// Signed distance of p from that plane (positive above).
  float distance(const Eigen::Vector3f& p) const { return normal.dot(p - centre); }
};

/// Every point of a scan binned into the tri-grid, and the node models.
struct TriGridField {
  TriGrid grid{1.0, 1.0};
  std::vector<Eigen::Vector3f> points;  ///< every input point in the level frame (non-finite ones kept)
  std::vector<int> point_node;          ///< node of each point; -1 when out of range or not finite
  std::vector<int> node_begin;          ///< node i's points: node_points[node_begin[i], node_begin[i + 1])
  std::vector<int> node_points;         ///< point indices grouped by node
  std::vector<TriGridNode> nodes;       ///< one per grid node
};

/// Rotation from the sensor frame to the level frame: roll and pitch of R_map_sensor, no yaw
/// (the level frame's x is the sensor's heading).
Eigen::Matrix3d level_rotation(const Eigen::Matrix3d& R_map_sensor);

/// Bins `cloud` (sensor frame) into the tri-grid and models every node. Points whose
/// horizontal range is outside [min_range, max_range] or that are not finite get no node.
TriGridField build_tri_grid_field(const PointCloud& cloud, const Eigen::Matrix3d& R_level_sensor,
                                  const GroundConfig& config);
/// The same into `field`, reusing its buffers (a scan after another allocates nothing new).
void build_tri_grid_field(const PointCloud& cloud, const Eigen::Matrix3d& R_level_sensor,
                          const GroundConfig& config, TriGridField* field);

}  // namespace tsgraphs::ground
