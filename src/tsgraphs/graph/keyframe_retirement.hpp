#pragma once
/// Keyframe retirement (keyframe management, S-Graphs 2.0's idea): on a revisit, a keyframe
/// that adds no information leaves the optimisation, so that the graph grows with the
/// building, not with the length of the run. A keyframe is redundant when
///   - a keyframe of an earlier pass (at least min_travel back) that is kept lies within
///     `radius` of it: that pass already has a keyframe here (radius is about the keyframe
///     spacing, keyframes.delta_trans, so the earlier pass would have made none here either);
///   - every plane it observes is observed by a kept keyframe of an earlier pass: it saw no
///     wall the map does not hold;
///   - with rooms_only, it stands inside a mapped room or corridor: the room's factor holds
///     those walls together, so the keyframe's view of them is what the map already says.
/// SituationalGraph::retire_keyframe folds it out: its plane edges are dropped, its odometry
/// and loop edges composed into its neighbours' (a documented sparsification: the estimate moves
/// by at most what tests/test_keyframe_retirement.cpp bounds), and its pose follows the nearest
/// such kept keyframe (its anchor). The newest keyframe is never retired.
#include <functional>
#include <vector>

#include "tsgraphs/graph/situational_graph.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::graph {

struct KeyframeRetirementConfig {
  bool enabled = true;
  double radius = 1.0;
  double min_travel = 8.0;
  bool rooms_only = true;

  template <class V>
  void visit(V& v) {
    v("enabled", enabled,
      "retire a keyframe near a kept one of an earlier pass that saw no wall the map lacks");
    v("radius", radius, above(0.0, 1000.0),
      "m; the kept keyframe of the earlier pass is this near (the keyframe spacing, keyframes.delta_trans)");
    v("min_travel", min_travel, above(0.0, 1e6),
      "m travelled since that pass (loop_closure.min_travel's rule)");
    v("rooms_only", rooms_only,
      "only inside a mapped room or corridor, whose factor holds its walls together");
  }
};

/// A keyframe to retire and the keyframe its pose then follows.
struct Retirement {
  int keyframe = -1;
  int anchor = -1;
};

/// The redundant keyframes among `candidates` (ids, any order; retired ones, the first and the
/// newest are skipped), decided and returned in id order: a keyframe returned neither anchors
/// nor holds the planes of a later one, so the list can be retired in its order.
/// `in_mapped_space(k)` says whether keyframe k stands in a mapped room or corridor (asked only
/// with rooms_only). Throws std::invalid_argument for a radius or min_travel that is not positive.
std::vector<Retirement> redundant_keyframes(const SituationalGraph& graph, const std::vector<int>& candidates,
                                            const KeyframeRetirementConfig& config,
                                            const std::function<bool(int)>& in_mapped_space);

}  // namespace tsgraphs::graph
