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
#include "tsgraphs/odometry/floor_levelling.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"
#include "tsgraphs/odometry/sweep_registration.hpp"
#include "tsgraphs/pipeline/keyframe_selector.hpp"
#include "tsgraphs/pipeline/platform.hpp"
#include "tsgraphs/pipeline/prefilter.hpp"
#include "tsgraphs/pipeline/room_layer.hpp"
#include "tsgraphs/rooms/map_walls.hpp"
#include "tsgraphs/walls/plane_extraction.hpp"
#include "tsgraphs/walls/plane_mapper.hpp"
#include "tsgraphs/core/config_range.hpp"

namespace tsgraphs::pipeline {

/// When the back-end runs.
struct ScheduleConfig {
  int optimize_every_keyframes = 5;  ///< a local solve after this many new keyframes
  int full_every_keyframes = 50;  ///< a full solve after the graph grew by this many keyframes (retired ones
                                  ///< leave it; 0 = only after loops and at the end)
  /// A loop this many sigmas or more from the estimate asks for a full solve (the old graph has
  /// drift to correct); a nearer one is taken in by a local solve (0: every loop a full solve).
  /// Sigmas: the loop's, with the odometry's of the keyframes since the last correction when
  /// that lies in the local window (Pipeline::loop_asks_for_full_solve).
  double full_solve_loop_sigmas = 3.0;
  bool merge_duplicate_planes = true;  ///< merge landmarks found to be one face after each solve

  template <class V>
  void visit(V& v) {
    v("optimize_every_keyframes", optimize_every_keyframes, between(1, 100000));
    v("full_every_keyframes", full_every_keyframes, between(0, 100000));
    v("full_solve_loop_sigmas", full_solve_loop_sigmas, between(0.0, 1e6));
    v("merge_duplicate_planes", merge_duplicate_planes);
  }
};

/// De-skewing of scans that carry per-point times (odometry/deskew.hpp, sweep_registration.hpp).
struct DeskewConfig {
  bool enabled = true;          ///< de-skew scans with per-point times
  std::string motion = "auto";  ///< the motion during a sweep: "poses" (from the poses around the scan, or
                                ///< the LiDAR odometry's last motion), "registration" (each sweep registered
                                ///< to a map of the ones before, the motion among the unknowns), "auto"
  double max_interval_ratio =
      1.5;  ///< auto registers the sweeps when scans are farther apart than this times a
            ///< sweep's duration: the poses then do not sample the motion inside a sweep
  odometry::SweepRegistrationConfig registration;  ///< the sweep registration's fields

  template <class V>
  void visit(V& v) {
    v("enabled", enabled);
    v("motion", motion, OneOf{"auto", "poses", "registration"});
    v("max_interval_ratio", max_interval_ratio, between(1.0, 1000.0));
    registration.visit(v);
  }

  /// Throws std::invalid_argument("DeskewConfig: <key> ...") for the first field out of range.
  void validate() const;
};

/// What the pipeline says about layers that stay empty.
struct DiagnosticsConfig {
  int empty_layer_keyframes = 50;  ///< warn when no ground or wall came for this many keyframes, or a run
                                   ///< this long has no room (0: never)

  template <class V>
  void visit(V& v) {
    v("empty_layer_keyframes", empty_layer_keyframes, between(0, 1000000));
  }
};

struct PipelineConfig {
  PlatformConfig platform;  ///< the sensor's height, seed radius and ground preset: measured unless given
  DeskewConfig deskew;      ///< step 1: scans moved into the frame of their stamp
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
  RoomLayerSettings rooms;  ///< free space, triggers, extraction and association (room_layer.hpp)
  DiagnosticsConfig diagnostics;
  rooms::MapWallsConfig map_walls;  ///< segment-map only: the walls of a 2-D occupancy map (map_walls.hpp)
  /// The ground keys a parameter file set ("num_min_pts", ...): the platform's preset does not
  /// replace them. Filled by load_pipeline_config; not a key itself.
  std::set<std::string> ground_keys_given;

  template <class V>
  void visit(V& v) {
    v.section("platform", platform);
    v.section("deskew", deskew);
    v.section("prefilter", prefilter);
    v.section("lidar_odometry", lidar_odometry);
    v.section("floor_levelling", floor_levelling);
    v.section("keyframes", keyframes);
    v.section("ground", ground);
    v.section("node_map", node_map);
    v.section("plane_extraction", plane_extraction);
    v.section("plane_mapping", plane_mapping);
    v.section("optimizer", optimizer);
    v.section("loop_closure", loop_closure);
    v.section("room_loop_closure", room_loop_closure);
    v.section("keyframe_retirement", keyframe_retirement);
    v.section("schedule", schedule);
    v.section("room_layer", rooms.layer);
    v.section("free_space", rooms.free_space);
    v.section("esdf_free_space", rooms.esdf);
    v.section("sight_map", rooms.sight);
    v.section("aisle", rooms.aisle);
    v.section("room_flush", rooms.flush);
    v.section("room_timer", rooms.timer);
    v.section("room_segmentation", rooms.segmentation);
    v.section("sgraphs_room_extraction", rooms.sgraphs_extraction);
    v.section("room_association", rooms.association);
    v.section("diagnostics", diagnostics);
    v.section("map_walls", map_walls);
  }
};

/// Reads a parameter file over the defaults: every key optional, unknown or duplicate keys,
/// wrong types and non-finite numbers are InputErrors naming the file, line and key.
/// Also checks values (ranges) and throws InputError for impossible ones.
PipelineConfig load_pipeline_config(const std::string& file);
/// The same from text (for tests); `name` is used in messages.
PipelineConfig parse_pipeline_config(const std::string& text, const std::string& name);
/// The whole configuration as YAML, every key, in the order of the sections.
std::string dump_pipeline_config(const PipelineConfig& config);

}  // namespace tsgraphs::pipeline
