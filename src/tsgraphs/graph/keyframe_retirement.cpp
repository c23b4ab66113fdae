#include "tsgraphs/graph/keyframe_retirement.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

namespace tsgraphs::graph {

std::vector<Retirement> redundant_keyframes(const SituationalGraph& graph, const std::vector<int>& candidates,
                                            const KeyframeRetirementConfig& config,
                                            const std::function<bool(int)>& in_mapped_space) {
  check_config(config, "keyframe_retirement");
  const auto& keyframes = graph.keyframes();
  const int newest = static_cast<int>(keyframes.size()) - 1;
  std::vector<int> ids;
  for (int id : candidates)
    if (id > 0 && id < newest && !keyframes[id].retired) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (ids.empty()) return {};

  // Each plane's observers; a plane is held by an earlier pass when one of them that stays is
  // min_travel or more of travel before the keyframe.
  std::map<int, std::vector<int>> observers;
  std::map<int, std::vector<int>> planes_of;
  for (const PlaneEdge& e : graph.plane_edges()) {
    observers[e.plane].push_back(e.keyframe);
    if (std::binary_search(ids.begin(), ids.end(), e.keyframe)) planes_of[e.keyframe].push_back(e.plane);
  }

  // In id order, each decided against what stays: a keyframe leaving in this call neither
  // anchors a later one nor holds its planes.
  std::vector<bool> leaving(keyframes.size(), false);
  const auto stays = [&](int o) { return !keyframes[o].retired && !leaving[o]; };
  std::vector<Retirement> out;
  for (int id : ids) {
    const KeyframeNode& k = keyframes[id];
    const double earlier = k.accum_distance - config.min_travel;
    int anchor = -1;
    double nearest = std::numeric_limits<double>::infinity();
    for (int o = 0; o < id; ++o) {
      const KeyframeNode& other = keyframes[o];
      if (!stays(o) || other.accum_distance > earlier) continue;
      const double d = (other.pose.translation() - k.pose.translation()).norm();
      if (d <= config.radius && d < nearest) {
        nearest = d;
        anchor = o;
      }
    }
    if (anchor < 0) continue;
    const std::vector<int>& planes = planes_of[id];
    const bool all_held = std::all_of(planes.begin(), planes.end(), [&](int p) {
      const std::vector<int>& seen_by = observers.at(p);
      return std::any_of(seen_by.begin(), seen_by.end(),
                         [&](int o) { return stays(o) && keyframes[o].accum_distance <= earlier; });
    });
    if (!all_held) continue;
    if (config.rooms_only && !in_mapped_space(id)) continue;
    leaving[id] = true;
    out.push_back({id, anchor});
  }
  return out;
}

}  // namespace tsgraphs::graph
