#pragma once
/// Room extraction from the robot's free-space cluster and the wall planes near it: a room
/// (two facing planes on each of two roughly perpendicular axes) or a corridor segment (one
/// pair of facing planes; its open direction bounded by the cluster). The footprint is an
/// oriented rectangle bounded by wall planes where walls bound the cluster and by the
/// cluster's robust extent where they do not (a railing, an open end).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tsgraphs/core/plane.hpp"
#include "tsgraphs/core/rect.hpp"

namespace tsgraphs::rooms {

enum class RoomKind { room, corridor };

/// "room" or "corridor".
std::string to_string(RoomKind kind);

/// A mapped vertical wall plane near the cluster.
struct WallCandidate {
  int id = -1;
  Plane plane;   ///< map frame; normal towards the observers, i.e. into the room (S-Graphs sign)
  Vec2 end_a = Vec2::Zero();  ///< horizontal segment ends of the plane's points, map x-y
  Vec2 end_b = Vec2::Zero();
};

struct ExtractedRoom {
  RoomKind kind = RoomKind::room;
  OrientedRect rect;          ///< footprint, map x-y; rect x axis is the first pair's normal axis
  /// Planes of the room factor: room: first pair then second pair (each pair: the plane
  /// whose normal is along the rect's +axis first); corridor: the one pair.
  std::vector<int> wall_ids;
  /// Corridor only: single planes that bound the open direction at one end (0 or 1 per end).
  std::vector<int> end_wall_ids;
};

struct RoomExtractionConfig {
  int min_cluster_points = 10;           ///< smaller clusters give nothing
  double max_normal_z = 0.2;             ///< |n.z| above this: not a vertical plane, ignored
  double crossing_tolerance = 0.15;      ///< a cluster point this far behind a plane crosses it (m)
  double max_crossing_ratio = 0.01;      ///< a plane crossed by more than this share of the cluster does not bound it
  double max_wall_clearance = 1.0;       ///< the cluster must reach within this of a plane that bounds it (m);
                                         ///< a wall across a void beyond a railing does not
  double min_segment_overlap_ratio = 0.3;///< segment/cluster overlap along the wall, share of the shorter of the two
  double parallel_tolerance_deg = 10.0;  ///< facing planes: normals anti-parallel within this
  double perpendicular_tolerance_deg = 15.0; ///< room axes: perpendicular within this
  double min_wall_gap = 0.5;             ///< facing planes closer than this are not a room or aisle (m)
  double extent_percentile = 0.01;       ///< cluster extent: this share of points trimmed at each end

  template <class V>
  void visit(V& v) {
    v("min_cluster_points", min_cluster_points);
    v("max_normal_z", max_normal_z);
    v("crossing_tolerance", crossing_tolerance);
    v("max_crossing_ratio", max_crossing_ratio);
    v("max_wall_clearance", max_wall_clearance);
    v("min_segment_overlap_ratio", min_segment_overlap_ratio);
    v("parallel_tolerance_deg", parallel_tolerance_deg);
    v("perpendicular_tolerance_deg", perpendicular_tolerance_deg);
    v("min_wall_gap", min_wall_gap);
    v("extent_percentile", extent_percentile);
  }
};

/// The room or corridor segment the cluster (map-frame points, e.g. traversable node centres)
/// lies in, or std::nullopt when no pair of facing planes bounds it. Per direction the plane
/// chosen is the nearest one to the cluster's centre among those that face the centre, are
/// not crossed by the cluster, are reached by it (within max_wall_clearance) and whose segment
/// overlaps the cluster's extent along it.
std::optional<ExtractedRoom> extract_room(const std::vector<Eigen::Vector3d>& cluster,
                                          const std::vector<WallCandidate>& walls,
                                          const RoomExtractionConfig& config = {});

}  // namespace tsgraphs::rooms
