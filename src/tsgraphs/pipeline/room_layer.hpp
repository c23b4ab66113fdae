#pragma once
/// The room layer of the pipeline (DESIGN.md steps 6-7, TS-graphs mode): at every keyframe the
/// free space on the traversable nodes near the robot, the aisle it is in, and the flush rule;
/// when the rule fires, the free space accumulated since the last flush is extracted as a room
/// or corridor segment from the mapped walls around it and associated with the room map.
#include <Eigen/Core>
#include <map>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/freespace/traversable_free_space.hpp"
#include "tsgraphs/ground/traversable_node_map.hpp"
#include "tsgraphs/rooms/room_association.hpp"
#include "tsgraphs/rooms/room_extraction.hpp"
#include "tsgraphs/rooms/room_flush_trigger.hpp"

namespace tsgraphs::pipeline {

struct RoomLayerConfig {
  double free_space_radius = 8.0;  ///< traversable nodes within this of the robot make the free-space graph (m)
  int obstacle_keyframes = 5;      ///< obstacle points come from the clouds of this many latest keyframes
  double level_tolerance = 1.5;    ///< floors within this height of a known level belong to it (m)
  double obstacle_voxel = 0.2;     ///< obstacle candidate points are thinned to this (m)
  double segment_radius = 2.5;     ///< only the cluster's vertices this near the robot join the segment (m):
                                   ///< the aisle it walks, not everything in view

  template <class V>
  void visit(V& v) {
    v("free_space_radius", free_space_radius);
    v("obstacle_keyframes", obstacle_keyframes);
    v("level_tolerance", level_tolerance);
    v("obstacle_voxel", obstacle_voxel);
    v("segment_radius", segment_radius);
  }
};

/// One room extraction (a line of rooms_events.jsonl, lap added by the writer).
struct RoomEventRecord {
  double stamp = 0.0;
  int keyframe = -1;
  int room_id = -1;
  bool is_new = false;
  int level = 0;
  rooms::RoomKind kind = rooms::RoomKind::room;
  OrientedRect rect;
  std::vector<int> walls;
};

/// What the layer needs of the rest of the map at a keyframe.
struct RoomLayerInput {
  double stamp = 0.0;
  int keyframe = -1;
  Pose3 pose = Pose3::Identity();          ///< the keyframe's current estimate (sensor)
  double sensor_height = 0.0;              ///< the sensor above the floor (m)
  const ground::TraversableNodeMap* nodes = nullptr;
  std::vector<Eigen::Vector3d> obstacle_candidates;  ///< map-frame points of the latest keyframes
  std::vector<rooms::WallCandidate> walls;           ///< mapped vertical planes with their extents
};

class RoomLayer {
 public:
  RoomLayer(RoomLayerConfig config, freespace::TraversableFreeSpaceConfig free_space,
            rooms::AisleMeasureConfig aisle, rooms::RoomFlushConfig flush, rooms::RoomExtractionConfig extraction,
            rooms::RoomAssociationConfig association);

  /// Processes one keyframe; returns the room events it produced (0 or 1).
  std::vector<RoomEventRecord> update(const RoomLayerInput& input);
  /// Extracts what is accumulated at the end of the run.
  std::vector<RoomEventRecord> finish(const RoomLayerInput& input);

  const rooms::RoomMap& room_map() const { return map_; }
  /// Size of the robot's free-space cluster at the last keyframe (vertices).
  std::size_t last_cluster_size() const { return last_cluster_size_; }
  /// Floor height (map frame) of each level index, in order of first visit.
  const std::vector<double>& levels() const { return levels_; }

 private:
  std::vector<RoomEventRecord> flush(const RoomLayerInput& input, int level);
  int level_of(double floor_z);

  RoomLayerConfig config_;
  freespace::TraversableFreeSpaceConfig free_space_;
  rooms::AisleMeasureConfig aisle_;
  rooms::RoomFlushTrigger trigger_;
  rooms::RoomExtractionConfig extraction_;
  rooms::RoomMap map_;
  std::map<int, Eigen::Vector3d> segment_;  ///< node id -> position: the free space since the last flush
  std::vector<double> levels_;              ///< floor heights of the levels seen
  int segment_level_ = -1;
  bool was_in_free_space_ = true;
  std::size_t last_cluster_size_ = 0;
};

}  // namespace tsgraphs::pipeline
