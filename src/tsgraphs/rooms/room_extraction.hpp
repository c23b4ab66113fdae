#pragma once
/// Room extraction from the free space the robot walked and the wall planes near it: a room
/// (two facing planes on each of two roughly perpendicular axes) or a corridor segment (one
/// pair of facing planes, or one wall whose open side is bounded by the free space, e.g. a
/// railing; its open direction bounded by the free space or by end walls). The footprint is an
/// oriented rectangle bounded by wall planes where walls bound the free space and by the free
/// space's robust extent where they do not (a railing, an open end).
///
/// Two point sets come in: the *segment*, the free space near the path walked since the last
/// flush, which finds the walls (not crossed by it, reached by it); and the *context*, the
/// whole free-space clusters the robot was in meanwhile, which carries a corridor's extent
/// along its axis beyond what was walked, up to end walls, a gap, or (on an open side) the
/// place where the aisle opens into a crossing aisle.
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
  double height = 3.0;        ///< vertical extent of the plane's points (m)
};

struct ExtractedRoom {
  RoomKind kind = RoomKind::room;
  OrientedRect rect;          ///< footprint, map x-y; rect x axis is the first pair's normal axis
  /// Planes of the room factor: room: first pair then second pair (each pair: the plane
  /// whose normal is along the rect's +axis first); corridor: the one pair.
  std::vector<int> wall_ids;
  /// Corridor only: single planes that bound the open direction at one end (0 or 1 per end).
  std::vector<int> end_wall_ids;
  /// Corridor only: one wall along it, the other side bounded by the free space (a railing);
  /// wall_ids then holds that one wall and no room-planes factor can be made from it.
  bool one_sided = false;
};

struct RoomExtractionConfig {
  int min_cluster_points = 10;           ///< smaller clusters give nothing
  double max_normal_z = 0.2;             ///< |n.z| above this: not a vertical plane, ignored
  double min_wall_height = 1.5;          ///< lower planes are furniture (desks, cabinets), not walls; a bookshelf is one (m)
  double crossing_tolerance = 0.15;      ///< a cluster point this far behind a plane crosses it (m)
  double max_crossing_ratio = 0.5;       ///< a plane crossed by more than this share of the cluster does not bound it...
  double max_passage_ratio = 0.3;        ///< ...nor one the cluster crosses over more than this share of its width
                                         ///< (a wall is crossed through doors only)
  double max_wall_clearance = 1.0;       ///< the cluster must reach within this of a plane that bounds it (m);
                                         ///< a wall across a void beyond a railing does not
  double min_segment_overlap_ratio = 0.3;///< segment/cluster overlap along the wall, share of the shorter of the two
  double parallel_tolerance_deg = 10.0;  ///< facing planes: normals anti-parallel within this
  double perpendicular_tolerance_deg = 15.0; ///< room axes: perpendicular within this
  double min_wall_gap = 0.5;             ///< facing planes closer than this are not a room or aisle (m)
  double extent_percentile = 0.01;       ///< cluster extent: this share of points trimmed at each end
  double band_tolerance = 0.3;           ///< context points this far outside a corridor's sides still extend it (m)
  double band_bin = 0.25;                ///< corridor extension: context binned along the axis at this step (m)
  double band_max_gap = 0.5;             ///< ...and the extension stops at an empty stretch longer than this (m)
  double min_band_fill = 0.5;            ///< ...where a bin's points span less than this share of the width, it counts as empty (a door)
  double open_side_margin = 0.6;         ///< ...or where context lies this far beyond an open side: a crossing aisle (m)
  double open_side_offset = 0.4;         ///< a free-space edge at an obstacle lies this short of it (the free space's lambda_th, m)
  double max_open_width = 4.0;           ///< one-wall corridor: wall to free-space edge at most this (m), else a hall
  double min_open_aspect = 2.0;          ///< one-wall corridor: length at least this times its width

  template <class V>
  void visit(V& v) {
    v("min_cluster_points", min_cluster_points);
    v("max_normal_z", max_normal_z);
    v("min_wall_height", min_wall_height);
    v("crossing_tolerance", crossing_tolerance);
    v("max_crossing_ratio", max_crossing_ratio);
    v("max_passage_ratio", max_passage_ratio);
    v("max_wall_clearance", max_wall_clearance);
    v("min_segment_overlap_ratio", min_segment_overlap_ratio);
    v("parallel_tolerance_deg", parallel_tolerance_deg);
    v("perpendicular_tolerance_deg", perpendicular_tolerance_deg);
    v("min_wall_gap", min_wall_gap);
    v("extent_percentile", extent_percentile);
    v("band_tolerance", band_tolerance);
    v("band_bin", band_bin);
    v("band_max_gap", band_max_gap);
    v("min_band_fill", min_band_fill);
    v("open_side_margin", open_side_margin);
    v("open_side_offset", open_side_offset);
    v("max_open_width", max_open_width);
    v("min_open_aspect", min_open_aspect);
  }
};

/// The room or corridor segment the `segment` (map-frame points, e.g. traversable node centres)
/// lies in, or std::nullopt when no wall bounds it as a room or corridor. Per direction the
/// plane chosen is the nearest one to the segment's centre among those that face the centre,
/// are not crossed by the segment, are reached by it (within max_wall_clearance) and whose
/// extent overlaps the segment's along it. `context` (may be empty: the segment alone) extends
/// a corridor along its axis as the file comment says.
std::optional<ExtractedRoom> extract_room(const std::vector<Eigen::Vector3d>& segment,
                                          const std::vector<Eigen::Vector3d>& context,
                                          const std::vector<WallCandidate>& walls,
                                          const RoomExtractionConfig& config = {});

}  // namespace tsgraphs::rooms
