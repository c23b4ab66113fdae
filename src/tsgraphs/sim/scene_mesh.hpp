#pragma once
/// Turns a scene into the labelled triangles the LiDAR sees: slabs with their voids cut
/// out, ceilings, walls with openings, railings, boxes, ramps and voxel-map cubes.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::sim {

struct LabelledMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;  ///< vertex indices
  std::vector<std::uint32_t> labels;       ///< PointLabel of each triangle
  std::vector<float>
      transmission;  ///< probability that a ray passes through each triangle (glass), 0 for most

  /// Adds a triangle; `label` is a PointLabel.
  void add_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    PointLabel label, float transmission = 0.0f);
  /// Adds a solid box with centre (x, y), z range, half sizes along its axes and yaw.
  void add_box(const Eigen::Vector2d& center, const Eigen::Vector2d& half_size, double yaw, double z0,
               double z1, PointLabel label, float transmission = 0.0f);
};

/// All surfaces of the scene in the world frame. Reads voxel-map PCD files.
LabelledMesh build_scene_mesh(const scene::Scene& scene);

}  // namespace tsgraphs::sim
