#pragma once
/// The room extraction of the S-Graphs+ baseline (snt-arg/lidar_situational_graphs, its room
/// analyzer), for the side-by-side comparison of docs/DESIGN.md ("Baseline mode").
///
/// S-Graphs+ takes one free-space cluster (ESDF slice cells) and the vertical planes seen by the
/// last keyframe. Each plane is an x-plane or a y-plane by the larger of |n.x|, |n.y| in the map
/// frame, and falls in one of four classes by the sign of that component (x+, x-, y+, y-). Per
/// class the plane with the most cluster points within `point_distance` of its face (the
/// segment of its points, on either side; S-Graphs measures to the plane's nearest point) wins. Two winners
/// of one axis that face each other and are far enough apart make a pair; two pairs make a room, one pair a
/// corridor whose length is the cluster's extent along it.
///
/// Where it differs from TS-graphs' room segmentation: the classes are the map axes, so a room rotated
/// in the map is still split by map x and y and its footprint is an axis-aligned rectangle; and a
/// plane is chosen by how many points lie near it, not by whether the cluster reaches it without
/// crossing it, so a plane the cluster crosses, or a wall across a void behind a railing, can be
/// chosen when enough cluster points lie within `point_distance` of it.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "tsgraphs/rooms/room.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::rooms {

struct SgraphsRoomExtractionConfig {
  double point_distance = 1.5;
  int min_points = 2;
  double min_width = 1.0;
  double min_cluster_extent = 0.5;
  double max_center_offset = 0.5;
  double max_normal_z = 0.2;

  template <class V>
  void visit(V& v) {
    v("point_distance", point_distance, above(0.0, 100.0),
      "a cluster point this close to a plane (either side) counts for it (m; S-Graphs: 1.5)");
    v("min_points", min_points, between(1, 10000000),
      "a class's winning plane needs at least this many points (S-Graphs' vertex_neigh_thres: 2)");
    v("min_width", min_width, between(0.0, 1000.0),
      "a pair's planes closer than this are no room or corridor (m; S-Graphs: 1.0)");
    v("min_cluster_extent", min_cluster_extent, between(0.0, 1000.0),
      "a cluster narrower than this along map x or y gives nothing (m; S-Graphs: 0.5)");
    v("max_center_offset", max_center_offset, above(0.0, 1000.0),
      "the footprint's centre must lie this close to a cluster point (m; S-Graphs: 0.5)");
    v("max_normal_z", max_normal_z, above(0.0, 0.99), "|n.z| above this: not a vertical plane, ignored");
  }
};

/// The room or corridor S-Graphs+ extracts from `cluster` (map-frame free-space points) and the
/// vertical `walls` (normals into the room), or std::nullopt. A room's rect is axis-aligned
/// (yaw 0) and bounded where each plane crosses the other axis' line through the cluster's
/// centroid; wall_ids = {x+, x-, y+, y-}. A corridor's rect has its x axis along the pair's
/// normal axis (yaw 0 for an x pair, pi/2 for a y pair), is bounded across by the pair and along
/// by the cluster's min..max, centred along it at the cluster's centroid; wall_ids = {+, -}.
std::optional<ExtractedRoom> extract_room_sgraphs(const std::vector<Eigen::Vector3d>& cluster,
                                                  const std::vector<WallCandidate>& walls,
                                                  const SgraphsRoomExtractionConfig& config = {});

}  // namespace tsgraphs::rooms
