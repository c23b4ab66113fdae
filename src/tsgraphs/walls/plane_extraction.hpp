#pragma once
/// Wall (vertical) and floor/ceiling (horizontal) planes from one keyframe cloud: point normals
/// (PCA over k neighbours), a class per point from its normal in the map frame, region growing
/// per class for plane hypotheses, an inlier sweep and least-squares refit per hypothesis, then
/// Euclidean clustering of the inliers so that one plane is one wall face (two walls in line
/// across a doorway are two faces only if the gap is wider than cluster_tolerance).
#include <vector>

#include "tsgraphs/core/plane.hpp"
#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::walls {

struct PlaneExtractionConfig {
  int normal_neighbours = 10;
  double max_vertical_normal_z = 0.15;
  double min_horizontal_normal_z = 0.95;
  double distance_threshold = 0.05;
  double normal_angle_threshold_deg = 15.0;
  int min_inliers = 150;
  double min_extent = 0.5;
  double cluster_tolerance = 0.4;
  int max_planes = 30;
  double max_range = 15.0;
  double point_voxel = 0.2;

  template <class V>
  void visit(V& v) {
    v("normal_neighbours", normal_neighbours, between(3, 100), "k nearest neighbours for point normals");
    v("max_vertical_normal_z", max_vertical_normal_z, between(0.0, 1.0),
      "|n_z| at most this: a wall candidate");
    v("min_horizontal_normal_z", min_horizontal_normal_z, between(0.0, 1.0),
      "|n_z| at least this: a floor or ceiling candidate");
    v("distance_threshold", distance_threshold, above(0.0, 10.0), "m; RANSAC inlier distance");
    v("normal_angle_threshold_deg", normal_angle_threshold_deg, above(0.0, 90.0),
      "inlier normals within this of the plane's");
    v("min_inliers", min_inliers, between(3, 10000000), "smallest face kept (points after prefiltering)");
    v("min_extent", min_extent, between(0.0, 1000.0),
      "m; shortest horizontal length of a wall face: a stretch of wall between a door and a corner (a "
      "pillar's sides are faces too)");
    v("cluster_tolerance", cluster_tolerance, between(0.0, 100.0),
      "m; a gap this wide splits one plane into two faces");
    v("max_planes", max_planes, between(1, 1000), "at most this many planes per keyframe");
    v("max_range", max_range, above(0.0, 10000.0), "m; farther points are not used for planes");
    v("point_voxel", point_voxel, between(0.01, 100.0), "m; inlier points kept per face are thinned to this");
  }
};

/// One plane seen from one keyframe, in the keyframe (sensor) frame.
struct PlaneObservation {
  /// n.x + d = 0 with the S-Graphs sign convention: n points towards the sensor that saw the
  /// face, so d > 0 in the keyframe frame; the two faces of a wall are two planes.
  Plane plane;
  bool vertical = true;                                ///< wall face; false: floor or ceiling
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< of the inliers, keyframe frame
  int num_inliers = 0;
  double fit_rms = 0.0;                 ///< RMS distance of inliers to the plane (m)
  std::vector<Eigen::Vector3f> points;  ///< inliers downsampled to point_voxel, keyframe frame
};

/// Extracts planes from `cloud` (keyframe frame). `R_map_keyframe` rotates keyframe-frame
/// vectors into the gravity-aligned map frame; it decides which planes are vertical.
/// Deterministic: the same cloud and config give the same planes in the same order.
std::vector<PlaneObservation> extract_planes(const PointCloud& cloud, const Eigen::Matrix3d& R_map_keyframe,
                                             const PlaneExtractionConfig& config);

}  // namespace tsgraphs::walls
