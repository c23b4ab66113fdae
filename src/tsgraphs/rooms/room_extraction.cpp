#include "tsgraphs/rooms/room_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

namespace tsgraphs::rooms {

namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// A wall plane reduced to a 2-D line n.q + d = 0 that bounds the cluster on one side.
struct Side {
  int id = -1;
  Vec2 n = Vec2::UnitX();  ///< unit, points into the cluster
  double d = 0.0;
  double distance = 0.0;   ///< of the cluster's centre from the line
};

struct Pair {
  std::size_t a = 0;  ///< index into the sides; the lower id
  std::size_t b = 0;
  double gap = 0.0;
};

/// The values at the `p` and 1 - `p` quantiles (p in [0, 0.5)).
std::pair<double, double> robust_range(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const double last = static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(p * last));
  const auto hi = static_cast<std::size_t>(std::ceil((1.0 - p) * last));
  return {values[lo], values[hi]};
}

std::vector<double> project(const std::vector<Vec2>& points, const Vec2& axis) {
  std::vector<double> out;
  out.reserve(points.size());
  for (const Vec2& q : points) out.push_back(axis.dot(q));
  return out;
}

/// Coordinate along `axis` where the line (n, d) crosses the line through `c` along `axis`.
double position_along(const Side& side, const Vec2& axis, const Vec2& c) {
  const double t = -(side.n.dot(c) + side.d) / side.n.dot(axis);
  return axis.dot(c) + t;
}

/// The planes that may bound the cluster: vertical, facing its centre, not crossed by it,
/// reached by it, and with a segment overlapping the cluster's extent along the wall.
std::vector<Side> bounding_sides(const std::vector<Vec2>& points, const Vec2& centre, double mean_z,
                                 const std::vector<WallCandidate>& walls, const RoomExtractionConfig& cfg) {
  std::vector<Side> sides;
  for (const WallCandidate& w : walls) {
    if (std::abs(w.plane.n.z()) > cfg.max_normal_z) continue;
    const double len = w.plane.n.head<2>().norm();
    Side s;
    s.id = w.id;
    s.n = w.plane.n.head<2>() / len;
    s.d = (w.plane.d + w.plane.n.z() * mean_z) / len;
    s.distance = s.n.dot(centre) + s.d;
    if (s.distance <= 0.0) continue;  // the plane faces away from the cluster

    std::vector<double> offsets;  // of the cluster's points from the plane
    offsets.reserve(points.size());
    std::size_t crossing = 0;
    for (const Vec2& q : points) {
      offsets.push_back(s.n.dot(q) + s.d);
      if (offsets.back() < -cfg.crossing_tolerance) ++crossing;
    }
    if (static_cast<double>(crossing) > cfg.max_crossing_ratio * static_cast<double>(points.size())) continue;
    if (robust_range(std::move(offsets), cfg.extent_percentile).first > cfg.max_wall_clearance) continue;

    const Vec2 along(-s.n.y(), s.n.x());
    const double seg_lo = std::min(along.dot(w.end_a), along.dot(w.end_b));
    const double seg_hi = std::max(along.dot(w.end_a), along.dot(w.end_b));
    const auto [cl_lo, cl_hi] = robust_range(project(points, along), cfg.extent_percentile);
    const double overlap = std::min(seg_hi, cl_hi) - std::max(seg_lo, cl_lo);
    const double shorter = std::min(seg_hi - seg_lo, cl_hi - cl_lo);
    if (overlap <= 0.0 || overlap < cfg.min_segment_overlap_ratio * shorter) continue;
    sides.push_back(s);
  }
  // Per direction only the nearest plane bounds the cluster (a bookshelf in front of a wall).
  const double cos_parallel = std::cos(cfg.parallel_tolerance_deg * kDegToRad);
  std::vector<Side> nearest;
  for (const Side& s : sides) {
    const bool beaten = std::any_of(sides.begin(), sides.end(), [&](const Side& o) {
      return o.id != s.id && o.n.dot(s.n) >= cos_parallel &&
             std::make_pair(o.distance, o.id) < std::make_pair(s.distance, s.id);
    });
    if (!beaten) nearest.push_back(s);
  }
  std::sort(nearest.begin(), nearest.end(), [](const Side& a, const Side& b) { return a.id < b.id; });
  return nearest;
}

std::vector<Pair> facing_pairs(const std::vector<Side>& sides, const RoomExtractionConfig& cfg) {
  const double cos_parallel = std::cos(cfg.parallel_tolerance_deg * kDegToRad);
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < sides.size(); ++i) {
    for (std::size_t j = i + 1; j < sides.size(); ++j) {
      if (sides[i].n.dot(sides[j].n) > -cos_parallel) continue;
      const double gap = sides[i].distance + sides[j].distance;
      if (gap < cfg.min_wall_gap) continue;
      pairs.push_back({i, j, gap});
    }
  }
  // Narrowest first; sides are sorted by id, so ties go to the lower ids.
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.gap < b.gap; });
  return pairs;
}

}  // namespace

std::string to_string(RoomKind kind) { return kind == RoomKind::room ? "room" : "corridor"; }

std::optional<ExtractedRoom> extract_room(const std::vector<Eigen::Vector3d>& cluster,
                                          const std::vector<WallCandidate>& walls,
                                          const RoomExtractionConfig& config) {
  if (cluster.empty() || static_cast<int>(cluster.size()) < config.min_cluster_points) return std::nullopt;
  std::vector<Vec2> points;
  points.reserve(cluster.size());
  Vec2 centre = Vec2::Zero();
  double mean_z = 0.0;
  for (const Eigen::Vector3d& p : cluster) {
    points.push_back(p.head<2>());
    centre += p.head<2>();
    mean_z += p.z();
  }
  centre /= static_cast<double>(cluster.size());
  mean_z /= static_cast<double>(cluster.size());

  const std::vector<Side> sides = bounding_sides(points, centre, mean_z, walls, config);
  const std::vector<Pair> pairs = facing_pairs(sides, config);
  if (pairs.empty()) return std::nullopt;

  const Pair& first = pairs.front();
  const Vec2 u = (sides[first.a].n - sides[first.b].n).normalized();
  const Vec2 v(-u.y(), u.x());
  const double sin_perpendicular = std::sin(config.perpendicular_tolerance_deg * kDegToRad);
  const auto second = std::find_if(pairs.begin() + 1, pairs.end(), [&](const Pair& p) {
    return std::abs(sides[p.a].n.dot(u)) <= sin_perpendicular;
  });

  ExtractedRoom out;
  out.wall_ids = {sides[first.a].id, sides[first.b].id};
  const double lo_u = position_along(sides[first.a], u, centre);
  const double hi_u = position_along(sides[first.b], u, centre);
  double lo_v = 0.0;
  double hi_v = 0.0;
  if (second != pairs.end()) {
    out.kind = RoomKind::room;
    // Order the second pair so that its first plane's normal is along +v (it bounds the low end).
    const bool a_low = sides[second->a].n.dot(v) > 0.0;
    const Side& low = a_low ? sides[second->a] : sides[second->b];
    const Side& high = a_low ? sides[second->b] : sides[second->a];
    out.wall_ids.push_back(low.id);
    out.wall_ids.push_back(high.id);
    lo_v = position_along(low, v, centre);
    hi_v = position_along(high, v, centre);
  } else {
    out.kind = RoomKind::corridor;
    std::tie(lo_v, hi_v) = robust_range(project(points, v), config.extent_percentile);
    // A single wall across the open direction bounds that end (a corridor's dead end).
    const double cos_end = std::cos(config.perpendicular_tolerance_deg * kDegToRad);
    const Side* low_end = nullptr;
    const Side* high_end = nullptr;
    for (const Side& s : sides) {
      const double along = s.n.dot(v);
      if (along >= cos_end && (low_end == nullptr || s.distance < low_end->distance)) low_end = &s;
      if (-along >= cos_end && (high_end == nullptr || s.distance < high_end->distance)) high_end = &s;
    }
    if (low_end != nullptr) {
      lo_v = position_along(*low_end, v, centre);
      out.end_wall_ids.push_back(low_end->id);
    }
    if (high_end != nullptr) {
      hi_v = position_along(*high_end, v, centre);
      out.end_wall_ids.push_back(high_end->id);
    }
  }
  if (hi_u <= lo_u || hi_v <= lo_v) return std::nullopt;
  out.rect.center = u * (0.5 * (lo_u + hi_u)) + v * (0.5 * (lo_v + hi_v));
  out.rect.size = Vec2(hi_u - lo_u, hi_v - lo_v);
  out.rect.yaw = std::atan2(u.y(), u.x());
  return out;
}

}  // namespace tsgraphs::rooms
