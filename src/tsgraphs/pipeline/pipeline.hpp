#pragma once
/// The per-scan SLAM pipeline: one scan and its odometry pose at a time (so a live source
/// can drive it), prefilter -> keyframe selection -> walls -> graph (loop closure,
/// optimisation). No file I/O: run_outputs.hpp writes what it holds.
#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/graph/graph_optimizer.hpp"
#include "tsgraphs/graph/situational_graph.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/pipeline/scan_log.hpp"
#include "tsgraphs/walls/plane_extraction.hpp"
#include "tsgraphs/walls/plane_mapper.hpp"

namespace tsgraphs::pipeline {

/// A scan after the steps that need nothing but the scan and its odometry: made by
/// Pipeline::prepare, which may run on other threads, ahead of process(). Only a keyframe's
/// prefiltered cloud, ground and planes are used, so only keyframe candidates get them here.
struct PreparedScan {
  ScanRecord record;            ///< with the prepare-time fields filled
  bool keyframe_steps = false;  ///< prefilter, ground and planes ran (a keyframe candidate)
  PointCloud cloud;             ///< prefiltered
  ground::GroundScan ground;
  std::optional<std::vector<walls::PlaneObservation>> planes;
  bool input_empty = false;      ///< no finite point (empty or all NaN): skipped with a warning
  bool input_no_points = false;  ///< no point at all (the warning says "empty", not "all NaN")
};

/// A loop closure as accepted (the graph's edge may later move: keyframe retirement folds it).
struct LoopClosureRecord {
  graph::BetweenEdge edge;
  std::string proposer;  ///< "distance" or "room"
};

/// One back-end run.
struct OptimizationRecord {
  int after_keyframe = -1;  ///< the newest keyframe when it ran
  std::string reason;       ///< "schedule", "loop", "periodic" or "final"
  graph::OptimizationStats stats;
  int active_keyframes = 0;  ///< keyframes in the graph after it and the retirements that followed
};

class Pipeline {
 public:
  /// Throws std::invalid_argument ("PipelineConfig: <section.key> must be ...") for a config
  /// its fields' declarations refuse, as load_pipeline_config refuses such a file.
  explicit Pipeline(PipelineConfig config = {});

  /// Measures the platform (sensor height, seed radius, ground preset: platform.hpp) from scans
  /// of the run, sensor frames (`ups`: empty, or the gravity's up in each when the poses give
  /// it), and sets the ground layer from it; once, before the first prepare().
  /// process(scan_index, ...) calls it with its first scan if nobody did.
  void set_platform(const std::vector<PointCloud>& scans, const std::vector<Eigen::Vector3d>& ups = {});
  /// The resolved platform, null before set_platform().
  const Platform* platform() const { return platform_ ? &*platform_ : nullptr; }
  /// Every warning so far, in order (a layer empty for diagnostics.empty_layer_keyframes, no
  /// room in a run of at least that many keyframes, the platform's); the caller prints the new ones.
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// Processes one scan (sensor frame) with its odometry pose (odom <- sensor). A scan with no
  /// usable point is recorded with a warning and only its pose is kept. A non-finite pose
  /// throws std::invalid_argument (the reader is expected to reject it with file and line).
  const ScanRecord& process(std::size_t scan_index, double stamp, const PointCloud& scan, const Pose3& odom);
  /// The same in two halves: prepare() is const and thread-safe, so a reader can run it for
  /// the next scans while process() takes the prepared scans in order. For a keyframe
  /// candidate it runs the keyframe steps (prefilter, ground, scoring against labels, wall
  /// planes). Results are the same as process() above. KeyframeSelector, run over the
  /// odometry alone, says which scans are candidates; a wrong guess only costs time: process()
  /// runs the steps itself on `scan` (the one given to prepare) for a keyframe not prepared as one.
  PreparedScan prepare(std::size_t scan_index, double stamp, const PointCloud& scan, const Pose3& odom,
                       bool keyframe_candidate) const;
  /// `scan` is used only when the scan is a keyframe (would_be_keyframe): a caller may pass
  /// an empty cloud for another, with the prepared scan's input_empty and input_no_points
  /// saying what it held.
  const ScanRecord& process(PreparedScan prepared, const PointCloud& scan);
  /// Whether process() will take a scan at `odom` (the next, in order) as a keyframe, if it
  /// has points left after prefiltering.
  bool would_be_keyframe(const Pose3& odom) const { return selector_.is_keyframe(odom); }
  /// Final full optimisation; call once after the last scan.
  void finish();

  const PipelineConfig& config() const { return config_; }
  const graph::SituationalGraph& graph() const { return graph_; }
  const walls::PlaneMapper& plane_map() const { return mapper_; }
  const ground::TraversableNodeMap& node_map() const { return node_map_; }
  const rooms::RoomMap& room_map() const { return rooms_.room_map(); }
  const room_layer::RoomLayer& room_layer() const { return rooms_; }
  /// The graph room node of mapped room `room_id`, -1 if it has none (a one-sided corridor).
  int room_node_of(int room_id) const {
    const auto it = room_nodes_.find(room_id);
    return it == room_nodes_.end() ? -1 : it->second.node;
  }
  /// Every room extraction so far, in time order.
  const std::vector<room_layer::RoomEventRecord>& room_events() const { return room_events_; }
  /// The ground of the newest keyframe (level frame of its scan), for callers that draw it.
  const ground::GroundScan& last_ground() const { return last_ground_; }
  /// Every scan processed so far, in order (spilled to a temporary file beyond the newest).
  const ScanLog& scan_log() const { return scan_log_; }
  const std::vector<OptimizationRecord>& optimizations() const { return optimizations_; }
  /// Every loop closure accepted, in order.
  const std::vector<LoopClosureRecord>& loop_closures() const { return loop_closures_; }
  /// Keyframe `id`'s prefiltered cloud in its own frame.
  const PointCloud& keyframe_cloud(int id) const { return keyframe_clouds_.at(id); }
  /// The corrected pose of every scan processed so far: its reference keyframe's estimate
  /// times the odometry motion since that keyframe.
  std::vector<Pose3> trajectory() const;

 private:
  void add_keyframe(ScanRecord& record, PointCloud cloud,
                    std::optional<std::vector<walls::PlaneObservation>> planes);
  /// The newest ground's traversable nodes into the global node map, in keyframe `id`'s frame;
  /// how many.
  std::size_t fuse_ground(int id);
  /// The keyframe's wall (and floor, ceiling) planes associated or mapped, their factors added;
  /// how many were walls.
  std::size_t add_planes(int id, const ScanRecord& record,
                         std::optional<std::vector<walls::PlaneObservation>> planes);
  /// Loop closure at keyframe `id`: a room re-detected with its walls proposes first, then the
  /// distance rule.
  void close_loop(int id);
  room_layer::RoomLayerInput room_input(int keyframe) const;
  /// Records room events and puts new rooms, and merges, into the graph.
  void add_room_events(const std::vector<room_layer::RoomEventRecord>& events);
  void move_rooms_with_graph();
  /// Prefilter, ground (scored against the scan's labels) and wall planes: what a keyframe uses.
  void run_keyframe_steps(const PointCloud& scan, const Pose3& odom, PreparedScan* out) const;
  void score_ground(const PointCloud& scan, const ground::GroundScan& ground, ScanRecord* record) const;
  void optimize(bool full, const std::string& reason);
  /// Whether a new loop disagrees with the estimate by schedule.full_solve_loop_sigmas or more
  /// of the noise a local solve can take up (loop_asks_for_full_solve's comment).
  bool loop_asks_for_full_solve(const graph::BetweenEdge& loop) const;
  /// Keyframe retirement after a solve: the redundant keyframes of the local window (after a
  /// full solve, of the whole graph) leave the graph, their observations the plane map, their
  /// clouds memory (once the room layer's obstacle window has passed them).
  void retire_redundant_keyframes(bool whole_graph, const std::function<Pose3(int)>& pose_of);
  /// Whether a pose stands inside a mapped room or corridor of its level.
  bool in_mapped_space(const Pose3& pose) const;
  /// Counts keyframes in which a layer stayed empty and warns once per layer.
  void check_empty_layers(int keyframe, std::size_t ground_nodes, std::size_t walls);
  /// Why the ground or the wall layer is empty, from the latest keyframe (`keyframe`).
  std::string no_ground_cause() const;
  std::string no_walls_cause(int keyframe) const;

  PipelineConfig config_;
  std::optional<Platform> platform_;
  std::vector<std::string> warnings_;
  /// Keyframes in a row without traversable ground / without a wall, in all, and whether the
  /// layer was warned about.
  struct EmptyLayer {
    int in_row = 0;
    int total = 0;
    bool warned = false;
  };
  EmptyLayer no_ground_, no_walls_;
  KeyframeSelector selector_;
  walls::PlaneMapper mapper_;
  ground::TraversableNodeMap node_map_;
  room_layer::RoomLayer rooms_;
  std::vector<room_layer::RoomEventRecord> room_events_;
  struct RoomNodeLink {
    int node = -1;               ///< graph room id
    Vec2 center = Vec2::Zero();  ///< its centre when the room map last followed it
  };
  std::map<int, RoomNodeLink> room_nodes_;  ///< room map id -> graph room node
  ground::GroundScan last_ground_;
  graph::SituationalGraph graph_;
  graph::GraphOptimizer optimizer_;
  graph::LoopDetector loop_detector_;
  std::vector<PointCloud> keyframe_clouds_;
  std::vector<int> clouds_to_release_;  ///< retired keyframes whose clouds the obstacle window still reads
  ScanLog scan_log_;
  ScanRecord last_record_;  ///< the newest scan's, returned by process()
  std::vector<OptimizationRecord> optimizations_;
  std::vector<LoopClosureRecord> loop_closures_;
  std::map<int, std::vector<int>> room_walls_;  ///< room map id -> the walls of its latest extraction
  int revisited_room_ = -1;  ///< a mapped room the newest keyframe re-detected with its walls, or -1
  double accum_distance_ = 0.0;
  std::optional<Pose3> last_odom_;
  int keyframes_since_solve_ = 0;
  int active_at_last_full_ = 0;  ///< keyframes in the graph after the last full solve
  int corrected_at_ = 0;         ///< newest keyframe at the last solve that took in a loop
};

}  // namespace tsgraphs::pipeline
