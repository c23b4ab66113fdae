#pragma once
/// Wall-mapping figures (docs/metrics.md, "Against ground truth"): for every ground-truth wall
/// face the sensor saw, the distance and angle error of the mapped plane associated with it,
/// and the duplicate planes left for one face.
#include <Eigen/Core>
#include <vector>

#include "tsgraphs/core/plane.hpp"
#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::eval {

/// A face of a scene wall: one side of it between the walls that meet it there (a vertical
/// rectangle in the world frame).
struct WallFaceTruth {
  int wall = -1;          ///< index into Scene::walls
  int side = 0;           ///< +1 or -1: which side of the centre line
  Plane plane;            ///< normal pointing away from the wall, into the room
  Eigen::Vector2d a, b;   ///< ends of the face's bottom edge (x, y)
  double z0 = 0, z1 = 0;  ///< world heights of its bottom and top
};

/// The faces of every wall of the scene: each side, split where another wall ends on it
/// (openings are not splits: across a door the face is one plane).
std::vector<WallFaceTruth> wall_faces(const scene::Scene& scene);

/// A mapped vertical plane as scene_graph.json gives it.
struct MappedWall {
  int id = -1;
  Plane plane;            ///< map frame
  Eigen::Vector2d a, b;   ///< ends of its points' extent along the plane (x, y)
  double z0 = 0, z1 = 0;  ///< height range of its points
};

struct WallMetricsConfig {
  double max_range = 10.0;             ///< a face counts as seen from points at most this far (m)
  double attribution_distance = 0.05;  ///< a wall point belongs to a face within this (m)
  int min_points = 100;                ///< points needed for a face to count as seen
  double match_angle_deg = 10.0;       ///< mapped planes within this angle...
  double match_distance = 0.3;         ///< ...and offset (m) are candidates for a face
  double min_overlap = 0.5;            ///< ...overlapping the face by this much along it and in height (m)
};

/// The points seen on one face.
struct FaceHits {
  int count = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();  ///< of their world positions
};

/// Adds, per face, the wall-labelled points of a scan (sensor frame, `T_world_sensor`) within
/// max_range that lie on it. `hits` is resized to one entry per face and accumulated.
void count_face_hits(const std::vector<WallFaceTruth>& faces, const PointCloud& scan,
                     const Pose3& T_world_sensor, const WallMetricsConfig& config,
                     std::vector<FaceHits>* hits);

struct WallErrors {
  int n_faces_seen = 0;
  int n_faces_mapped = 0;                      ///< seen faces with an associated mapped plane
  double mean_dist_err = 0, max_dist_err = 0;  ///< m
  double mean_angle_err_deg = 0, max_angle_err_deg = 0;
  int n_duplicates = 0;  ///< extra mapped planes overlapping the same stretch of a face
};

/// Errors of the mapped planes (map frame; `T_world_map` takes them to the world) against
/// the faces with at least min_points hits. The distance error of a face is measured at the
/// centre of its seen part.
WallErrors wall_errors(const std::vector<WallFaceTruth>& faces, const std::vector<FaceHits>& hits,
                       const std::vector<MappedWall>& mapped, const Pose3& T_world_map,
                       const WallMetricsConfig& config);

}  // namespace tsgraphs::eval
