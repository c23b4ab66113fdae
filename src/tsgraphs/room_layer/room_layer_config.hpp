#pragma once
/// The room layer's own fields (room_layer.hpp): which free space and which trigger (TS-graphs,
/// S-Graphs+ or an ablation), and how levels are told apart.
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::room_layer {

/// Where rooms are segmented from.
enum class FreeSpaceMethod {
  traversable,  ///< TS-graphs: the traversable nodes and what the rays saw over them
  esdf          ///< S-Graphs+: an ESDF slice of the latest keyframes' points
};
inline const Choices<FreeSpaceMethod> kFreeSpaceMethods{{FreeSpaceMethod::traversable, "traversable"},
                                                        {FreeSpaceMethod::esdf, "esdf"}};

/// When a room is extracted.
enum class RoomTrigger {
  flush,  ///< TS-graphs: when the aisle walked changes (rooms/room_flush_trigger.hpp)
  timer   ///< S-Graphs+: every room_timer.period_s
};
inline const Choices<RoomTrigger> kRoomTriggers{{RoomTrigger::flush, "flush"}, {RoomTrigger::timer, "timer"}};

struct RoomLayerConfig {
  FreeSpaceMethod free_space_method = FreeSpaceMethod::traversable;
  RoomTrigger room_trigger = RoomTrigger::flush;
  double free_space_radius = 8.0;
  int obstacle_keyframes = 5;
  double level_tolerance = 1.5;
  double obstacle_voxel = 0.2;
  double segment_radius = 2.5;
  double min_segment_length = 2.0;
  double min_visit_length = 1.0;
  double max_frontier = 0.1;
  double level_band = 0.3;
  double max_floor_slope = 0.05;
  double floor_window = 2.0;

  template <class V>
  void visit(V& v) {
    v("free_space_method", free_space_method, kFreeSpaceMethods,
      "traversable (TS-graphs) or esdf (S-Graphs+: ESDF free space, planes paired by counting, centre "
      "association)");
    v("room_trigger", room_trigger, kRoomTriggers,
      "flush (TS-graphs) or timer (S-Graphs+, every room_timer.period_s)");
    v("free_space_radius", free_space_radius, above(0.0, 100.0),
      "free space is computed within this of the robot (m)");
    v("obstacle_keyframes", obstacle_keyframes, between(1, 1000),
      "obstacle points come from the clouds of this many latest keyframes");
    v("level_tolerance", level_tolerance, above(0.0, 100.0),
      "floors within this height of a known level belong to it (m)");
    v("obstacle_voxel", obstacle_voxel, between(0.01, 10.0),
      "obstacle candidate points are thinned to this (m)");
    v("segment_radius", segment_radius, between(0.0, 1000.0),
      "flush: only the cluster's vertices this near the robot along the free space join the segment (m): the "
      "aisle it walks, not everything in view");
    v("min_segment_length", min_segment_length, between(0.0, 1000.0),
      "flush: a segment walked less than this (a corner, a doorway passed through) is not extracted but "
      "carried into the next one (m)");
    v("min_visit_length", min_visit_length, between(0.0, 1000.0),
      "flush: a space the segment's path runs this far in is extracted (m); a step through a doorway is no "
      "visit");
    v("max_frontier", max_frontier, between(0.0, 1.0),
      "flush: a space more than this share of whose edge borders the unseen waits for a later flush (or the "
      "end): its footprint is still growing");
    v("level_band", level_band, between(0.0, 100.0),
      "flush: ground within this height of the walked floor is the level's (m): steps, not a ramp's rise");
    v("max_floor_slope", max_floor_slope, above(0.0, 100.0),
      "a level's floor rises less than this per metre walked (1:20, where building codes call a walk a "
      "ramp); steeper: ramp or stairs, between levels; steeper ground round a node (a ramp's foot) is no "
      "floor of the level");
    v("floor_window", floor_window, above(0.0, 1000.0),
      "the floor's rise is measured over this much of the path, the ground's over this square round a node "
      "(m)");
  }
};

}  // namespace tsgraphs::room_layer
