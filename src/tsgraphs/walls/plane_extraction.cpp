#include "tsgraphs/walls/plane_extraction.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "tsgraphs/core/kd_tree.hpp"
#include "tsgraphs/core/voxel_key.hpp"

namespace tsgraphs::walls {
namespace {

// A point's normal is trusted only where its neighbourhood spreads in two directions (middle
// eigenvalue at least this share of the largest): far scan lines give line-shaped
// neighbourhoods whose smallest eigenvector is any direction across the line.
constexpr double kMinPlanarSpread = 0.05;
// Plane fit -> inlier sweep rounds per hypothesis; the second round settles the fit.
constexpr int kRefineRounds = 2;
// Euclidean clustering works in the plane on square cells this fraction of the tolerance,
// so that any two points of one cell are within the tolerance of each other.
constexpr double kCellPerTolerance = M_SQRT1_2;
// Cell offsets searched around a cell: up to two cells away (a cell is tolerance / sqrt 2),
// except the far diagonal corners, which are never closer than the tolerance.
constexpr int kCellReach = 2;

enum class NormalClass : std::uint8_t { kNone, kVertical, kHorizontal };

// Point normals by PCA over the k nearest neighbours, oriented towards the sensor.
struct Normals {
  std::vector<Eigen::Vector3f> normal;
  std::vector<float> curvature;           ///< smallest eigenvalue over the sum
  std::vector<bool> reliable;             ///< neighbourhood is plane-like, not line-like
  std::vector<std::uint32_t> neighbours;  ///< k per point, the kNN graph for region growing
};

// Least-squares plane of a set of points: centroid, unit normal (smallest eigenvector).
struct Fit {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  bool ok = false;
};

template <class Indices>
Fit fit_plane(const std::vector<Eigen::Vector3f>& pts, const Indices& idx) {
  Fit f;
  if (idx.size() < 3) return f;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto i : idx) c += pts[i].template cast<double>();
  c /= static_cast<double>(idx.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto i : idx) {
    const Eigen::Vector3d q = pts[i].template cast<double>() - c;
    cov.noalias() += q * q.transpose();
  }
  // The iterative solver: computeDirect loses precision on nearly flat covariances.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  if (es.info() != Eigen::Success) return f;
  f.centroid = c;
  f.normal = es.eigenvectors().col(0).normalized();
  f.ok = f.normal.allFinite();
  return f;
}

Normals estimate_normals(const std::vector<Eigen::Vector3f>& pts, int k) {
  Normals out;
  const std::size_t n = pts.size();
  out.normal.assign(n, Eigen::Vector3f::UnitZ());
  out.curvature.assign(n, 1.0f);
  out.reliable.assign(n, false);
  out.neighbours.assign(n * static_cast<std::size_t>(k), 0);

  const KdTree3f tree(pts);
  std::vector<float> d2(static_cast<std::size_t>(k));
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t* nb = out.neighbours.data() + i * static_cast<std::size_t>(k);
    const std::size_t found = tree.knn(pts[i].data(), static_cast<std::size_t>(k), nb, d2.data());
    for (std::size_t j = found; j < static_cast<std::size_t>(k); ++j) nb[j] = static_cast<std::uint32_t>(i);
    if (found < 3) continue;
    // Moments relative to the query point: no cancellation far from the sensor.
    Eigen::Vector3f s = Eigen::Vector3f::Zero();
    Eigen::Matrix3f m = Eigen::Matrix3f::Zero();
    for (std::size_t j = 0; j < found; ++j) {
      const Eigen::Vector3f q = pts[nb[j]] - pts[i];
      s += q;
      m.noalias() += q * q.transpose();
    }
    const float inv = 1.0f / static_cast<float>(found);
    const Eigen::Matrix3d cov = (m * inv - (s * inv) * (s * inv).transpose()).cast<double>();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(cov);
    const Eigen::Vector3d ev = es.eigenvalues();
    const double sum = ev.sum();
    if (!(sum > 0.0)) continue;
    Eigen::Vector3f nrm = es.eigenvectors().col(0).cast<float>().normalized();
    if (!nrm.allFinite()) continue;
    if (nrm.dot(pts[i]) > 0.0f) nrm = -nrm;  // towards the sensor at the origin
    out.normal[i] = nrm;
    out.curvature[i] = static_cast<float>(ev(0) / sum);
    out.reliable[i] = ev(1) >= kMinPlanarSpread * ev(2);
  }
  return out;
}

// Splits the inliers of one plane into groups whose in-plane gaps are at most `tolerance`
// (no split for a tolerance <= 0). Groups come out ordered by their smallest point index, each
// in increasing index order.
std::vector<std::vector<std::uint32_t>> euclidean_clusters(const std::vector<Eigen::Vector3f>& pts,
                                                           std::vector<std::uint32_t> idx,
                                                           const Eigen::Vector3d& normal, double tolerance) {
  std::sort(idx.begin(), idx.end());
  if (!(tolerance > 0.0)) return {idx};
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.cross(u);
  const double cell = tolerance * kCellPerTolerance;
  const double tol2 = tolerance * tolerance;
  const std::size_t m = idx.size();

  std::vector<Eigen::Vector2d> uv(m);
  std::vector<std::pair<std::int64_t, std::int64_t>> cell_of(m);
  std::unordered_map<std::uint64_t, std::uint32_t> cell_index;
  std::vector<std::vector<std::uint32_t>> cells;  // local indices into idx
  std::vector<std::pair<std::int64_t, std::int64_t>> cell_coord;
  for (std::size_t j = 0; j < m; ++j) {
    const Eigen::Vector3d p = pts[idx[j]].cast<double>();
    uv[j] = {u.dot(p), v.dot(p)};
    const std::int64_t a = static_cast<std::int64_t>(std::floor(uv[j].x() / cell));
    const std::int64_t b = static_cast<std::int64_t>(std::floor(uv[j].y() / cell));
    const auto [it, fresh] = cell_index.emplace(cell_key(a, b), static_cast<std::uint32_t>(cells.size()));
    if (fresh) {
      cells.emplace_back();
      cell_coord.emplace_back(a, b);
    }
    cells[it->second].push_back(static_cast<std::uint32_t>(j));
  }

  std::vector<std::uint32_t> parent(cells.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    for (int da = -kCellReach; da <= kCellReach; ++da) {
      for (int db = -kCellReach; db <= kCellReach; ++db) {
        if (std::abs(da) == kCellReach && std::abs(db) == kCellReach) continue;
        const auto it = cell_index.find(cell_key(cell_coord[c].first + da, cell_coord[c].second + db));
        if (it == cell_index.end() || it->second <= c) continue;  // each pair once
        const std::uint32_t ra = find(c), rb = find(it->second);
        if (ra == rb) continue;
        bool close = false;
        for (const std::uint32_t a : cells[c]) {
          for (const std::uint32_t b : cells[it->second]) {
            if ((uv[a] - uv[b]).squaredNorm() <= tol2) {
              close = true;
              break;
            }
          }
          if (close) break;
        }
        if (close) parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
  }

  std::unordered_map<std::uint32_t, std::uint32_t> group_of_root;
  std::vector<std::vector<std::uint32_t>> groups;
  std::vector<std::uint32_t> root_of_point(m);
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    for (const std::uint32_t j : cells[c]) root_of_point[j] = find(c);
  }
  for (std::size_t j = 0; j < m; ++j) {  // increasing point index: deterministic group order
    const auto [it, fresh] =
        group_of_root.emplace(root_of_point[j], static_cast<std::uint32_t>(groups.size()));
    if (fresh) groups.emplace_back();
    groups[it->second].push_back(idx[j]);
  }
  return groups;
}

// Centroids of the points per voxel of edge `voxel`, in order of first appearance.
std::vector<Eigen::Vector3f> downsample(const std::vector<Eigen::Vector3f>& pts,
                                        const std::vector<std::uint32_t>& idx, double voxel) {
  std::vector<Eigen::Vector3f> out;
  if (!(voxel > 0.0)) {
    out.reserve(idx.size());
    for (const std::uint32_t i : idx) out.push_back(pts[i]);
    return out;
  }
  const double inv = 1.0 / voxel;
  std::unordered_map<std::uint64_t, std::uint32_t> slot;
  std::vector<Eigen::Vector3d> sum;
  std::vector<int> count;
  for (const std::uint32_t i : idx) {
    const Eigen::Vector3f& p = pts[i];
    const auto [it, fresh] = slot.emplace(voxel_key(p, inv), static_cast<std::uint32_t>(sum.size()));
    if (fresh) {
      sum.emplace_back(Eigen::Vector3d::Zero());
      count.push_back(0);
    }
    sum[it->second] += p.cast<double>();
    ++count[it->second];
  }
  out.reserve(sum.size());
  for (std::size_t s = 0; s < sum.size(); ++s) out.push_back((sum[s] / count[s]).cast<float>());
  return out;
}

// One face: least-squares plane of its points, oriented towards the sensor (d > 0).
bool make_observation(const std::vector<Eigen::Vector3f>& pts, const std::vector<std::uint32_t>& face,
                      bool vertical, const Eigen::Matrix3d& R_map_keyframe,
                      const PlaneExtractionConfig& config, PlaneObservation* obs) {
  const Fit fit = fit_plane(pts, face);
  if (!fit.ok) return false;
  Plane plane = Plane::from_point_normal(fit.centroid, fit.normal);
  if (plane.d < 0.0) {
    plane.n = -plane.n;
    plane.d = -plane.d;
  }
  // A face whose own refit leaves the class of the points it was swept from is dropped.
  const Eigen::Vector3d n_map = R_map_keyframe * plane.n;
  if (vertical ? std::abs(n_map.z()) > config.max_vertical_normal_z
               : std::abs(n_map.z()) < config.min_horizontal_normal_z) {
    return false;
  }
  if (vertical) {
    // Horizontal direction within the face, in the keyframe frame.
    const Eigen::Vector3d along_map = Eigen::Vector3d::UnitZ().cross(n_map);
    if (along_map.norm() <= 0.0) return false;
    const Eigen::Vector3d along = R_map_keyframe.transpose() * along_map.normalized();
    double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    for (const std::uint32_t i : face) {
      const double s = along.dot(pts[i].cast<double>());
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
    if (hi - lo < config.min_extent) return false;
  }
  double sq = 0.0;
  for (const std::uint32_t i : face) {
    const double e = plane.signed_distance(pts[i].cast<double>());
    sq += e * e;
  }
  obs->plane = plane;
  obs->vertical = vertical;
  obs->centroid = fit.centroid;
  obs->num_inliers = static_cast<int>(face.size());
  obs->fit_rms = std::sqrt(sq / static_cast<double>(face.size()));
  obs->points = downsample(pts, face, config.point_voxel);
  return obs->plane.n.allFinite() && std::isfinite(obs->plane.d) && std::isfinite(obs->fit_rms);
}

/// Finite points within `max_range` of the sensor.
std::vector<Eigen::Vector3f> points_in_range(const PointCloud& cloud, double max_range) {
  std::vector<Eigen::Vector3f> pts;
  pts.reserve(cloud.size());
  const float max_range2 = static_cast<float>(max_range * max_range);
  for (const Eigen::Vector3f& p : cloud.points) {
    if (p.allFinite() && p.squaredNorm() <= max_range2) pts.push_back(p);
  }
  return pts;
}

/// Normal class of every point, judged in the gravity-aligned map frame.
std::vector<NormalClass> classify_normals(const Normals& normals, const Eigen::Matrix3d& R_map_keyframe,
                                          const PlaneExtractionConfig& config) {
  std::vector<NormalClass> cls(normals.normal.size(), NormalClass::kNone);
  const Eigen::Vector3f z_in_keyframe = (R_map_keyframe.transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
  for (std::size_t i = 0; i < cls.size(); ++i) {
    if (!normals.reliable[i]) continue;
    const double nz = std::abs(normals.normal[i].dot(z_in_keyframe));
    if (nz <= config.max_vertical_normal_z)
      cls[i] = NormalClass::kVertical;
    else if (nz >= config.min_horizontal_normal_z)
      cls[i] = NormalClass::kHorizontal;
  }
  return cls;
}

/// Plane hypotheses by region growing over the kNN graph, largest first (discovery order on a
/// tie): smoothest points seed first; a neighbour joins if its normal agrees with the seed's and
/// it lies on the current point's tangent plane (no step onto a parallel surface in front).
std::vector<std::vector<std::uint32_t>> grow_regions(const std::vector<Eigen::Vector3f>& pts,
                                                     const Normals& normals,
                                                     const std::vector<NormalClass>& cls, int k,
                                                     float cos_thr, float dist_thr) {
  const std::size_t n = pts.size();
  std::vector<std::uint32_t> order;
  order.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (cls[i] != NormalClass::kNone) order.push_back(i);
  }
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return normals.curvature[a] != normals.curvature[b] ? normals.curvature[a] < normals.curvature[b] : a < b;
  });
  std::vector<std::int32_t> region_of(n, -1);
  std::vector<std::vector<std::uint32_t>> regions;
  for (const std::uint32_t seed : order) {
    if (region_of[seed] >= 0) continue;
    const std::int32_t r = static_cast<std::int32_t>(regions.size());
    regions.emplace_back();
    std::vector<std::uint32_t>& region = regions.back();
    region.push_back(seed);
    region_of[seed] = r;
    const Eigen::Vector3f& ns = normals.normal[seed];
    for (std::size_t head = 0; head < region.size(); ++head) {
      const std::uint32_t i = region[head];
      const std::uint32_t* nb = normals.neighbours.data() + static_cast<std::size_t>(i) * k;
      for (int j = 0; j < k; ++j) {
        const std::uint32_t q = nb[j];
        if (region_of[q] >= 0 || cls[q] != cls[seed]) continue;
        if (normals.normal[q].dot(ns) < cos_thr) continue;
        if (std::abs(normals.normal[i].dot(pts[q] - pts[i])) > dist_thr) continue;
        region_of[q] = r;
        region.push_back(q);
      }
    }
  }
  std::stable_sort(regions.begin(), regions.end(),
                   [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return regions;
}

/// A hypothesis's plane: fit its untaken points, sweep the inliers of its class over the whole
/// cloud, refit, kRefineRounds times; `inliers` holds the last sweep's.
Fit refine_plane(const std::vector<Eigen::Vector3f>& pts, const Normals& normals,
                 const std::vector<NormalClass>& cls, const std::vector<bool>& taken, NormalClass c,
                 std::size_t min_inliers, float cos_thr, float dist_thr,
                 std::vector<std::uint32_t>& inliers) {
  Fit fit = fit_plane(pts, inliers);
  for (int round = 0; round < kRefineRounds && fit.ok; ++round) {
    const Eigen::Vector3f nf = fit.normal.cast<float>();
    const Eigen::Vector3f cf = fit.centroid.cast<float>();
    // The fitted normal's sign is arbitrary; point normals face the sensor.
    const float sign = nf.dot(cf) > 0.0f ? -1.0f : 1.0f;
    inliers.clear();
    for (std::uint32_t i = 0; i < pts.size(); ++i) {
      if (taken[i] || cls[i] != c) continue;
      if (std::abs(nf.dot(pts[i] - cf)) > dist_thr) continue;
      if (sign * nf.dot(normals.normal[i]) < cos_thr) continue;
      inliers.push_back(i);
    }
    if (inliers.size() < min_inliers) break;
    fit = fit_plane(pts, inliers);
  }
  return fit;
}

}  // namespace

std::vector<PlaneObservation> extract_planes(const PointCloud& cloud, const Eigen::Matrix3d& R_map_keyframe,
                                             const PlaneExtractionConfig& config) {
  std::vector<PlaneObservation> planes;
  const int k = std::max(3, config.normal_neighbours);
  const std::size_t min_inliers = static_cast<std::size_t>(std::max(3, config.min_inliers));
  const std::vector<Eigen::Vector3f> pts = points_in_range(cloud, config.max_range);
  if (pts.size() < std::max(min_inliers, static_cast<std::size_t>(k))) return planes;
  const Normals normals = estimate_normals(pts, k);
  const std::vector<NormalClass> cls = classify_normals(normals, R_map_keyframe, config);
  const float cos_thr = static_cast<float>(std::cos(config.normal_angle_threshold_deg * M_PI / 180.0));
  const float dist_thr = static_cast<float>(config.distance_threshold);

  // Per hypothesis: its plane refined over the whole cloud; the inliers are then taken, and
  // split into faces by Euclidean clustering.
  std::vector<bool> taken(pts.size(), false);
  std::vector<std::uint32_t> inliers;
  for (const std::vector<std::uint32_t>& region : grow_regions(pts, normals, cls, k, cos_thr, dist_thr)) {
    if (region.size() < min_inliers) break;  // sorted: the rest are smaller
    inliers.clear();
    for (const std::uint32_t i : region) {
      if (!taken[i]) inliers.push_back(i);
    }
    if (inliers.size() < min_inliers) continue;
    const NormalClass c = cls[region.front()];
    const Fit fit = refine_plane(pts, normals, cls, taken, c, min_inliers, cos_thr, dist_thr, inliers);
    if (!fit.ok || inliers.size() < min_inliers) continue;
    for (const std::uint32_t i : inliers) taken[i] = true;
    for (const std::vector<std::uint32_t>& face :
         euclidean_clusters(pts, inliers, fit.normal, config.cluster_tolerance)) {
      if (face.size() < min_inliers) continue;
      PlaneObservation obs;
      if (make_observation(pts, face, c == NormalClass::kVertical, R_map_keyframe, config, &obs)) {
        planes.push_back(std::move(obs));
      }
    }
  }

  // Largest first; discovery order breaks ties.
  std::stable_sort(planes.begin(), planes.end(), [](const PlaneObservation& a, const PlaneObservation& b) {
    return a.num_inliers > b.num_inliers;
  });
  const std::size_t max_planes = static_cast<std::size_t>(std::max(0, config.max_planes));
  if (planes.size() > max_planes) planes.resize(max_planes);
  return planes;
}

}  // namespace tsgraphs::walls
