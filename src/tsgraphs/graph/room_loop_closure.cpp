#include "tsgraphs/graph/room_loop_closure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace tsgraphs::graph {

std::vector<int> room_loop_candidates(const SituationalGraph& graph, int id, const Polygon2& footprint,
                                      double min_travel, const RoomLoopClosureConfig& config) {
  if (id < 0 || id >= static_cast<int>(graph.keyframes().size()))
    throw std::out_of_range("room_loop_candidates: no keyframe " + std::to_string(id));
  const KeyframeNode& current = graph.keyframes()[static_cast<std::size_t>(id)];
  std::vector<std::pair<double, int>> inside;  // (distance, id)
  if (footprint.size() < 3) return {};
  for (int k = 0; k < id; ++k) {
    const KeyframeNode& earlier = graph.keyframes()[static_cast<std::size_t>(k)];
    if (earlier.retired || current.accum_distance - earlier.accum_distance < min_travel) continue;
    const Eigen::Vector3d& p = earlier.pose.translation();
    if (std::abs(p.z() - current.pose.translation().z()) > config.max_height_difference) continue;
    if (!contains(footprint, p.head<2>())) continue;
    inside.emplace_back((p - current.pose.translation()).norm(), k);
  }
  std::sort(inside.begin(), inside.end());
  const std::size_t n = std::min(inside.size(), static_cast<std::size_t>(std::max(config.max_candidates, 0)));
  std::vector<int> ids;
  for (std::size_t i = 0; i < n; ++i) ids.push_back(inside[i].second);
  return ids;
}

bool walls_match(const std::vector<int>& walls, const std::vector<int>& previous_walls,
                 const RoomLoopClosureConfig& config) {
  int common = 0;
  for (int w : walls) common += std::count(previous_walls.begin(), previous_walls.end(), w) > 0 ? 1 : 0;
  return common >= config.min_common_walls;
}

}  // namespace tsgraphs::graph
