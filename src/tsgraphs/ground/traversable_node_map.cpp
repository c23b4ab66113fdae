#include "tsgraphs/ground/traversable_node_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "tsgraphs/core/voxel_key.hpp"

namespace tsgraphs::ground {

namespace {

/// Unit weighted mean of two normals; `b` is flipped onto `a`'s side first, since a surface
/// normal seen from two poses may come with either sign.
Eigen::Vector3d mean_normal(const Eigen::Vector3d& a, double wa, const Eigen::Vector3d& b, double wb) {
  const Eigen::Vector3d sum = wa * a + (a.dot(b) < 0.0 ? -wb : wb) * b;
  const double norm = sum.norm();
  return norm > 0.0 ? Eigen::Vector3d(sum / norm) : a;
}

/// Drops the oldest entries beyond `cap` (a negative cap keeps none).
void keep_most_recent(std::vector<int>& keyframes, int cap) {
  const auto n = static_cast<std::size_t>(std::max(cap, 0));
  if (keyframes.size() > n)
    keyframes.erase(keyframes.begin(), keyframes.end() - static_cast<std::ptrdiff_t>(n));
}

/// p expressed in the frame of T (T^-1 p), without forming the inverse.
Eigen::Vector3d to_frame(const Pose3& T, const Eigen::Vector3d& p) {
  return T.linear().transpose() * (p - T.translation());
}

}  // namespace

TraversableNodeMap::TraversableNodeMap(NodeMapConfig config) : config_(std::move(config)) {
  check_config(config_, "TraversableNodeMap");
}

std::uint64_t TraversableNodeMap::cell_key(const Eigen::Vector3d& p) const {
  return tsgraphs::cell_key(static_cast<std::int64_t>(std::floor(p.x() / config_.cell_size)),
                            static_cast<std::int64_t>(std::floor(p.y() / config_.cell_size)));
}

int TraversableNodeMap::find_layer(std::uint64_t key, double z) const {
  const auto it = cells_.find(key);
  if (it == cells_.end()) return -1;
  int best = -1;  // nodes_ is in id order: the lower index is the lower id
  double best_dz = 0.0;
  for (int i = it->second; i >= 0; i = next_in_cell_[i]) {
    const double dz = std::abs(nodes_[i].position.z() - z);
    if (dz > config_.level_tolerance) continue;
    if (best < 0 || dz < best_dz || (dz == best_dz && i < best)) {
      best = i;
      best_dz = dz;
    }
  }
  return best;
}

void TraversableNodeMap::add_to_cell(int index, std::uint64_t key) {
  const auto [it, inserted] = cells_.try_emplace(key, index);
  next_in_cell_[index] = inserted ? -1 : it->second;
  it->second = index;
}

void TraversableNodeMap::note_keyframe(GlobalNode& node, int keyframe_id) const {
  std::vector<int>& kfs = node.keyframes;
  if (!kfs.empty() && kfs.back() == keyframe_id) return;
  kfs.erase(std::remove(kfs.begin(), kfs.end(), keyframe_id), kfs.end());
  kfs.push_back(keyframe_id);
  keep_most_recent(kfs, config_.max_keyframes_per_node);
}

void TraversableNodeMap::merge(GlobalNode& keep, const GlobalNode& gone) const {
  const Pose3& T_map_anchor = keyframes_.at(keep.anchor_keyframe).pose;
  const double wk = keep.observations, wg = gone.observations, w = wk + wg;
  const Eigen::Vector3d position = (wk * keep.position + wg * gone.position) / w;
  keep.local = to_frame(T_map_anchor, position);
  keep.position = T_map_anchor * keep.local;
  keep.normal = mean_normal(keep.normal, wk, gone.normal, wg);
  keep.local_normal = T_map_anchor.linear().transpose() * keep.normal;
  keep.probability = (wk * keep.probability + wg * gone.probability) / w;
  keep.observations += gone.observations;

  // Both lists hold keyframes given to fuse(); order them by when they were last fused.
  std::vector<int> kfs = keep.keyframes;
  kfs.insert(kfs.end(), gone.keyframes.begin(), gone.keyframes.end());
  std::sort(kfs.begin(), kfs.end(),
            [&](int a, int b) { return keyframes_.at(a).fused_at < keyframes_.at(b).fused_at; });
  kfs.erase(std::unique(kfs.begin(), kfs.end()), kfs.end());
  keep_most_recent(kfs, config_.max_keyframes_per_node);
  keep.keyframes = std::move(kfs);
}

void TraversableNodeMap::fuse(int keyframe_id, const Pose3& T_map_keyframe,
                              const std::vector<NodeObservation>& nodes) {
  const auto known = keyframes_.find(keyframe_id);
  if (known != keyframes_.end() && known->second.pose.matrix() != T_map_keyframe.matrix()) {
    update([&](int id) { return id == keyframe_id ? T_map_keyframe : keyframes_.at(id).pose; });
  }
  KeyframeRecord& record = keyframes_[keyframe_id];
  record.pose = T_map_keyframe;
  record.fused_at = ++fuse_calls_;

  for (const NodeObservation& obs : nodes) {
    if (!(obs.probability >= config_.min_probability) || !obs.position.allFinite() ||
        !obs.normal.allFinite()) {
      continue;
    }
    const double normal_norm = obs.normal.norm();
    if (!(normal_norm > 0.0)) continue;
    const Eigen::Vector3d position = T_map_keyframe * obs.position;
    const Eigen::Vector3d normal = T_map_keyframe.linear() * obs.normal / normal_norm;
    const std::uint64_t key = cell_key(position);
    const int index = find_layer(key, position.z());

    if (index < 0) {  // a new cell or layer: a node anchored at this keyframe
      GlobalNode node;
      node.id = next_id_++;
      node.anchor_keyframe = keyframe_id;
      node.local = obs.position;
      node.local_normal = obs.normal / normal_norm;
      node.position = position;
      node.normal = normal;
      node.probability = obs.probability;
      node.observations = 1;
      note_keyframe(node, keyframe_id);
      nodes_.push_back(std::move(node));
      next_in_cell_.push_back(-1);
      add_to_cell(static_cast<int>(nodes_.size()) - 1, key);
      continue;
    }

    // Running means in the anchor's frame, so the node keeps moving with its anchor.
    GlobalNode& node = nodes_[index];
    const Pose3& T_map_anchor = keyframes_.at(node.anchor_keyframe).pose;
    const double w = node.observations;
    node.local = (w * node.local + to_frame(T_map_anchor, position)) / (w + 1.0);
    node.local_normal = mean_normal(node.local_normal, w, T_map_anchor.linear().transpose() * normal, 1.0);
    node.position = T_map_anchor * node.local;
    node.normal = T_map_anchor.linear() * node.local_normal;
    node.probability = (w * node.probability + obs.probability) / (w + 1.0);
    ++node.observations;
    note_keyframe(node, keyframe_id);
  }
}

void TraversableNodeMap::update(const std::function<Pose3(int)>& keyframe_pose) {
  for (auto& [id, record] : keyframes_) record.pose = keyframe_pose(id);

  // Re-hash in id order, so a node that lands on an existing layer merges into the lower id;
  // the survivors are compacted to the front, so storage does not grow with merges.
  cells_.clear();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    GlobalNode& node = nodes_[i];
    const Pose3& T_map_anchor = keyframes_.at(node.anchor_keyframe).pose;
    node.position = T_map_anchor * node.local;
    node.normal = T_map_anchor.linear() * node.local_normal;
    const std::uint64_t key = cell_key(node.position);
    const int other = find_layer(key, node.position.z());
    if (other >= 0) {
      merge(nodes_[static_cast<std::size_t>(other)], node);
      continue;
    }
    if (kept != i) nodes_[kept] = std::move(node);
    add_to_cell(static_cast<int>(kept), key);
    ++kept;
  }
  nodes_.resize(kept);
  next_in_cell_.resize(kept);
}

std::vector<const GlobalNode*> TraversableNodeMap::nodes_near(const Eigen::Vector3d& p, double radius) const {
  std::vector<std::pair<double, int>> found;  // (squared horizontal distance, index: in id order)
  const double r2 = radius * radius;
  auto consider = [&](int i) {
    const GlobalNode& node = nodes_[static_cast<std::size_t>(i)];
    if (std::abs(node.position.z() - p.z()) > config_.level_tolerance) return;
    const double d2 = (node.position.head<2>() - p.head<2>()).squaredNorm();
    if (d2 <= r2) found.emplace_back(d2, i);
  };

  if (radius >= 0.0 && p.allFinite()) {
    const double cs = config_.cell_size;
    const double x0 = std::floor((p.x() - radius) / cs), x1 = std::floor((p.x() + radius) / cs);
    const double y0 = std::floor((p.y() - radius) / cs), y1 = std::floor((p.y() + radius) / cs);
    if ((x1 - x0 + 1.0) * (y1 - y0 + 1.0) > static_cast<double>(nodes_.size())) {
      for (std::size_t i = 0; i < nodes_.size(); ++i)
        consider(static_cast<int>(i));  // cheaper than the cells
    } else {
      for (auto ix = static_cast<std::int64_t>(x0); ix <= static_cast<std::int64_t>(x1); ++ix) {
        for (auto iy = static_cast<std::int64_t>(y0); iy <= static_cast<std::int64_t>(y1); ++iy) {
          const auto it = cells_.find(tsgraphs::cell_key(ix, iy));
          if (it == cells_.end()) continue;
          for (int i = it->second; i >= 0; i = next_in_cell_[i]) consider(i);
        }
      }
    }
  }

  std::sort(found.begin(), found.end());
  std::vector<const GlobalNode*> out;
  out.reserve(found.size());
  for (const auto& [d2, i] : found) out.push_back(&nodes_[static_cast<std::size_t>(i)]);
  return out;
}

std::vector<const GlobalNode*> TraversableNodeMap::nodes_in_height_range(double z_min, double z_max) const {
  std::vector<const GlobalNode*> out;
  for (const GlobalNode& node : nodes_) {
    if (node.position.z() >= z_min && node.position.z() <= z_max) out.push_back(&node);
  }
  return out;
}

std::vector<const GlobalNode*> TraversableNodeMap::nodes() const {
  std::vector<const GlobalNode*> out;
  out.reserve(nodes_.size());
  for (const GlobalNode& node : nodes_) out.push_back(&node);
  return out;
}

const GlobalNode* TraversableNodeMap::node(int id) const {
  // nodes_ is in id order: binary search.
  const auto it = std::lower_bound(nodes_.begin(), nodes_.end(), id,
                                   [](const GlobalNode& n, int value) { return n.id < value; });
  return it != nodes_.end() && it->id == id ? &*it : nullptr;
}

}  // namespace tsgraphs::ground
