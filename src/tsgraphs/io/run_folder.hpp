#pragma once
/// The run folder's schema (docs/run.md, "Outputs"): the files `tsgraphs run` writes that eval
/// and report read back, as plain structs, each with the one formatter and the one reader of
/// its file. Readers throw InputError naming the file, the line (text files) and the key;
/// unknown JSON keys and unknown CSV columns are ignored, so an older reader takes a newer
/// folder. Every number must be finite and every position, size and plane offset of
/// scene_graph.json and rooms_events.jsonl within kMaxCoordinate (coordinate_limit.hpp); a
/// number beyond a double names its line, a folder in a file's place says so.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/core/rect.hpp"

namespace tsgraphs::io {

/// File names inside a run folder.
namespace run_files {
inline constexpr const char* kTrajectory = "trajectory.txt";
inline constexpr const char* kOdometry = "odometry.txt";
inline constexpr const char* kSceneGraph = "scene_graph.json";
inline constexpr const char* kMap = "map.ply";
inline constexpr const char* kTimings = "timings.csv";
inline constexpr const char* kParams = "params.yaml";
inline constexpr const char* kRunInfo = "run_info.json";
inline constexpr const char* kMetrics = "metrics.json";
inline constexpr const char* kRoomEvents = "rooms_events.jsonl";
inline constexpr const char* kSegmentations = "segmentations";  ///< a folder, with run --segmentations
}  // namespace run_files

// ---- scene_graph.json ---------------------------------------------------------------------

/// A pose as the file holds it: translation and quaternion, kept as written so that the
/// file reads back to the same text.
struct PoseRecord {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  ///< written [x, y, z, w]

  static PoseRecord of(const Pose3& pose);
  /// The pose, the quaternion normalised.
  Pose3 pose() const;
};

/// Every node and edge of the situational graph at the end of a run, map frame. Keys in
/// brackets are optional when reading (older folders); everything is written.
struct SceneGraph {
  struct Keyframe {
    int id = -1;
    std::size_t scan_index = 0;  ///< index of its scan in the input sequence
    double stamp = 0.0;
    double accum_distance = 0.0;  ///< odometry distance from the start, m
    PoseRecord pose;              ///< optimised, map <- keyframe
    PoseRecord odom;              ///< the input odometry
    int anchor =
        -1;  ///< [anchor]: retired (keyframe_retirement), its pose follows this keyframe's; -1: in the graph
  };
  /// A mapped plane; the extent fields exist when it has points (segment: walls only).
  struct Plane {
    int id = -1;
    std::string kind = "wall";  ///< "wall" or "horizontal"
    Eigen::Vector3d n = Eigen::Vector3d::UnitX();
    double d = 0.0;
    std::vector<int> keyframes;                    ///< observers, ascending
    std::optional<std::size_t> num_points;         ///< [num_points]
    std::optional<Eigen::Vector3d> centroid;       ///< [centroid], on the plane
    std::optional<std::array<Vec2, 2>> segment;    ///< [segment]: ends of the points' extent, x-y
    std::optional<std::array<double, 2>> z_range;  ///< [z_range]: the points' heights
  };
  struct TraversableNode {
    int id = -1;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double probability = 0.0;
    int observations = 0;        ///< [observations]
    int anchor_keyframe = -1;    ///< [anchor_keyframe]
    std::vector<int> keyframes;  ///< [keyframes]
  };
  /// A footprint of the room map.
  struct Room {
    int id = -1;
    std::string kind = "room";  ///< "room" or "corridor"
    int level = 0;              ///< index into `levels`
    OrientedRect rect;          ///< the footprint, or the smallest rectangle round `polygon`
    Polygon2 polygon;  ///< [polygon]: the footprint when it is no rectangle (counter-clockwise), else empty
    std::vector<int> walls;                   ///< [walls]
    int extractions = 0;                      ///< [extractions]: extractions associated with it
    std::optional<int> node;                  ///< [node]: its room node, null when it has none
    std::vector<Eigen::Vector3d> free_space;  ///< [free_space]: vertices of its latest extraction
  };
  /// A room node of the graph (optimised centre).
  struct RoomNode {
    int id = -1;
    std::string kind = "room";
    int level = 0;
    Vec2 center = Vec2::Zero();
  };
  struct Floor {
    int id = -1;
    int level = 0;
    Vec2 center = Vec2::Zero();
  };
  struct OdometryEdge {
    int from = -1, to = -1;
    PoseRecord measurement;  ///< T_from_to
  };
  struct LoopEdge {
    int from = -1, to = -1;
    double fitness = 0.0;
    PoseRecord measurement;  ///< T_from_to
    int folded = 0;          ///< [folded]: retired keyframes composed into it (it moved to a later keyframe)
  };
  /// A loop closure as it was accepted (the graph's loop edge may since have moved, folded).
  struct LoopClosure {
    int from = -1, to = -1;
    double fitness = 0.0;
    PoseRecord measurement;  ///< T_from_to, as registered
    std::string proposer;    ///< who proposed the pair: "distance" (near in the map, far in travel) or "room"
  };
  struct KeyframePlaneEdge {
    int keyframe = -1, plane = -1;
    Eigen::Vector4d measurement = Eigen::Vector4d::Zero();  ///< n and d in the keyframe's frame
  };
  struct RoomPlanesEdge {
    int room = -1;
    std::string kind = "room";
    std::vector<int> planes;
    Vec2 cluster_center = Vec2::Zero();
  };
  struct FloorRoomEdge {
    int floor = -1, room = -1;
  };

  std::string frame = "map";
  std::vector<Keyframe> keyframes;
  std::vector<Plane> planes;
  std::vector<TraversableNode> traversable_nodes;  ///< [traversable_nodes]
  std::vector<Room> rooms;                         ///< [rooms]
  std::vector<RoomNode> room_nodes;                ///< [room_nodes]
  std::vector<Floor> floors;                       ///< [floors]
  std::vector<double> levels;                      ///< [levels]: floor height of each level index
  /// "edges" holds them in this order, each with its "type"; unknown types are skipped.
  std::vector<OdometryEdge> odometry_edges;
  std::vector<LoopEdge> loop_edges;
  std::vector<KeyframePlaneEdge> keyframe_plane_edges;
  std::vector<RoomPlanesEdge> room_planes_edges;
  std::vector<FloorRoomEdge> floor_room_edges;
  std::vector<LoopClosure> loop_closures;  ///< [loop_closures]: every accepted loop, in order
};

/// scene_graph.json's text ("format": "tsgraphs-scene-graph", "version": 1).
std::string format_scene_graph(const SceneGraph& graph);
/// Reads a scene_graph.json; `keyframes`, `planes` and `edges` are required.
SceneGraph read_scene_graph(const std::string& path);

// ---- rooms_events.jsonl -------------------------------------------------------------------

/// One line of rooms_events.jsonl: one room extraction (docs/metrics.md).
struct RoomEvent {
  double t = 0.0;      ///< time of the extraction, s
  int lap = 1;         ///< traversal it happened in, from 1
  int room_id = -1;    ///< the room node it created or was associated with
  bool is_new = true;  ///< key "new": false for a re-detection of an existing room node
  int level = 0;       ///< index of the level
  Vec2 center = Vec2::Zero();
  OrientedRect
      rect;  ///< footprint in the map frame at the time of extraction (or the rectangle round `polygon`)
  Polygon2 polygon;           ///< [polygon]: the footprint when it is no rectangle, else empty
  std::vector<int> walls;     ///< ids of the wall planes that bound it
  std::string kind = "room";  ///< "room" or "corridor"
};

/// The event as one line of JSON without the newline, keys in alphabetical order (as `run`
/// has always written them). Numbers round-trip exactly through read_room_events.
std::string format_room_event(const RoomEvent& event);
/// The whole file: one line per event.
std::string format_room_events(const std::vector<RoomEvent>& events);
/// Every event of a rooms_events.jsonl file, in file order; blank lines are skipped.
std::vector<RoomEvent> read_room_events(const std::string& path);

// ---- timings.csv --------------------------------------------------------------------------

/// A scan row: what the front end did with one scan.
struct ScanTiming {
  std::size_t index = 0;  ///< scan index
  double stamp = 0.0;
  int keyframe = -1;  ///< keyframe made from it, -1 for none
  std::size_t num_points = 0;
  double prefilter_ms = 0.0, walls_ms = 0.0, loop_ms = 0.0, frontend_ms = 0.0;
  std::string warning;  ///< column "reason": why it was skipped, "" for none
  double ground_ms = 0.0;
  std::size_t ground_nodes = 0;
  long ground_tp = -1, ground_fp = -1, ground_fn = -1;  ///< -1: the scan had no labels
  double rooms_ms = 0.0;
};

/// An optimization row: one back-end run.
struct OptimizationTiming {
  std::size_t index = 0;  ///< running number
  double stamp = 0.0;     ///< stamp of the newest keyframe
  int keyframe = -1;      ///< the newest keyframe
  double seconds = 0.0;   ///< column "optimization_s"
  bool full = false;
  int n_variables = 0, n_factors = 0, iterations = 0;
  std::string reason;  ///< "schedule", "loop", "periodic" or "final"
  int active_keyframes =
      -1;  ///< keyframes in the graph after it (retired ones not counted); -1: not recorded
};

struct Timings {
  std::vector<ScanTiming> scans;
  std::vector<OptimizationTiming> optimizations;
};

/// The CSV text: the header, a row per scan, then a row per optimization.
std::string format_timings(const Timings& timings);
/// Reads timings.csv; columns are found by the header's names (every column written today is
/// required, others are ignored).
Timings read_timings(const std::string& path);

// ---- run_info.json ------------------------------------------------------------------------

/// The platform the run measured or was given (pipeline/platform.hpp).
struct RunPlatform {
  double sensor_height = 0.0;        ///< m above the floor
  std::string sensor_height_source;  ///< "measured", "config" or "fallback"
  double tilt_deg = 0.0;             ///< measured: the sensor's z against the floor's normal
  std::size_t scans_measured = 0, floors_found = 0;
  double height_spread = 0.0;  ///< m, max - min over the scans with a floor
  int rings = 0;               ///< beam rings found
  double ring_spacing_deg = 0.0, lowest_ring_deg = 0.0;
  std::string preset;              ///< the ground's preset ("" none)
  std::string preset_source;       ///< "beams", "config" or "none"
  double seed_radius = 0.0;        ///< m
  std::string seed_radius_source;  ///< "beams", "config" or "default"
};

/// The run's summary.
struct RunSummary {
  std::string sequence;  ///< input folder or file
  std::size_t num_scans = 0, num_skipped = 0;
  std::string odometry = "input";  ///< "input" or "lidar": where the poses came from
  std::size_t num_keyframes = 0, num_planes = 0, num_traversable_nodes = 0, num_rooms = 0,
              num_room_events = 0, num_loops = 0, num_optimizations = 0;
  double t_pgo_s = 0.0;  ///< total back-end time
  double sequence_duration_s = 0.0;
  double wall_time_s = 0.0;
  double rtf = 0.0;  ///< sequence_duration_s / wall_time_s (0 when no time passed)
  double peak_rss_mb = 0.0;
  std::optional<RunPlatform> platform;  ///< absent in runs written before tsgraphs measured it
  std::vector<std::string>
      warnings;  ///< the pipeline's warnings (a layer left empty, the platform), in order
};

std::string format_run_summary(const RunSummary& summary);
/// Reads run_info.json; every key above is required but `platform` and `warnings`.
RunSummary read_run_summary(const std::string& path);

// ---- map.ply --------------------------------------------------------------------------------

/// A vertex of map.ply: where, and its layer's colour.
struct MapVertex {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  std::uint8_t r = 0, g = 0, b = 0;
};
/// map.ply's vertices: binary little-endian, x y z (double, or float as runs wrote before the
/// map frame) then uchar red green blue. Anything else, a body short of its vertex count or
/// longer, or a coordinate not finite or beyond kMaxCoordinate is an InputError naming the file
/// and the byte (and the vertex).
std::vector<MapVertex> read_map_ply(const std::string& path);

}  // namespace tsgraphs::io
