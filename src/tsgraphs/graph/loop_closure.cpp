#include "tsgraphs/graph/loop_closure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace tsgraphs::graph {
namespace {

const KeyframeNode& keyframe_at(const SituationalGraph& graph, int id) {
  if (id < 0 || id >= static_cast<int>(graph.keyframes().size()))
    throw std::out_of_range("LoopDetector: no keyframe " + std::to_string(id));
  return graph.keyframes()[static_cast<std::size_t>(id)];
}

// Prepared clouds kept between keyframes: a keyframe's candidates (max_candidates from each
// proposer) are mostly its predecessor's. ~0.75 MB each for an os1-64 keyframe at the default
// voxel; 8 saved as much time as 32 on the built-in atrium for 18 MB less peak memory.
constexpr std::size_t kPreparedKept = 8;

}  // namespace

LoopDetector::LoopDetector(LoopClosureConfig config) : config_(std::move(config)) {}

std::vector<int> LoopDetector::candidates(const SituationalGraph& graph, int id) const {
  const KeyframeNode& current = keyframe_at(graph, id);
  std::vector<std::pair<double, int>> near;  // (distance, id)
  for (int k = 0; k < id; ++k) {
    const KeyframeNode& earlier = graph.keyframes()[static_cast<std::size_t>(k)];
    if (earlier.retired) continue;  // out of the graph, and its cloud is gone
    // Far back in travel: odometry alone has had time to drift, so a match is worth a factor.
    if (std::abs(current.accum_distance - earlier.accum_distance) < config_.min_travel) continue;
    const double distance = (current.pose.translation() - earlier.pose.translation()).norm();
    if (distance < config_.max_distance) near.emplace_back(distance, k);
  }
  // Nearest first; equal distances by id, so the order never depends on the sort.
  std::sort(near.begin(), near.end());
  const std::size_t n = std::min(near.size(), static_cast<std::size_t>(std::max(config_.max_candidates, 0)));
  std::vector<int> ids;
  ids.reserve(n);
  for (std::size_t i = 0; i < n; ++i) ids.push_back(near[i].second);
  return ids;
}

std::optional<BetweenEdge> LoopDetector::detect(const SituationalGraph& graph, int id,
                                                const std::function<const PointCloud&(int)>& cloud_of) {
  const KeyframeNode& current = keyframe_at(graph, id);
  if (current.accum_distance - last_loop_travel_ < config_.min_loop_interval) return std::nullopt;
  return verify(graph, id, candidates(graph, id), cloud_of);
}

std::optional<BetweenEdge> LoopDetector::verify(const SituationalGraph& graph, int id, const std::vector<int>& candidates,
                                                const std::function<const PointCloud&(int)>& cloud_of) {
  const KeyframeNode& current = keyframe_at(graph, id);
  for (const int k : candidates) {
    const KeyframeNode& earlier = keyframe_at(graph, k);
    if (earlier.retired || k == id) continue;
    const Pose3 guess = earlier.pose.inverse() * current.pose;  // T_k_id from the current estimates
    const registration::PreparedCloud& source = prepared(id, cloud_of);
    const registration::RegistrationResult r =
        registration::register_clouds(source, prepared(k, cloud_of), guess, config_.registration);
    if (!r.converged || r.fitness > config_.max_fitness || r.inlier_ratio < config_.min_inlier_ratio) continue;
    // Surfaces that leave a direction free let GICP slide along it (a corridor's length).
    if (r.weakest_direction_share < config_.min_facing_share) continue;
    // A large correction means GICP slid to another optimum (a corridor's length, a twin room).
    const double correction = (r.T_target_source.translation() - guess.translation()).norm();
    if (correction > config_.max_correction) continue;
    // Last, as it costs a second registration: the same pair the other way round must find the same match.
    const registration::RegistrationResult back =
        registration::register_clouds(prepared(k, cloud_of), source, guess.inverse(), config_.registration);
    if (!back.converged ||
        (r.T_target_source * back.T_target_source).translation().norm() > config_.max_reverse_disagreement)
      continue;

    last_loop_travel_ = current.accum_distance;
    BetweenEdge edge;
    edge.from = k;
    edge.to = id;
    edge.measurement = r.T_target_source;
    edge.fitness = r.fitness;
    return edge;
  }
  return std::nullopt;
}

const registration::PreparedCloud& LoopDetector::prepared(int k,
                                                         const std::function<const PointCloud&(int)>& cloud_of) {
  ++uses_;
  auto it = prepared_.find(k);
  if (it != prepared_.end()) {
    it->second.last_use = uses_;
    return it->second.cloud;
  }
  if (prepared_.size() >= kPreparedKept) {
    // Drop the least recently used (never the source of the current verify: it was asked for
    // just before its candidates).
    const auto oldest = std::min_element(prepared_.begin(), prepared_.end(), [](const auto& a, const auto& b) {
      return a.second.last_use < b.second.last_use;
    });
    prepared_.erase(oldest);
  }
  Prepared& made = prepared_[k];
  made.cloud = registration::prepare_cloud(cloud_of(k), config_.registration);
  made.last_use = uses_;
  return made.cloud;
}

}  // namespace tsgraphs::graph
