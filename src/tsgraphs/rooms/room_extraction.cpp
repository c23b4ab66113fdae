#include "tsgraphs/rooms/room_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include <Eigen/Eigenvalues>

namespace tsgraphs::rooms {

namespace {

constexpr double kDegToRad = M_PI / 180.0;
/// A one-sided corridor's open side is bounded when free space lies beyond it along less than
/// this share of the walked stretch (a railing with gaps, a corner), not along most of it (a hall).
constexpr double kMaxBeyondOpenSide = 0.5;

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
    if (std::abs(w.plane.n.z()) > cfg.max_normal_z || w.height < cfg.min_wall_height) continue;
    const double len = w.plane.n.head<2>().norm();
    Side s;
    s.id = w.id;
    s.n = w.plane.n.head<2>() / len;
    s.d = (w.plane.d + w.plane.n.z() * mean_z) / len;
    s.distance = s.n.dot(centre) + s.d;
    if (s.distance <= 0.0) continue;  // the plane faces away from the cluster

    // Points behind the plane must be a minority that came through narrow passages (doors):
    // a plane the free space runs across along much of its width is no wall of it.
    const Vec2 along(-s.n.y(), s.n.x());
    std::vector<double> offsets;  // of the cluster's points from the plane
    offsets.reserve(points.size());
    std::size_t crossing = 0;
    std::set<long> passage_bins;  // along the wall, where points lie on the plane
    for (const Vec2& q : points) {
      offsets.push_back(s.n.dot(q) + s.d);
      if (offsets.back() < -cfg.crossing_tolerance) ++crossing;
      if (std::abs(offsets.back()) <= cfg.crossing_tolerance)
        passage_bins.insert(std::lround(std::floor(along.dot(q) / cfg.band_bin)));
    }
    if (static_cast<double>(crossing) > cfg.max_crossing_ratio * static_cast<double>(points.size())) continue;
    if (robust_range(std::move(offsets), cfg.extent_percentile).first > cfg.max_wall_clearance) continue;
    const auto [cl_lo, cl_hi] = robust_range(project(points, along), cfg.extent_percentile);
    const double passage = static_cast<double>(passage_bins.size()) * cfg.band_bin;
    if (crossing > 0 && passage > cfg.max_passage_ratio * (cl_hi - cl_lo)) continue;

    const double seg_lo = std::min(along.dot(w.end_a), along.dot(w.end_b));
    const double seg_hi = std::max(along.dot(w.end_a), along.dot(w.end_b));
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

/// The one wall a one-sided corridor runs along: among the sides, the nearest whose normal is
/// perpendicular (within tolerance) to the segment's principal axis.
const Side* along_wall(const std::vector<Vec2>& points, const std::vector<Side>& sides,
                       const RoomExtractionConfig& cfg) {
  Vec2 centre = Vec2::Zero();
  for (const Vec2& q : points) centre += q;
  centre /= static_cast<double>(points.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Vec2& q : points) cov += (q - centre) * (q - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Vec2 axis = eig.eigenvectors().col(1);
  const double sin_perpendicular = std::sin(cfg.perpendicular_tolerance_deg * kDegToRad);
  const Side* best = nullptr;
  for (const Side& s : sides) {
    if (std::abs(s.n.dot(axis)) > sin_perpendicular) continue;
    if (best == nullptr || s.distance < best->distance) best = &s;
  }
  return best;
}

/// The open side of a one-sided corridor along +u: per bin along v, the farthest segment point;
/// the median over bins, so that a crossing aisle at one end does not widen it.
double open_side_edge(const std::vector<Vec2>& points, const Vec2& u, const Vec2& v, double bin) {
  std::map<long, double> far;
  for (const Vec2& q : points) {
    const long b = std::lround(std::floor(v.dot(q) / bin));
    const auto [it, inserted] = far.emplace(b, u.dot(q));
    if (!inserted) it->second = std::max(it->second, u.dot(q));
  }
  std::vector<double> values;
  for (const auto& entry : far) values.push_back(entry.second);
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

/// Whether free space at `a` across a one-sided corridor lies just beyond its open side at
/// hi_u: past the margin, and no farther than an aisle's width (what lies farther, e.g. across
/// an atrium's void, is another aisle).
bool beyond_open_side(double a, double hi_u, const RoomExtractionConfig& cfg) {
  return a > hi_u + cfg.open_side_margin && a <= hi_u + cfg.open_side_margin + cfg.max_open_width;
}

/// A corridor's extent along v: the segment's own extent, carried on through the context points
/// within the band lo_u..hi_u while they span most of the band across (gaps up to band_max_gap;
/// a door is such a gap) and, when the +u side is open, until context appears beyond it (a
/// crossing aisle opens there).
std::pair<double, double> band_extent(const std::vector<Vec2>& context, const Vec2& u, const Vec2& v, double lo_u,
                                      double hi_u, bool open_high_side, std::pair<double, double> start,
                                      const RoomExtractionConfig& cfg) {
  struct Bin {
    bool band = false;
    bool spill = false;
    double lo = 0.0, hi = 0.0;          ///< v range of the band points in it
    double lo_a = 0.0, hi_a = 0.0;      ///< u range of the band points in it
  };
  std::map<long, Bin> bins;
  for (const Vec2& q : context) {
    const double a = u.dot(q);
    const double b = v.dot(q);
    Bin& bin = bins[std::lround(std::floor(b / cfg.band_bin))];
    if (open_high_side && beyond_open_side(a, hi_u, cfg)) bin.spill = true;
    if (a < lo_u - cfg.band_tolerance || a > hi_u + cfg.band_tolerance) continue;
    bin.lo = bin.band ? std::min(bin.lo, b) : b;
    bin.hi = bin.band ? std::max(bin.hi, b) : b;
    bin.lo_a = bin.band ? std::min(bin.lo_a, a) : a;
    bin.hi_a = bin.band ? std::max(bin.hi_a, a) : a;
    bin.band = true;
  }
  // A bin the free space spans only partly across is a door or the end of the aisle.
  const double min_span = cfg.min_band_fill * (hi_u - lo_u);
  for (auto& entry : bins) entry.second.band = entry.second.band && entry.second.hi_a - entry.second.lo_a >= min_span;
  const long max_empty = std::lround(std::ceil(cfg.band_max_gap / cfg.band_bin));
  auto [lo, hi] = start;
  for (int dir : {-1, 1}) {
    long b = std::lround(std::floor((dir > 0 ? hi : lo) / cfg.band_bin)) + dir;
    for (long empty = 0; empty <= max_empty; b += dir) {
      const auto it = bins.find(b);
      if (it == bins.end() || !it->second.band) {
        ++empty;
        continue;
      }
      if (it->second.spill) break;
      empty = 0;
      if (dir > 0) hi = std::max(hi, it->second.hi);
      else lo = std::min(lo, it->second.lo);
    }
  }
  return {lo, hi};
}

/// Whether the free space ends at a one-sided corridor's open side along most of the walked
/// stretch `walked` (a railing), rather than going on beyond it (an open hall).
bool open_side_bounded(const std::vector<Vec2>& context, const Vec2& u, const Vec2& v, double hi_u,
                       std::pair<double, double> walked, const RoomExtractionConfig& cfg) {
  std::set<long> beyond;
  for (const Vec2& q : context) {
    const double b = v.dot(q);
    if (b >= walked.first && b <= walked.second && beyond_open_side(u.dot(q), hi_u, cfg))
      beyond.insert(std::lround(std::floor(b / cfg.band_bin)));
  }
  const double bins = std::max(1.0, std::ceil((walked.second - walked.first) / cfg.band_bin));
  return static_cast<double>(beyond.size()) < kMaxBeyondOpenSide * bins;
}

/// Shortens [lo, hi] along v to the nearest wall across the band lo_u..hi_u beyond the segment's
/// own range `start` on each side: the free space may leak past a wall whose points are out of
/// the obstacle window, the wall still ends the aisle.
void stop_at_crossing_walls(const std::vector<WallCandidate>& walls, const Vec2& u, const Vec2& v, double lo_u,
                            double hi_u, std::pair<double, double> start, const RoomExtractionConfig& cfg,
                            double& lo, double& hi) {
  const double cos_across = std::cos(cfg.perpendicular_tolerance_deg * kDegToRad);
  for (const WallCandidate& w : walls) {
    if (std::abs(w.plane.n.z()) > cfg.max_normal_z || w.height < cfg.min_wall_height) continue;
    const Vec2 n = w.plane.n.head<2>().normalized();
    if (std::abs(n.dot(v)) < cos_across) continue;
    const double a0 = std::min(u.dot(w.end_a), u.dot(w.end_b));
    const double a1 = std::max(u.dot(w.end_a), u.dot(w.end_b));
    if (std::min(a1, hi_u) - std::max(a0, lo_u) < cfg.min_band_fill * (hi_u - lo_u)) continue;
    const double at = 0.5 * (v.dot(w.end_a) + v.dot(w.end_b));
    if (at > start.second && at < hi) hi = at;
    if (at < start.first && at > lo) lo = at;
  }
}

/// Carries a two-walled corridor's [lo, hi] along v as far as both its walls run: ground far
/// down an aisle is mapped late and sparse, its walls early (they face the sensor), so the
/// free space alone ends a corridor short of where it ends. Walls across it (an end wall, a
/// door's wall) stop it afterwards, as they stop the free space.
void carry_along_walls(const std::vector<WallCandidate>& walls, const std::vector<int>& pair, const Vec2& v,
                       double& lo, double& hi) {
  double common_lo = -std::numeric_limits<double>::infinity();
  double common_hi = std::numeric_limits<double>::infinity();
  for (const WallCandidate& w : walls) {
    if (std::find(pair.begin(), pair.end(), w.id) == pair.end()) continue;
    common_lo = std::max(common_lo, std::min(v.dot(w.end_a), v.dot(w.end_b)));
    common_hi = std::min(common_hi, std::max(v.dot(w.end_a), v.dot(w.end_b)));
  }
  if (common_hi - common_lo <= 0.0) return;
  lo = std::min(lo, common_lo);
  hi = std::max(hi, common_hi);
}

/// The nearest side facing along +v (low end) and along -v (high end), each may be null.
std::pair<const Side*, const Side*> end_walls(const std::vector<Side>& sides, const Vec2& v,
                                              const RoomExtractionConfig& cfg) {
  const double cos_end = std::cos(cfg.perpendicular_tolerance_deg * kDegToRad);
  const Side* low = nullptr;
  const Side* high = nullptr;
  for (const Side& s : sides) {
    const double along = s.n.dot(v);
    if (along >= cos_end && (low == nullptr || s.distance < low->distance)) low = &s;
    if (-along >= cos_end && (high == nullptr || s.distance < high->distance)) high = &s;
  }
  return {low, high};
}

std::vector<Vec2> flat(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) out.push_back(p.head<2>());
  return out;
}

/// The coordinate-wise median: where most of the free space is. Free space that leaks through
/// a door into the next room pulls the mean towards it, past the wall between them.
Vec2 median_of(const std::vector<Vec2>& points) {
  Vec2 m;
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> values;
    values.reserve(points.size());
    for (const Vec2& q : points) values.push_back(q[axis]);
    const auto mid = values.begin() + static_cast<long>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    m[axis] = *mid;
  }
  return m;
}

OrientedRect rect_of(const Vec2& u, const Vec2& v, double lo_u, double hi_u, double lo_v, double hi_v) {
  OrientedRect r;
  r.center = u * (0.5 * (lo_u + hi_u)) + v * (0.5 * (lo_v + hi_v));
  r.size = Vec2(hi_u - lo_u, hi_v - lo_v);
  r.yaw = std::atan2(u.y(), u.x());
  return r;
}

}  // namespace

std::string to_string(RoomKind kind) { return kind == RoomKind::room ? "room" : "corridor"; }

std::optional<ExtractedRoom> extract_room(const std::vector<Eigen::Vector3d>& segment,
                                          const std::vector<Eigen::Vector3d>& context,
                                          const std::vector<WallCandidate>& walls,
                                          const RoomExtractionConfig& config) {
  if (segment.empty() || static_cast<int>(segment.size()) < config.min_cluster_points) return std::nullopt;
  const std::vector<Vec2> points = flat(segment);
  const Vec2 centre = median_of(points);
  double mean_z = 0.0;
  for (const Eigen::Vector3d& p : segment) mean_z += p.z();
  mean_z /= static_cast<double>(segment.size());

  const std::vector<Side> sides = bounding_sides(points, centre, mean_z, walls, config);
  const std::vector<Pair> pairs = facing_pairs(sides, config);

  // Across the aisle (u): a facing pair, or one wall and the free space's edge on its open side.
  ExtractedRoom out;
  Vec2 u;
  double lo_u = 0.0;
  double hi_u = 0.0;
  if (!pairs.empty()) {
    const Pair& first = pairs.front();
    u = (sides[first.a].n - sides[first.b].n).normalized();
    out.wall_ids = {sides[first.a].id, sides[first.b].id};
    lo_u = position_along(sides[first.a], u, centre);
    hi_u = position_along(sides[first.b], u, centre);
  } else {
    const Side* wall = along_wall(points, sides, config);
    if (wall == nullptr) return std::nullopt;
    u = wall->n;
    out.one_sided = true;
    out.wall_ids = {wall->id};
    lo_u = position_along(*wall, u, centre);
    hi_u = open_side_edge(points, u, Vec2(-u.y(), u.x()), config.band_bin) + config.open_side_offset;
    if (hi_u - lo_u < config.min_wall_gap || hi_u - lo_u > config.max_open_width) return std::nullopt;
  }
  const Vec2 v(-u.y(), u.x());

  // Along it (v): a second facing pair found by the segment makes a room.
  const double sin_perpendicular = std::sin(config.perpendicular_tolerance_deg * kDegToRad);
  const auto second = std::find_if(pairs.begin() + (pairs.empty() ? 0 : 1), pairs.end(), [&](const Pair& p) {
    return std::abs(sides[p.a].n.dot(u)) <= sin_perpendicular;
  });
  if (second != pairs.end()) {
    out.kind = RoomKind::room;
    // Order the second pair so that its first plane's normal is along +v (it bounds the low end).
    const bool a_low = sides[second->a].n.dot(v) > 0.0;
    const Side& low = a_low ? sides[second->a] : sides[second->b];
    const Side& high = a_low ? sides[second->b] : sides[second->a];
    out.wall_ids.push_back(low.id);
    out.wall_ids.push_back(high.id);
    const double lo_v = position_along(low, v, centre);
    const double hi_v = position_along(high, v, centre);
    if (hi_u <= lo_u || hi_v <= lo_v) return std::nullopt;
    out.rect = rect_of(u, v, lo_u, hi_u, lo_v, hi_v);
    return out;
  }

  // Otherwise the context carries the aisle on along v, up to end walls where they are.
  const std::vector<Vec2> around = context.empty() ? points : flat(context);
  const std::pair<double, double> walked = robust_range(project(points, v), config.extent_percentile);
  if (out.one_sided && !open_side_bounded(around, u, v, hi_u, walked, config)) return std::nullopt;
  auto [lo_v, hi_v] = band_extent(around, u, v, lo_u, hi_u, out.one_sided, walked, config);
  if (!out.one_sided) carry_along_walls(walls, out.wall_ids, v, lo_v, hi_v);
  stop_at_crossing_walls(walls, u, v, lo_u, hi_u, walked, config, lo_v, hi_v);
  std::vector<Vec2> run;
  for (const Vec2& q : around) {
    const double a = u.dot(q);
    const double b = v.dot(q);
    if (a >= lo_u - config.band_tolerance && a <= hi_u + config.band_tolerance && b >= lo_v && b <= hi_v)
      run.push_back(q);
  }
  if (run.empty()) run = points;
  const std::vector<Side> run_sides = bounding_sides(run, median_of(run), mean_z, walls, config);
  const auto [low_end, high_end] = end_walls(run_sides, v, config);
  if (low_end != nullptr) lo_v = position_along(*low_end, v, centre);
  if (high_end != nullptr) hi_v = position_along(*high_end, v, centre);
  if (hi_u <= lo_u || hi_v <= lo_v) return std::nullopt;
  if (out.one_sided && hi_v - lo_v < config.min_open_aspect * (hi_u - lo_u)) return std::nullopt;

  if (!out.one_sided && low_end != nullptr && high_end != nullptr) {
    out.kind = RoomKind::room;  // a facing pair closed at both ends: four walls
    out.wall_ids.push_back(low_end->id);
    out.wall_ids.push_back(high_end->id);
  } else {
    out.kind = RoomKind::corridor;
    if (low_end != nullptr) out.end_wall_ids.push_back(low_end->id);
    if (high_end != nullptr) out.end_wall_ids.push_back(high_end->id);
  }
  out.rect = rect_of(u, v, lo_u, hi_u, lo_v, hi_v);
  return out;
}

}  // namespace tsgraphs::rooms
