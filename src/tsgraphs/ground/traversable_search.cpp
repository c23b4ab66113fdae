#include "tsgraphs/ground/traversable_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tsgraphs::ground {

double link_gap(double range, const GroundConfig& config) {
  const double spacing = config.ring_spacing_deg * M_PI / 180.0;
  const double next_ring_elevation = std::atan2(config.sensor_height, range) - spacing;
  if (!(next_ring_elevation > 0.0)) return config.max_gap;  // no ring meets the floor farther out...
  const double next_ring = config.sensor_height / std::tan(next_ring_elevation);
  if (next_ring > config.max_range) return config.max_gap;  // nor within the field
  return std::max(config.max_gap, next_ring - range + config.resolution);
}

NodeLinker::NodeLinker(const TriGridField& field, const GroundConfig& config)
    : field_(field), config_(config), stamp_(field.nodes.size(), 0) {}

int NodeLinker::links(int node, std::vector<int>* out) {
  out->clear();
  ++call_;
  stamp_[node] = call_;
  const Eigen::Vector2d origin = field_.grid.centroid(node);
  const double gap = link_gap(origin.norm(), config_);
  const double gap_sq = gap * gap;
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
      if (!adjacent_to_start && (field_.grid.centroid(b) - origin).squaredNorm() > gap_sq) continue;
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
    const double distance_sq = node.centre.head<2>().cast<double>().squaredNorm();
    if (distance_sq > radius_sq) continue;
    // Ground the robot could stand on: no steeper than the steepest ramp, and no higher or lower
    // than such a ramp from its floor could take it. A box top's edge, its plane tipped 13-18
    // degrees by the box's side, carried to the robot, would otherwise pass.
    if (node.normal.head<2>().norm() > config.seed_max_slope * node.normal.z()) continue;
    const double rise = std::abs(node.centre.z() + config.sensor_height);
    if (rise > config.seed_height_tolerance + config.seed_max_slope * std::sqrt(distance_sq)) continue;
    // A face's foot has the prior's tilt, so its plane carried to the robot says nothing: the
    // face of a void's far edge, a ring below the floor, would pass. It is a seed only at the
    // floor's level where it stands.
    if (node.face_foot && rise > config.th_dist) continue;
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

bool adopt_plane(const TriGridField& field, const TriGridNode& from, int to, const GroundConfig& config,
                 TriGridNode* out) {
  const TriGridNode& node = field.nodes[to];
  if (node.state == NodeState::kEmpty || node.num_points < config.sparse_min_pts) return false;
  // Level with from's centre, not along from's plane: a plane fitted to one far ring is tilted
  // by a degree or two, which over a link of max_gap moves it by more than th_dist.
  const float level = from.centre.z();
  const float band = static_cast<float>(config.th_dist);
  // Nothing below the level in the node or the nodes sharing an edge with it: a drop, a void's
  // edge, a stair down, the top of a low wall with the ground falling away beside it.
  const auto below = [&](int n) {
    for (int k = field.node_begin[n]; k < field.node_begin[n + 1]; ++k)
      if (field.points[field.node_points[k]].z() < level - band) return true;
    return false;
  };
  std::array<int, 3> adjacent{};
  const int num_adjacent = field.grid.adjacent(to, &adjacent);
  if (below(to)) return false;
  for (int a = 0; a < num_adjacent; ++a)
    if (below(adjacent[a])) return false;
  int in_band = 0, above = 0;
  for (int k = field.node_begin[to]; k < field.node_begin[to + 1]; ++k) {
    const float d = field.points[field.node_points[k]].z() - level;
    if (d <= band) {
      ++in_band;
    } else if (d <= config.th_seeds) {
      ++above;  // something standing on the floor (a ceiling far above does not count)
    }
  }
  if (in_band < config.sparse_min_pts || above > in_band) return false;
  *out = node;
  out->state = NodeState::kModelled;
  out->ground_like = true;
  out->num_inliers = in_band;
  out->normal = Eigen::Vector3f::UnitZ();
  out->centre.z() = level;  // not its points' mean: a chain of adoptions must not climb a wall's foot
  return true;
}

std::vector<std::uint8_t> search_traversable(TriGridField* field, const std::vector<int>& seeds,
                                             const GroundConfig& config) {
  const TriGridField& f = *field;
  // An adopted node's plane is the level it continues, not a fit to its points: what it
  // reaches, it reaches by adoption too, never by the convexity test against that level.
  std::vector<std::uint8_t> adopted(f.nodes.size(), 0);
  TriGridNode plane;
  return flood_from(
      f, seeds, config, [&](int i) { return f.nodes[i].state != NodeState::kEmpty; },
      [&](int a, int b) {
        if (!adopted[a] && f.nodes[b].ground_like && locally_convex(f.nodes[a], f.nodes[b], config))
          return true;
        if (!adopt_plane(f, f.nodes[a], b, config, &plane)) return false;
        // flood_from asks link_ok last: a true answer reaches b. From now on b is a modelled
        // node, so runs of empty or unknown nodes end at it as at any other.
        field->nodes[b] = plane;
        adopted[b] = 1;
        return true;
      });
}

}  // namespace tsgraphs::ground
