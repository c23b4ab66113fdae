#include "tsgraphs/walls/plane_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "tsgraphs/core/voxel_key.hpp"

namespace tsgraphs::walls {
namespace {

Eigen::Array3i cell_of(const Eigen::Vector3f& p, double inv_size) {
  return (p.cast<double>() * inv_size).array().floor().cast<int>();
}

// Smallest cell of a hash (m): keeps cell keys finite for a zero radius or voxel.
constexpr double kMinCell = 1e-3;

// Angle between two unit normals, robust near zero (acos is not).
double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

Eigen::Vector3d centroid_of(const std::vector<Eigen::Vector3f>& pts) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& p : pts) c += p.cast<double>();
  return pts.empty() ? c : Eigen::Vector3d(c / static_cast<double>(pts.size()));
}

std::vector<Eigen::Vector3f> transform_points(const std::vector<Eigen::Vector3f>& pts, const Pose3& T) {
  const Eigen::Isometry3f Tf = T.cast<float>();
  std::vector<Eigen::Vector3f> out;
  out.reserve(pts.size());
  for (const Eigen::Vector3f& p : pts) out.push_back(Tf * p);
  return out;
}

// Share of `pts` that lie within the hash's radius of one of its points. (Templates only
// because the hash is PlaneMapper's private type.)
template <class Hash>
double overlap_ratio(const std::vector<Eigen::Vector3f>& pts, const Hash& hash) {
  if (pts.empty()) return 0.0;
  std::size_t hits = 0;
  for (const Eigen::Vector3f& p : pts) hits += hash.any_within(p) ? 1 : 0;
  return static_cast<double>(hits) / static_cast<double>(pts.size());
}

template <class Hash>
bool any_within(const std::vector<Eigen::Vector3f>& pts, const Hash& hash) {
  return std::any_of(pts.begin(), pts.end(), [&](const Eigen::Vector3f& p) { return hash.any_within(p); });
}

}  // namespace

PlaneMapper::PointHash::PointHash(const std::vector<Eigen::Vector3f>& pts, double radius)
    : inv_(1.0 / std::max(radius, kMinCell)), r2_(static_cast<float>(radius * radius)) {
  for (const Eigen::Vector3f& p : pts) add(p);
}

void PlaneMapper::PointHash::add(const Eigen::Vector3f& p) { cells_[voxel_key(p, inv_)].push_back(p); }

bool PlaneMapper::PointHash::any_within(const Eigen::Vector3f& q) const {
  const Eigen::Array3i c = cell_of(q, inv_);
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        const auto it = cells_.find(voxel_key(c.x() + dx, c.y() + dy, c.z() + dz));
        if (it == cells_.end()) continue;
        for (const Eigen::Vector3f& p : it->second) {
          if ((p - q).squaredNorm() <= r2_) return true;
        }
      }
    }
  }
  return false;
}

PlaneMapper::PlaneMapper(PlaneMapperConfig config) : config_(config) {}

int PlaneMapper::associate(const PlaneObservation& obs, const Pose3& T_map_keyframe) const {
  const Plane plane = obs.plane.transformed(T_map_keyframe);
  const Eigen::Vector3d centroid = T_map_keyframe * obs.centroid;
  const double sigma_angle = config_.sigma_angle_deg * M_PI / 180.0;
  std::vector<Eigen::Vector3f> pts;  // map frame, made once a landmark passes the gate
  int best = -1;
  double best_mahalanobis = config_.max_mahalanobis;
  for (const auto& [id, lm] : landmarks_) {
    if (lm.vertical != obs.vertical || lm.plane.n.dot(plane.n) <= 0.0) continue;
    // The offset difference at the observation, not at the origin: the raw d of two planes
    // that differ by a small angle differs by that angle times the distance to the origin.
    const double da = angle_between(lm.plane.n, plane.n) / sigma_angle;
    const double dd = lm.plane.signed_distance(centroid) / config_.sigma_distance;
    const double mahalanobis = std::sqrt(da * da + dd * dd);
    if (mahalanobis > best_mahalanobis || (best >= 0 && mahalanobis == best_mahalanobis)) continue;
    if (pts.empty()) pts = transform_points(obs.points, T_map_keyframe);
    if (overlap_ratio(pts, index_.at(id).near) < config_.min_overlap_ratio) continue;
    best = id;
    best_mahalanobis = mahalanobis;
  }
  return best;
}

void PlaneMapper::add_landmark(int id, const PlaneObservation& obs, const Pose3& T_map_keyframe,
                               int keyframe_id) {
  PlaneLandmark lm;
  lm.id = id;
  lm.plane = obs.plane.transformed(T_map_keyframe);
  lm.vertical = obs.vertical;
  landmarks_[id] = std::move(lm);
  index_.insert_or_assign(id, PointIndex{{}, {}, PointHash({}, config_.overlap_distance)});
  add_observation(id, obs, T_map_keyframe, keyframe_id);
}

void PlaneMapper::add_observation(int id, const PlaneObservation& obs, const Pose3& T_map_keyframe,
                                  int keyframe_id) {
  const auto it = landmarks_.find(id);
  if (it == landmarks_.end()) return;
  PlaneLandmark& lm = it->second;
  // One keyframe may see a face as two pieces (a door near the sensor): keep both.
  std::vector<Eigen::Vector3f>& seen = lm.observations[keyframe_id];
  seen.insert(seen.end(), obs.points.begin(), obs.points.end());
  add_points(lm, obs.points, T_map_keyframe, keyframe_id);
}

void PlaneMapper::add_points(PlaneLandmark& lm, const std::vector<Eigen::Vector3f>& pts_keyframe,
                             const Pose3& T_map_keyframe, int keyframe_id) {
  PointIndex& index = index_.at(lm.id);
  index.poses[keyframe_id] = T_map_keyframe;
  const double inv = 1.0 / std::max(config_.landmark_voxel, kMinCell);
  for (const Eigen::Vector3f& p : transform_points(pts_keyframe, T_map_keyframe)) {
    if (!index.occupied.insert(voxel_key(p, inv)).second) continue;
    lm.points.push_back(p);
    index.near.add(p);
  }
}

void PlaneMapper::rebuild(PlaneLandmark& lm, const std::function<Pose3(int)>& keyframe_pose) {
  PointIndex& index = index_.at(lm.id);
  index.occupied.clear();
  index.poses.clear();
  index.near.clear();
  lm.points.clear();
  for (const auto& [kf, pts] : lm.observations) add_points(lm, pts, keyframe_pose(kf), kf);
}

void PlaneMapper::update(const std::map<int, Plane>& planes, const std::function<Pose3(int)>& keyframe_pose) {
  for (const auto& [id, plane] : planes) {
    const auto it = landmarks_.find(id);
    if (it != landmarks_.end()) it->second.plane = plane;
  }
  for (auto& [id, lm] : landmarks_) {
    const PointIndex& index = index_.at(id);
    bool moved = false;
    for (const auto& [kf, pts] : lm.observations) {
      const auto used = index.poses.find(kf);
      moved = used == index.poses.end() || !(used->second.matrix() == keyframe_pose(kf).matrix());
      if (moved) break;
    }
    if (moved) rebuild(lm, keyframe_pose);
  }
}

std::vector<std::pair<int, int>> PlaneMapper::find_duplicates() const {
  const double cos_merge = std::cos(config_.merge_angle_deg * M_PI / 180.0);
  const bool same_radius = config_.merge_overlap_distance == config_.overlap_distance;
  std::vector<int> ids;
  std::vector<const PlaneLandmark*> lms;
  std::vector<Eigen::Vector3d> centroids;
  for (const auto& [id, lm] : landmarks_) {
    ids.push_back(id);
    lms.push_back(&lm);
    centroids.push_back(centroid_of(lm.points));
  }
  // Union-find over duplicate pairs, so that three pieces of one face become one group.
  std::vector<std::size_t> parent(lms.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t a = 0; a < lms.size(); ++a) {
    if (lms[a]->points.empty()) continue;
    // A's points hashed at the merge radius: association's hash when the two radii agree
    // (the default), else made when a pair first passes the plane tests.
    std::optional<PointHash> own;
    const PointHash* hash = same_radius ? &index_.at(ids[a]).near : nullptr;
    for (std::size_t b = a + 1; b < lms.size(); ++b) {
      const PlaneLandmark& A = *lms[a];
      const PlaneLandmark& B = *lms[b];
      if (A.vertical != B.vertical || B.points.empty()) continue;
      if (A.plane.n.dot(B.plane.n) < cos_merge) continue;
      if (std::abs(A.plane.signed_distance(centroids[b])) > config_.merge_distance) continue;
      if (std::abs(B.plane.signed_distance(centroids[a])) > config_.merge_distance) continue;
      if (find(a) == find(b)) continue;
      if (!hash) hash = &own.emplace(A.points, config_.merge_overlap_distance);
      if (!any_within(B.points, *hash)) continue;
      parent[std::max(find(a), find(b))] = std::min(find(a), find(b));
    }
  }
  // Per group: keep the landmark with the most observations (lowest id on a tie).
  std::map<std::size_t, std::size_t> keep_of_root;
  for (std::size_t a = 0; a < lms.size(); ++a) {
    const auto [it, fresh] = keep_of_root.emplace(find(a), a);
    if (!fresh && lms[a]->observations.size() > lms[it->second]->observations.size()) it->second = a;
  }
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t a = 0; a < lms.size(); ++a) {
    const std::size_t keep = keep_of_root.at(find(a));
    if (keep != a) pairs.emplace_back(ids[keep], ids[a]);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

void PlaneMapper::forget_keyframes(const std::vector<int>& keyframe_ids,
                                   const std::function<Pose3(int)>& keyframe_pose) {
  for (auto& [id, lm] : landmarks_) {
    bool forgot = false;
    for (const int keyframe_id : keyframe_ids) {
      const auto it = lm.observations.find(keyframe_id);
      // The last observation stays: a landmark keeps the points it was mapped from.
      if (it == lm.observations.end() || lm.observations.size() == 1) continue;
      lm.observations.erase(it);
      forgot = true;
    }
    // Once per landmark, not per keyframe: a full solve's retirements touch the same walls.
    if (forgot) rebuild(lm, keyframe_pose);
  }
}

void PlaneMapper::merge(int keep, int drop, const std::function<Pose3(int)>& keyframe_pose) {
  const auto k = landmarks_.find(keep);
  const auto d = landmarks_.find(drop);
  if (k == landmarks_.end() || d == landmarks_.end() || keep == drop) return;
  for (auto& [kf, pts] : d->second.observations) {
    std::vector<Eigen::Vector3f>& seen = k->second.observations[kf];
    seen.insert(seen.end(), pts.begin(), pts.end());
  }
  landmarks_.erase(d);
  index_.erase(drop);
  rebuild(k->second, keyframe_pose);
}

}  // namespace tsgraphs::walls
