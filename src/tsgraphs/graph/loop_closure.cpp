#include "tsgraphs/graph/loop_closure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

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

// f(0) ... f(n - 1) on the threads free for them. Isolated: a caller running inside a pipeline
// stage (sequence_runner.cpp) must not take up another stage's work while it waits for these.
template <class F>
void side_by_side(std::size_t n, const F& f) {
  tbb::this_task_arena::isolate([&] { tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) { f(i); }); });
}

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

std::optional<BetweenEdge> LoopDetector::verify(const SituationalGraph& graph, int id,
                                                const std::vector<int>& candidates,
                                                const std::function<const PointCloud&(int)>& cloud_of) {
  const KeyframeNode& current = keyframe_at(graph, id);
  std::vector<int> ks;
  for (const int k : candidates) {
    if (keyframe_at(graph, k).retired || k == id) continue;
    ks.push_back(k);
  }
  if (ks.empty()) return std::nullopt;
  // The clouds (from the cache, or prepared side by side), then every candidate's registration
  // side by side: most keyframes' candidates all fail, and the first that passes is the one
  // trying them one after another would find.
  std::vector<int> ids = ks;
  ids.push_back(id);
  std::vector<registration::PreparedCloud> targets = prepared(ids, cloud_of);
  const registration::PreparedCloud source = targets.back();
  targets.pop_back();
  std::vector<Pose3> guesses;
  for (const int k : ks) guesses.push_back(keyframe_at(graph, k).pose.inverse() * current.pose);  // T_k_id
  std::vector<registration::RegistrationResult> results(ks.size());
  side_by_side(ks.size(), [&](std::size_t i) {
    results[i] = registration::register_clouds(source, targets[i], guesses[i], config_.registration);
  });
  for (std::size_t i = 0; i < ks.size(); ++i) {
    const Pose3& guess = guesses[i];
    const registration::RegistrationResult& r = results[i];
    if (!r.converged || r.fitness > config_.max_fitness || r.inlier_ratio < config_.min_inlier_ratio)
      continue;
    // Surfaces that leave a direction free let GICP slide along it (a corridor's length).
    if (r.weakest_direction_share < config_.min_facing_share) continue;
    // A large correction means GICP slid to another optimum (a corridor's length, a twin room).
    const double correction = (r.T_target_source.translation() - guess.translation()).norm();
    if (correction > config_.max_correction) continue;
    // Last, as it costs a second registration: the same pair the other way round must find the same match.
    const registration::RegistrationResult back =
        registration::register_clouds(targets[i], source, guess.inverse(), config_.registration);
    if (!back.converged ||
        (r.T_target_source * back.T_target_source).translation().norm() > config_.max_reverse_disagreement)
      continue;

    last_loop_travel_ = current.accum_distance;
    BetweenEdge edge;
    edge.from = ks[i];
    edge.to = id;
    edge.measurement = r.T_target_source;
    edge.fitness = r.fitness;
    return edge;
  }
  return std::nullopt;
}

std::vector<registration::PreparedCloud> LoopDetector::prepared(
    const std::vector<int>& ids, const std::function<const PointCloud&(int)>& cloud_of) {
  std::vector<registration::PreparedCloud> out(ids.size());
  std::vector<std::size_t> missing;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto it = prepared_.find(ids[i]);
    if (it == prepared_.end()) {
      missing.push_back(i);
    } else {
      it->second.last_use = ++uses_;
      out[i] = it->second.cloud;
    }
  }
  side_by_side(missing.size(), [&](std::size_t j) {
    out[missing[j]] = registration::prepare_cloud(cloud_of(ids[missing[j]]), config_.registration);
  });
  for (const std::size_t i : missing) {
    if (prepared_.size() >= kPreparedKept) {
      // Drop the least recently used.
      const auto oldest = std::min_element(
          prepared_.begin(), prepared_.end(),
          [](const auto& a, const auto& b) { return a.second.last_use < b.second.last_use; });
      prepared_.erase(oldest);
    }
    prepared_[ids[i]] = {out[i], ++uses_};
  }
  return out;
}

}  // namespace tsgraphs::graph
