#pragma once
/// Turns a scene into the labelled triangles the LiDAR sees: slabs with their voids cut
/// out, ceilings, walls with openings, railings, boxes, ramps and voxel-map cubes.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/sim/scene.hpp"

namespace tsgraphs::sim {

struct LabelledMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;   ///< vertex indices
  std::vector<std::uint32_t> labels;        ///< PointLabel of each triangle

  /// Adds a triangle; `label` is a PointLabel.
  void add_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, PointLabel label);
  /// Adds a solid box with centre (x, y), z range, half sizes along its axes and yaw.
  void add_box(const Eigen::Vector2d& center, const Eigen::Vector2d& half_size, double yaw, double z0, double z1,
               PointLabel label);
};

/// All surfaces of the scene in the world frame. Reads voxel-map PCD files.
LabelledMesh build_scene_mesh(const Scene& scene);

/// The solid pieces of a wall once its openings are cut out: boxes along the wall given by
/// [s0, s1] along its centre line and [z0, z1] above its level.
struct WallPiece {
  double s0, s1, z0, z1;
};
std::vector<WallPiece> wall_pieces(const Wall& wall);

/// Region of the ceiling of `level`: its slab minus its voids and the next level up's voids.
std::vector<Polygon2> ceiling_holes(const Scene& scene, int level);

}  // namespace tsgraphs::sim
