#pragma once
/// Room-based loop closure (after TACS-Graphs' CoSG-LCD: loops from the consistent room layer):
/// when the room layer re-detects a mapped room with walls it had before, the kept keyframes
/// of an earlier pass that stood in that room are the loop candidates of the keyframe that
/// re-detected it, nearest first. LoopDetector::verify registers them as it does the
/// distance rule's. The room says where the earlier pass saw what this keyframe sees, however
/// far the estimates have drifted apart within it; the distance rule needs them within
/// loop_closure.max_distance.
#include <vector>

#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/graph/situational_graph.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::graph {

struct RoomLoopClosureConfig {
  bool enabled = true;
  int max_candidates = 3;
  int min_common_walls = 2;
  double max_height_difference = 1.0;

  template <class V>
  void visit(V& v) {
    v("enabled", enabled,
      "tried before the distance rule at the keyframe that re-detected it; verified by loop_closure's "
      "registration and checks");
    v("max_candidates", max_candidates, between(1, 100), "keyframes in the room registered, nearest first");
    v("min_common_walls", min_common_walls, between(1, 4),
      "walls the re-detection shares with the room's previous extraction");
    v("max_height_difference", max_height_difference, above(0.0, 1000.0),
      "m; candidates on the room's level (storeys are >= 2.5 m apart)");
  }
};

/// Kept keyframes at least `min_travel` m of travel before keyframe `id` whose x-y lies in the
/// room's `footprint` (map frame) and whose height is within max_height_difference of
/// keyframe `id`'s, nearest to it first (ties by id), at most max_candidates.
std::vector<int> room_loop_candidates(const SituationalGraph& graph, int id, const Polygon2& footprint,
                                      double min_travel, const RoomLoopClosureConfig& config);

/// Whether a re-detection bounded by `walls` shares min_common_walls with `previous_walls`,
/// the walls of the room's previous extraction.
bool walls_match(const std::vector<int>& walls, const std::vector<int>& previous_walls,
                 const RoomLoopClosureConfig& config);

}  // namespace tsgraphs::graph
