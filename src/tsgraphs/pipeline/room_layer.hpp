#pragma once
/// The room layer of the pipeline (DESIGN.md steps 6-7 and the baseline mode): at every keyframe
/// the free space around the robot, and the trigger that says when to extract a room from it.
///
/// - TS-graphs (`free_space_method: traversable`, `room_trigger: flush`): free space on the
///   traversable nodes near the robot; the aisle it is in and the flush rule; when the rule
///   fires, the free space walked since the last flush is extracted as a room or corridor
///   segment from the mapped walls around it (extract_room) and associated with the room map by
///   Dice or centre distance.
/// - S-Graphs+ (`esdf`, `timer`): free space from the ESDF slice of the latest keyframes' points;
///   every period the robot's cluster is extracted with the planes of the last keyframe
///   (extract_room_sgraphs) and associated by centre distance only.
/// - The other two combinations are the ablation: the free space method brings its extraction
///   and association, the trigger says when.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/freespace/esdf_free_space.hpp"
#include "tsgraphs/freespace/traversable_free_space.hpp"
#include "tsgraphs/ground/traversable_node_map.hpp"
#include "tsgraphs/rooms/room_association.hpp"
#include "tsgraphs/rooms/room_extraction.hpp"
#include "tsgraphs/rooms/room_flush_trigger.hpp"
#include "tsgraphs/rooms/room_timer_trigger.hpp"
#include "tsgraphs/rooms/sgraphs_room_extraction.hpp"

namespace tsgraphs::pipeline {

struct RoomLayerConfig {
  std::string free_space_method = "traversable";  ///< "traversable" (TS-graphs) or "esdf" (S-Graphs+)
  std::string room_trigger = "flush";             ///< "flush" (TS-graphs) or "timer" (S-Graphs+)
  double free_space_radius = 8.0;  ///< free space is computed within this of the robot (m)
  int obstacle_keyframes = 5;      ///< obstacle points come from the clouds of this many latest keyframes
  double level_tolerance = 1.5;    ///< floors within this height of a known level belong to it (m)
  double obstacle_voxel = 0.2;     ///< obstacle candidate points are thinned to this (m)
  double segment_radius = 2.5;     ///< flush: only the cluster's vertices this near the robot along the free space join the segment (m):
                                   ///< the aisle it walks, not everything in view
  double context_radius = 20.0;    ///< flush: mapped ground within this of the robot also carries a corridor on (m)
  double min_segment_length = 2.0; ///< flush: a segment walked less than this (a corner, a doorway passed
                                   ///< through) is not extracted but carried into the next one (m)

  template <class V>
  void visit(V& v) {
    v("free_space_method", free_space_method);
    v("room_trigger", room_trigger);
    v("free_space_radius", free_space_radius);
    v("obstacle_keyframes", obstacle_keyframes);
    v("level_tolerance", level_tolerance);
    v("obstacle_voxel", obstacle_voxel);
    v("segment_radius", segment_radius);
    v("context_radius", context_radius);
    v("min_segment_length", min_segment_length);
  }
};

/// Every parameter the room layer uses, one struct per module.
struct RoomLayerSettings {
  RoomLayerConfig layer;
  freespace::TraversableFreeSpaceConfig free_space;
  freespace::EsdfFreeSpaceConfig esdf;
  rooms::AisleMeasureConfig aisle;
  rooms::RoomFlushConfig flush;
  rooms::RoomTimerConfig timer;
  rooms::RoomExtractionConfig extraction;
  rooms::SgraphsRoomExtractionConfig sgraphs_extraction;
  rooms::RoomAssociationConfig association;
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
  std::vector<int> walls;                 ///< every plane that bounds it
  std::vector<int> factor_walls;          ///< the planes of its room-planes factor (4, 2, or none)
  std::vector<std::pair<int, int>> merged;///< (keep, drop) room ids merged as duplicates after it
  std::vector<Eigen::Vector3d> free_space;///< the free-space vertices it was extracted from (map frame)
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
  std::vector<int> keyframe_planes;                  ///< ids of the planes this keyframe observes
};

class RoomLayer {
 public:
  /// Throws std::invalid_argument for an unknown free_space_method, room_trigger or footprint policy.
  explicit RoomLayer(RoomLayerSettings settings);

  /// Processes one keyframe; returns the room events it produced (0 or 1).
  std::vector<RoomEventRecord> update(const RoomLayerInput& input);
  /// Extracts what is accumulated at the end of the run (flush trigger).
  std::vector<RoomEventRecord> finish(const RoomLayerInput& input);

  const rooms::RoomMap& room_map() const { return map_; }
  /// Moves mapped room `id` (the back-end moved its room node).
  void move_room(int id, const Vec2& center);
  /// Size of the robot's free-space cluster at the last keyframe (vertices).
  std::size_t last_cluster_size() const { return last_cluster_size_; }
  /// Floor height (map frame) of each level index, in order of first visit.
  const std::vector<double>& levels() const { return levels_; }

 private:
  /// Free space vertex key -> position: a node id (nodes move with their keyframes) or an ESDF
  /// cell index (fixed in the map frame).
  using Vertices = std::map<std::int64_t, Eigen::Vector3d>;
  struct KeyframeSpace {
    Vertices near;     ///< the robot's cluster near its path (segment_radius)
    Vertices cluster;  ///< the whole robot cluster (context)
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< the robot's floor point
  };

  bool esdf() const { return settings_.layer.free_space_method == "esdf"; }
  /// The robot's free-space cluster at this keyframe; false when the robot is in none.
  bool robot_space(const RoomLayerInput& input, const Eigen::Vector3d& floor, KeyframeSpace& out);
  std::vector<RoomEventRecord> update_flush(const RoomLayerInput& input, KeyframeSpace space, int level,
                                            bool passed_doorway);
  std::vector<RoomEventRecord> extract(const RoomLayerInput& input, const Vertices& segment,
                                       const Vertices& context, int level);
  int level_of(double floor_z);
  void commit(const KeyframeSpace& space);
  void clear_segment();

  RoomLayerSettings settings_;
  rooms::RoomFlushTrigger flush_trigger_;
  rooms::RoomTimerTrigger timer_trigger_;
  rooms::RoomMap map_;
  Vertices segment_;                        ///< the free space walked since the last flush
  Vertices context_;                        ///< the whole clusters the robot was in meanwhile
  double segment_length_ = 0.0;             ///< path walked in the segment (m)
  std::optional<Eigen::Vector3d> last_position_;
  std::vector<KeyframeSpace> pending_;      ///< the latest keyframes' free space, held while the trigger confirms a change
  std::vector<double> levels_;              ///< floor heights of the levels seen
  int segment_level_ = -1;
  bool was_in_free_space_ = true;
  std::size_t last_cluster_size_ = 0;
};

}  // namespace tsgraphs::pipeline
