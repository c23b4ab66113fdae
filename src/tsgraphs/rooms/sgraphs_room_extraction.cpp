#include "tsgraphs/rooms/sgraphs_room_extraction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tsgraphs::rooms {

namespace {

constexpr int kX = 0;  // map axis indices
constexpr int kY = 1;
constexpr double kQuarterTurn = M_PI / 2.0;  // yaw of a rect whose x axis is the map's y axis

/// A wall plane cut at the cluster's height: the 2-D line n.q + d = 0, n unit.
struct Trace {
  int id = -1;
  Vec2 n = Vec2::UnitX();
  double d = 0.0;
};

/// The winner of one class (x+, x-, y+, y-): the plane with the most cluster points near it.
struct Winner {
  bool found = false;
  Trace trace;
  int points = 0;
};

/// A class index 0..3: 2 * axis + (0 for a normal along +axis, 1 along -axis).
int class_of(const Vec2& n) {
  const int axis = std::abs(n.x()) > std::abs(n.y()) ? kX : kY;
  return 2 * axis + (n[axis] > 0.0 ? 0 : 1);
}

/// Coordinate along `axis` where the line crosses the line through `c` along `axis`.
double position_along(const Trace& t, int axis, const Vec2& c) {
  return c[axis] - (t.n.dot(c) + t.d) / t.n[axis];
}

/// Distance from q to the segment a-b (a point when a == b).
double segment_distance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (q - (a + t * ab)).norm();
}

/// Per class, the plane with the most cluster points within point_distance of its face (either
/// side: S-Graphs measures to the plane's nearest point); ties go to the lower id.
std::array<Winner, 4> class_winners(const std::vector<Vec2>& points, double mean_z,
                                    const std::vector<WallCandidate>& walls,
                                    const SgraphsRoomExtractionConfig& cfg) {
  std::array<Winner, 4> winners;
  for (const WallCandidate& w : walls) {
    const Vec2 horizontal = w.plane.n.head<2>();
    const double len = horizontal.norm();
    if (std::abs(w.plane.n.z()) > cfg.max_normal_z || len == 0.0) continue;
    Trace t;
    t.id = w.id;
    t.n = horizontal / len;
    t.d = (w.plane.d + w.plane.n.z() * mean_z) / len;
    int near = 0;
    for (const Vec2& q : points) {
      if (segment_distance(q, w.end_a, w.end_b) < cfg.point_distance) ++near;
    }
    Winner& best = winners[static_cast<std::size_t>(class_of(t.n))];
    if (!best.found || near > best.points || (near == best.points && t.id < best.trace.id))
      best = {true, t, near};
  }
  return winners;
}

/// One axis' pair: the +axis winner at `lo`, the -axis winner at `hi` (positions along the axis).
struct AxisPair {
  bool valid = false;
  int low_id = -1;   ///< normal along +axis
  int high_id = -1;  ///< normal along -axis
  double lo = 0.0;
  double hi = 0.0;
};

AxisPair axis_pair(const std::array<Winner, 4>& winners, int axis, const Vec2& centroid,
                   const SgraphsRoomExtractionConfig& cfg) {
  const Winner& low = winners[static_cast<std::size_t>(2 * axis)];
  const Winner& high = winners[static_cast<std::size_t>(2 * axis + 1)];
  AxisPair p;
  if (!low.found || !high.found || low.points < cfg.min_points || high.points < cfg.min_points) return p;
  p.low_id = low.trace.id;
  p.high_id = high.trace.id;
  p.lo = position_along(low.trace, axis, centroid);
  p.hi = position_along(high.trace, axis, centroid);
  // Facing: the plane whose normal is along +axis lies on the low side.
  p.valid = p.hi > p.lo && p.hi - p.lo >= cfg.min_width;
  return p;
}

}  // namespace

std::optional<ExtractedRoom> extract_room_sgraphs(const std::vector<Eigen::Vector3d>& cluster,
                                                  const std::vector<WallCandidate>& walls,
                                                  const SgraphsRoomExtractionConfig& config) {
  if (cluster.empty() || walls.empty()) return std::nullopt;
  std::vector<Vec2> points;
  points.reserve(cluster.size());
  Vec2 centroid = Vec2::Zero();
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = -lo;
  double mean_z = 0.0;
  for (const Eigen::Vector3d& p : cluster) {
    points.push_back(p.head<2>());
    centroid += p.head<2>();
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
    mean_z += p.z();
  }
  centroid /= static_cast<double>(cluster.size());
  mean_z /= static_cast<double>(cluster.size());
  if ((hi - lo).minCoeff() < config.min_cluster_extent) return std::nullopt;

  const std::array<Winner, 4> winners = class_winners(points, mean_z, walls, config);
  const std::array<AxisPair, 2> pairs = {axis_pair(winners, kX, centroid, config),
                                         axis_pair(winners, kY, centroid, config)};

  ExtractedRoom out;
  if (pairs[kX].valid && pairs[kY].valid) {
    out.kind = RoomKind::room;
    out.wall_ids = {pairs[kX].low_id, pairs[kX].high_id, pairs[kY].low_id, pairs[kY].high_id};
    out.rect.center = Vec2(0.5 * (pairs[kX].lo + pairs[kX].hi), 0.5 * (pairs[kY].lo + pairs[kY].hi));
    out.rect.size = Vec2(pairs[kX].hi - pairs[kX].lo, pairs[kY].hi - pairs[kY].lo);
    out.rect.yaw = 0.0;
  } else if (pairs[kX].valid || pairs[kY].valid) {
    // Across: the pair; along: the whole cluster, centred at its centroid.
    const int across = pairs[kX].valid ? kX : kY;
    const int along = 1 - across;
    const AxisPair& pair = pairs[static_cast<std::size_t>(across)];
    out.kind = RoomKind::corridor;
    out.wall_ids = {pair.low_id, pair.high_id};
    out.rect.center[across] = 0.5 * (pair.lo + pair.hi);
    out.rect.center[along] = centroid[along];
    out.rect.size = Vec2(pair.hi - pair.lo, hi[along] - lo[along]);
    out.rect.yaw = across == kX ? 0.0 : kQuarterTurn;
  } else {
    return std::nullopt;
  }

  // A footprint whose centre lies away from the cluster is dropped.
  const bool centre_in_cluster = std::any_of(points.begin(), points.end(), [&](const Vec2& q) {
    return (q - out.rect.center).norm() <= config.max_center_offset;
  });
  if (!centre_in_cluster) return std::nullopt;
  return out;
}

}  // namespace tsgraphs::rooms
