#include "tsgraphs/ground/traversable_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tsgraphs::ground {

NodeLinker::NodeLinker(const TriGridField& field, double max_gap)
    : field_(field), max_gap_sq_(max_gap * max_gap), stamp_(field.nodes.size(), 0) {}

int NodeLinker::links(int node, std::vector<int>* out) {
  out->clear();
  ++call_;
  stamp_[node] = call_;
  const Eigen::Vector2d origin = field_.grid.centroid(node);
  queue_.clear();
  queue_.push_back(node);
  std::array<int, 3> adj{};
  int num_adjacent = 0;
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    if (head == 1) num_adjacent = static_cast<int>(out->size());
    const int count = field_.grid.adjacent(queue_[head], &adj);
    for (int k = 0; k < count; ++k) {
      const int b = adj[k];
      if (stamp_[b] == call_) continue;
      stamp_[b] = call_;
      const bool adjacent_to_start = head == 0;
      if (!adjacent_to_start && (field_.grid.centroid(b) - origin).squaredNorm() > max_gap_sq_) continue;
      const NodeState state = field_.nodes[b].state;
      if (state != NodeState::kEmpty) out->push_back(b);
      // Runs continue through nodes without a plane; a modelled node ends them.
      if (state != NodeState::kModelled) queue_.push_back(b);
    }
  }
  return queue_.size() == 1 ? static_cast<int>(out->size()) : num_adjacent;
}

std::vector<int> find_seed_nodes(const TriGridField& field, const GroundConfig& config) {
  std::vector<int> seeds;
  const double radius_sq = config.seed_radius * config.seed_radius;
  for (int k = 0; k < static_cast<int>(field.nodes.size()); ++k) {
    const TriGridNode& node = field.nodes[k];
    if (!node.ground_like) continue;
    if (node.centre.head<2>().cast<double>().squaredNorm() > radius_sq) continue;
    const double under_robot = node.height_at(0.0f, 0.0f);
    if (std::abs(under_robot + config.sensor_height) <= config.seed_height_tolerance) seeds.push_back(k);
  }
  return seeds;
}

bool locally_convex(const TriGridNode& a, const TriGridNode& b, const GroundConfig& config) {
  const Eigen::Vector3f d = b.centre - a.centre;
  const double dmu = d.norm();
  if (a.normal.dot(b.normal) < 1.0 - std::sin(dmu * config.th_lcc_normal)) return false;
  const double tolerance = std::min(dmu * std::sin(config.th_lcc_planar), config.th_dist);
  return std::abs(a.normal.dot(d)) <= tolerance && std::abs(b.normal.dot(d)) <= tolerance;
}

std::vector<std::uint8_t> search_traversable(const TriGridField& field, const std::vector<int>& seeds,
                                             const GroundConfig& config) {
  return flood_from(
      field, seeds, config.max_gap, [&](int i) { return field.nodes[i].ground_like; },
      [&](int a, int b) { return locally_convex(field.nodes[a], field.nodes[b], config); });
}

}  // namespace tsgraphs::ground
