#pragma once
/// The room layer of the pipeline (DESIGN.md steps 6-7 and the baseline mode): at every keyframe
/// the free space around the robot, and the trigger that says when to extract a room from it.
///
/// - TS-graphs (`free_space_method: traversable`, `room_trigger: flush`): free space on the
///   traversable nodes near the robot, and what its rays saw at walking height (sight map);
///   the flush rule on the aisle it is in, and a step across a mapped wall (a door); when
///   either fires, the level's free space is segmented into spaces (segment_rooms) and each
///   space the segment's path ran in is extracted, associated with the room map by the overlap
///   of the footprints (Dice) or centre distance.
/// - S-Graphs+ (`esdf`, `timer`): free space from the ESDF slice of the latest keyframes' points;
///   every period the robot's cluster is extracted with the planes of the last keyframe
///   (extract_room_sgraphs) and associated by centre distance only.
/// - The other two combinations are the ablation: the free space method brings its extraction
///   and association, the trigger says when.
#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/room_layer/room_layer_config.hpp"
#include "tsgraphs/freespace/esdf_free_space.hpp"
#include "tsgraphs/freespace/sight_map.hpp"
#include "tsgraphs/freespace/wall_top_rays.hpp"
#include "tsgraphs/freespace/traversable_free_space.hpp"
#include "tsgraphs/ground/traversable_node_map.hpp"
#include "tsgraphs/rooms/room_association.hpp"
#include "tsgraphs/rooms/room_flush_trigger.hpp"
#include "tsgraphs/rooms/room_segmentation.hpp"
#include "tsgraphs/rooms/room_timer_trigger.hpp"
#include "tsgraphs/rooms/sgraphs_room_extraction.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::room_layer {

/// Every parameter the room layer uses, one struct per module.
struct RoomLayerSettings {
  RoomLayerConfig layer;
  freespace::TraversableFreeSpaceConfig free_space;
  freespace::EsdfFreeSpaceConfig esdf;
  freespace::SightMapConfig sight;  ///< floor_step and headroom come from free_space's obstacle heights
  rooms::AisleMeasureConfig aisle;
  rooms::RoomFlushConfig flush;
  rooms::RoomTimerConfig timer;
  rooms::RoomSegmentationConfig segmentation;
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
  Polygon2 outline;                         ///< the footprint when it is no rectangle (empty: rect)
  std::vector<int> walls;                   ///< every plane that bounds it
  std::vector<int> factor_walls;            ///< the planes of its room-planes factor (4, 2, or none)
  std::vector<std::pair<int, int>> merged;  ///< (keep, drop) room ids merged as duplicates after it
  std::vector<Eigen::Vector3d> free_space;  ///< the free-space vertices it was extracted from (map frame)
};

/// What the layer needs of the rest of the map at a keyframe.
struct RoomLayerInput {
  double stamp = 0.0;
  int keyframe = -1;
  Pose3 pose = Pose3::Identity();  ///< the keyframe's current estimate (sensor)
  double sensor_height = 0.0;      ///< the sensor above the floor (m)
  const ground::TraversableNodeMap* nodes = nullptr;
  std::vector<Eigen::Vector3d> obstacle_candidates;  ///< map-frame points of the latest keyframes
  std::vector<Eigen::Vector3d>
      scan_points;                    ///< this keyframe's points, map frame, thinned (the sight map's rays)
  std::vector<Pose3> keyframe_poses;  ///< TS-graphs: every keyframe's current estimate by index, so that
                                      ///< earlier rays follow their keyframes (empty: they stay where traced)
  std::vector<rooms::WallCandidate> walls;  ///< every mapped vertical plane with its extent
  std::vector<int> keyframe_planes;         ///< ids of the planes this keyframe observes
};

class RoomLayer {
 public:
  /// Throws std::invalid_argument for a layer or association config out of its limits.
  explicit RoomLayer(RoomLayerSettings settings);

  /// Processes one keyframe; returns the room events it produced (0 or 1).
  std::vector<RoomEventRecord> update(const RoomLayerInput& input);
  /// Extracts what is accumulated at the end of the run (flush trigger).
  std::vector<RoomEventRecord> finish(const RoomLayerInput& input);

  const rooms::RoomMap& room_map() const { return map_; }
  /// Moves mapped room `id` (the back-end moved its room node).
  void move_room(int id, const Vec2& center);
  /// A keyframe retired from the graph (keyframe_retirement.hpp): its rays leave the sight map
  /// and their points memory; the earlier pass's rays cover where it stood.
  void forget_keyframe(int keyframe);
  /// Size of the robot's free-space cluster at the last keyframe (vertices).
  std::size_t last_cluster_size() const { return last_cluster_size_; }
  /// Floor height (map frame) of each level index, in order of first visit.
  const std::vector<double>& levels() const { return levels_; }
  /// TS-graphs: the latest segmentation of a level (null before the first) and its level
  /// index; `segmentations()` counts them, so a caller can tell a new one.
  const rooms::RoomSegmentation* last_segmentation() const {
    return last_segmentation_ ? &*last_segmentation_ : nullptr;
  }
  int last_segmentation_level() const { return last_segmentation_level_; }
  std::size_t segmentations() const { return segmentations_; }

 private:
  /// Free space vertex key -> position: a node id (nodes move with their keyframes) or an ESDF
  /// cell index (fixed in the map frame).
  using Vertices = std::map<std::int64_t, Eigen::Vector3d>;
  struct KeyframeSpace {
    Vertices near;     ///< the robot's cluster near its path (segment_radius)
    Vertices cluster;  ///< the whole robot cluster (context)
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< the robot's floor point
  };

  bool esdf() const { return settings_.layer.free_space_method == FreeSpaceMethod::esdf; }
  /// The robot's free-space cluster at this keyframe; false when the robot is in none.
  bool robot_space(const RoomLayerInput& input, const Eigen::Vector3d& floor, KeyframeSpace& out);
  std::vector<RoomEventRecord> update_flush(const RoomLayerInput& input, KeyframeSpace space, int level,
                                            bool passed_doorway);
  /// TS-graphs: the keyframe's rays into the level's sight map (kept to follow the keyframe),
  /// and the walls' tops judged by them.
  void trace(const RoomLayerInput& input, int level);
  /// Whether rays passed above each wall short of the reach height (walls_' top_seen).
  void judge_wall_tops(const RoomLayerInput& input, int level, const std::vector<Eigen::Vector3d>& points,
                       const freespace::SightMap& sight);
  /// S-Graphs+: every period, the robot's whole cluster as it is now.
  std::vector<RoomEventRecord> update_timer(const RoomLayerInput& input, const Eigen::Vector3d& floor,
                                            int level);
  /// TS-graphs: whether the robot, stepping from `from` to `floor`, has walked min_visit_length
  /// into another space of the latest segmentation (a corner or a doorway's strip is no change).
  bool moved_on(const Eigen::Vector3d& from, const Eigen::Vector3d& floor, int level);
  /// The level's segmentation input: its floor from the segment's free space, its ground and
  /// raised ground, the free space walked, the walls and what the rays saw; none when there is
  /// nothing to bound.
  std::optional<rooms::SegmentationInput> segmentation_input(const RoomLayerInput& input,
                                                             const Vertices& segment, int level);
  std::vector<RoomEventRecord> extract(const RoomLayerInput& input, const Vertices& segment, int level,
                                       bool final = false);
  /// TS-graphs: the spaces of the level's segmentation the segment's path ran in.
  /// The spaces explored enough are returned; the path in the others is kept in deferred_path_
  /// for the next extraction (all are returned when `final`).
  std::vector<rooms::ExtractedRoom> segmented_spaces(const RoomLayerInput& input, const Vertices& segment,
                                                     std::vector<Eigen::Vector3d> path, int level,
                                                     bool final);
  /// The path with the deferred floor points of its level first (the others stay deferred).
  std::vector<Eigen::Vector3d> with_deferred_path(std::vector<Eigen::Vector3d> path);
  /// The space of `seg` holding the floor point (or the nearest within a node's reach of the free space), or
  /// -1.
  int space_of(const rooms::RoomSegmentation& seg, const Eigen::Vector3d& floor) const;
  RoomEventRecord event_of(const RoomLayerInput& input, const rooms::ExtractedRoom& room, int level,
                           std::vector<Eigen::Vector3d> free_space);
  int level_of(double floor_z);
  /// Adds the robot's floor point to its recent track; false while the track rises faster than
  /// max_floor_slope over floor_window (a ramp, stairs): such floors belong to no level.
  bool on_level_floor(const Eigen::Vector3d& floor);
  void commit(const KeyframeSpace& space);
  /// TS-graphs: a keyframe's rays, kept in its own frame so that they follow it when the
  /// back-end corrects it (the planes they are judged against move with the optimisation).
  struct TracedScan {
    int keyframe = -1;
    int level = -1;
    Pose3 traced_at = Pose3::Identity();  ///< where its rays are in the sight map
    std::vector<Eigen::Vector3f> local;   ///< its points, sensor frame
    double reach = 0.0;                   ///< its farthest point from the sensor (m)
  };
  static std::vector<Eigen::Vector3d> map_points(const TracedScan& scan);
  /// Traces again each kept scan whose keyframe has moved by more than a sight-map cell at its
  /// farthest point (counted in retraced_).
  void retrace(const RoomLayerInput& input);
  void clear_segment();

  RoomLayerSettings settings_;
  rooms::RoomFlushTrigger flush_trigger_;
  rooms::RoomTimerTrigger timer_trigger_;
  rooms::RoomMap map_;
  Vertices segment_;             ///< the free space walked since the last flush
  double segment_length_ = 0.0;  ///< path walked in the segment (m)
  std::optional<Eigen::Vector3d> last_position_;
  std::vector<Eigen::Vector3d> segment_path_;  ///< the robot's floor points in the segment, in order
  std::optional<rooms::RoomSegmentation>
      last_segmentation_;  ///< TS-graphs: the latest one, to tell a change of space
  int last_segmentation_level_ = -1;
  std::size_t segmentations_ = 0;
  int last_space_ = -1;                         ///< the space of it the robot is in
  int entering_space_ = -1;                     ///< another space the robot has stepped into...
  double entering_length_ = 0.0;                ///< ...and how far it has walked in it (m)
  double nodes_cell_ = 0.25;                    ///< the node map's cell (the reach of a node)
  std::vector<Eigen::Vector3d> deferred_path_;  ///< TS-graphs: floor points in spaces not yet explored enough
  std::map<int, freespace::SightMap> sight_;    ///< TS-graphs: per level, what the rays saw
  freespace::WallTopRays wall_tops_;            ///< TS-graphs: the rays that passed above the planes' tops
  std::vector<TracedScan> traced_;              ///< TS-graphs: every keyframe's rays in the sight map
  int retraced_ = 0;                            ///< TS-graphs: how many times kept scans were traced again
  std::map<int, int> wall_tops_at_;  ///< TS-graphs: per plane, retraced_ when its rays were recorded
  std::set<int> free_nodes_;         ///< TS-graphs: every node that was in the robot's free space
  std::vector<KeyframeSpace>
      pending_;  ///< the latest keyframes' free space, held while the trigger confirms a change
  std::vector<double> levels_;  ///< floor heights of the levels seen
  std::vector<rooms::WallCandidate>
      walls_;  ///< TS-graphs: the keyframe's walls, whether rays saw above their tops set
  std::deque<std::pair<double, Eigen::Vector3d>>
      floor_track_;            ///< (path length, floor point) over the last floor_window
  double track_length_ = 0.0;  ///< the robot's path length so far (m)
  int segment_level_ = -1;
  bool was_in_free_space_ = true;
  std::size_t last_cluster_size_ = 0;
};

}  // namespace tsgraphs::room_layer
