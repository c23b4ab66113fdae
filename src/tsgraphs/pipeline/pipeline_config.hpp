#pragma once
/// Every parameter of the pipeline, one section per module, and the YAML file that sets
/// them (config/params.yaml lists every key with its default). Unknown keys are errors.
#include <set>
#include <string>

#include "tsgraphs/graph/graph_optimizer.hpp"
#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/ground/traversable_node_map.hpp"
#include "tsgraphs/graph/keyframe_retirement.hpp"
#include "tsgraphs/graph/loop_closure.hpp"
#include "tsgraphs/graph/room_loop_closure.hpp"
#include "tsgraphs/odometry/deskew_config.hpp"
#include "tsgraphs/odometry/floor_levelling.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"
#include "tsgraphs/odometry/sweep_registration.hpp"
#include "tsgraphs/pipeline/keyframe_selector.hpp"
#include "tsgraphs/pipeline/platform.hpp"
#include "tsgraphs/pipeline/prefilter.hpp"
#include "tsgraphs/room_layer/room_layer.hpp"
#include "tsgraphs/rooms/map_walls.hpp"
#include "tsgraphs/walls/plane_extraction.hpp"
#include "tsgraphs/walls/plane_mapper.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::pipeline {

/// When the back-end runs.
struct ScheduleConfig {
  int optimize_every_keyframes = 5;
  int full_every_keyframes = 50;
  /// A loop this many sigmas or more from the estimate asks for a full solve (the old graph has
  /// drift to correct); a nearer one is taken in by a local solve (0: every loop a full solve).
  /// Sigmas: the loop's, with the odometry's of the keyframes since the last correction when
  /// that lies in the local window (Pipeline::loop_asks_for_full_solve).
  double full_solve_loop_sigmas = 3.0;
  bool merge_duplicate_planes = true;

  template <class V>
  void visit(V& v) {
    v("optimize_every_keyframes", optimize_every_keyframes, between(1, 100000),
      "a local solve after this many new keyframes");
    v("full_every_keyframes", full_every_keyframes, between(0, 100000),
      "a full solve after the graph grew by this many keyframes (retired ones leave it; 0 = only after loops "
      "and at the end)");
    v("full_solve_loop_sigmas", full_solve_loop_sigmas, between(0.0, 1e6),
      "a loop this many sigmas from the estimate asks for a full solve (sigmas: the loop's, with the "
      "odometry's since the last correction when it lies in the local window); a nearer one, a local solve "
      "(0: every loop)");
    v("merge_duplicate_planes", merge_duplicate_planes,
      "merge mapped planes found to be one face after each solve");
  }
};

/// What the pipeline says about layers that stay empty.
struct DiagnosticsConfig {
  int empty_layer_keyframes = 50;

  template <class V>
  void visit(V& v) {
    v("empty_layer_keyframes", empty_layer_keyframes, between(0, 1000000),
      "warn when no traversable ground or no wall came for this many keyframes, or a run this long has no "
      "room (0: never)");
  }
};

struct PipelineConfig {
  PlatformConfig platform;  ///< the sensor's height, seed radius and ground preset: measured unless given
  odometry::DeskewConfig deskew;  ///< step 1: scans moved into the frame of their stamp
  odometry::LidarOdometryConfig
      lidar_odometry;  ///< step 2 when the input has no odometry (or `run --odometry lidar`)
  odometry::FloorLevellingConfig
      floor_levelling;  ///< step 2: the map's first pose when nothing gives the sensor's mount
  PrefilterConfig prefilter;
  KeyframeConfig keyframes;
  ground::GroundConfig ground;
  ground::NodeMapConfig node_map;
  walls::PlaneExtractionConfig plane_extraction;
  walls::PlaneMapperConfig plane_mapping;
  graph::GraphOptimizerConfig optimizer;
  graph::LoopClosureConfig loop_closure;
  graph::RoomLoopClosureConfig room_loop_closure;       ///< loop candidates from room re-detections
  graph::KeyframeRetirementConfig keyframe_retirement;  ///< revisits' redundant keyframes leave the graph
  ScheduleConfig schedule;
  room_layer::RoomLayerSettings rooms;  ///< free space, triggers, extraction and association (room_layer.hpp)
  DiagnosticsConfig diagnostics;
  rooms::MapWallsConfig map_walls;  ///< segment-map only: the walls of a 2-D occupancy map (map_walls.hpp)
  /// The ground keys a parameter file set ("num_min_pts", ...): the platform's preset does not
  /// replace them. Filled by load_pipeline_config; not a key itself.
  std::set<std::string> ground_keys_given;

  template <class V>
  void visit(V& v) {
    v.section(
        "platform", platform,
        "the sensor on its platform: measured from scans spread over the run unless given (docs/run.md)");
    v.section("deskew", deskew,
              "step 1, every scan with per-point times (PCD/PointCloud2 fields t, time, timestamp, "
              "offset_time; a sequence's .time files)");
    v.section("prefilter", prefilter, "step 1, every keyframe (only keyframes' clouds are used)");
    v.section("lidar_odometry", lidar_odometry,
              "step 2, every scan, when the input has no odometry (or run --odometry lidar): KISS-ICP style");
    v.section("floor_levelling", floor_levelling,
              "step 2, once, when LiDAR odometry has nothing to start from (no poses, no sensor mount)");
    v.section("keyframes", keyframes, "step 3");
    v.section("ground", ground,
              "step 4, every keyframe: tri-grid traversable ground (TRAVEL) from the robot, BGK");
    v.section("node_map", node_map, "step 4, at keyframes: the global traversable node map");
    v.section("plane_extraction", plane_extraction, "step 5, every keyframe");
    v.section("plane_mapping", plane_mapping, "step 5, association of observed planes with mapped ones");
    v.section("optimizer", optimizer, "step 9, the Ceres back-end");
    v.section("loop_closure", loop_closure, "step 9, hdl_graph_slam's rule plus a registration check");
    v.section("room_loop_closure", room_loop_closure,
              "step 9: a mapped room re-detected with its walls proposes the earlier pass's keyframes in it "
              "(graph/room_loop_closure.hpp)");
    v.section("keyframe_retirement", keyframe_retirement,
              "keyframe management: on revisits, keyframes that add nothing leave the graph "
              "(graph/keyframe_retirement.hpp)");
    v.section("schedule", schedule, "when the back-end runs");
    v.section(
        "room_layer", rooms.layer,
        "steps 6-7 at keyframes: the room layer (free space, trigger, extraction); DESIGN \"Baseline mode\"");
    v.section("free_space", rooms.free_space, "step 6: free space on traversable nodes");
    v.section("esdf_free_space", rooms.esdf, "baseline (S-Graphs+): free space from an ESDF slice");
    v.section("sight_map", rooms.sight,
              "step 6 (TS-graphs): where the rays passed at walking height over a floor (heights: "
              "free_space's obstacle_min/max_height)");
    v.section("aisle", rooms.aisle,
              "step 7: the aisle at the robot (width and direction) for the flush rule");
    v.section("room_flush", rooms.flush, "step 7: the flush rule");
    v.section("room_timer", rooms.timer, "baseline (S-Graphs+): the timer trigger");
    v.section("room_segmentation", rooms.segmentation,
              "step 7 (TS-graphs): spaces = the free space walked, cut by the mapped walls (doors closed), "
              "grown back to the walls");
    v.section("sgraphs_room_extraction", rooms.sgraphs_extraction,
              "baseline (S-Graphs+): planes paired by counting cluster points near them");
    v.section("room_association", rooms.association, "step 7: re-detections and duplicates");
    v.section("diagnostics", diagnostics, "what the run says about layers that stay empty");
    v.section("map_walls", map_walls,
              "segment-map only: the walls of a 2-D occupancy map (the straight edges of its free space)");
  }
};

/// Reads a parameter file over the defaults: every key optional, unknown or duplicate keys,
/// wrong types and non-finite numbers are InputErrors naming the file, line and key.
/// Also checks values (ranges) and throws InputError for impossible ones.
PipelineConfig load_pipeline_config(const std::string& file);
/// The same from text (for tests); `name` is used in messages.
PipelineConfig parse_pipeline_config(const std::string& text, const std::string& name);
/// The whole configuration as YAML, every key, in the order of the sections (a run folder's
/// params.yaml).
std::string dump_pipeline_config(const PipelineConfig& config);
/// The same with each key's comment and a header: config/params.yaml is this of the defaults
/// (`tsgraphs params`).
std::string documented_pipeline_config(const PipelineConfig& config);

}  // namespace tsgraphs::pipeline
