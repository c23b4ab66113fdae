#include "tsgraphs/ground/ground_segmentation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tsgraphs/ground/bgk_smoothing.hpp"
#include "tsgraphs/ground/traversable_search.hpp"
#include "tsgraphs/ground/tri_grid_ground.hpp"

namespace tsgraphs::ground {

namespace {

/// For every node, the traversable node nearest to it over the grid's edges (itself when it
/// is traversable), or -1 when there is none.
void nearest_traversable(const TriGrid& grid, const std::vector<std::uint8_t>& traversable,
                         std::vector<int>* out, std::vector<int>* queue_buffer) {
  std::vector<int>& nearest = *out;
  nearest.assign(traversable.size(), -1);
  std::vector<int>& queue = *queue_buffer;
  queue.clear();
  for (int k = 0; k < static_cast<int>(traversable.size()); ++k) {
    if (!traversable[k]) continue;
    nearest[k] = k;
    queue.push_back(k);
  }
  std::array<int, 3> adj{};
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int current = queue[head];
    const int count = grid.adjacent(current, &adj);
    for (int a = 0; a < count; ++a) {
      if (nearest[adj[a]] >= 0) continue;
      nearest[adj[a]] = nearest[current];
      queue.push_back(adj[a]);
    }
  }
}

/// Where obstacle returns stand just above the ground (a wall, a box side): a ground-band
/// point within foot_radius (horizontally) of one is that obstacle's foot. Marks are kept on a
/// bitmap of foot_radius cells (a quick "nothing near") and, sorted by cell, for the exact test.
class FootMap {
 public:
  /// Empties the map for marks within half_extent of the sensor, keeping its buffers.
  void reset(double radius, double half_extent) {
    radius_ = radius;
    cells_ = static_cast<std::int64_t>(std::ceil(2.0 * half_extent / radius)) + 3;
    origin_ = -0.5 * static_cast<double>(cells_) * radius;
    bits_.assign((cells_ * cells_ + 63) / 64, 0);
    marks_.clear();
  }

  void add(const Eigen::Vector3f& p) {
    const std::int64_t u = cell(p.x(), origin_), v = cell(p.y(), origin_);
    if (u < 0 || v < 0 || u >= cells_ || v >= cells_) return;
    const std::int64_t k = u * cells_ + v;
    bits_[k / 64] |= std::uint64_t{1} << (k % 64);
    marks_.push_back({k, p.x(), p.y()});
  }
  /// Call once after the last add().
  void index() {
    std::sort(marks_.begin(), marks_.end(), [](const Mark& a, const Mark& b) { return a.key < b.key; });
  }

  bool near_mark(const Eigen::Vector3f& p) const {
    const std::int64_t u = cell(p.x(), origin_), v = cell(p.y(), origin_);
    const double r_sq = radius_ * radius_;
    for (std::int64_t a = std::max<std::int64_t>(u - 1, 0); a <= std::min(u + 1, cells_ - 1); ++a) {
      for (std::int64_t b = std::max<std::int64_t>(v - 1, 0); b <= std::min(v + 1, cells_ - 1); ++b) {
        const std::int64_t k = a * cells_ + b;
        if (!(bits_[k / 64] >> (k % 64) & 1)) continue;
        auto it = std::lower_bound(marks_.begin(), marks_.end(), k,
                                   [](const Mark& m, std::int64_t x) { return m.key < x; });
        for (; it != marks_.end() && it->key == k; ++it) {
          const double dx = it->x - p.x(), dy = it->y - p.y();
          if (dx * dx + dy * dy <= r_sq) return true;
        }
      }
    }
    return false;
  }

 private:
  struct Mark {
    std::int64_t key;
    float x, y;
  };
  std::int64_t cell(float x, double origin) const {
    return static_cast<std::int64_t>(std::floor((x - origin) / radius_));
  }
  double radius_ = 1.0;
  std::int64_t cells_ = 0;
  double origin_ = 0.0;
  std::vector<std::uint64_t> bits_;
  std::vector<Mark> marks_;
};

/// The buffers of one segmentation. Each thread keeps its own and reuses it from scan to scan:
/// allocating these few megabytes afresh for every scan took about as long as the
/// segmentation itself (the pages are faulted in again each time).
struct Workspace {
  TriGridField field;
  std::vector<SmoothedNode> smoothed;
  std::vector<TriGridNode> ground;
  std::vector<int> nearest, queue;
  std::vector<Eigen::Vector3d> ground_sum;
  FootMap feet;
};

}  // namespace

GroundConfig per_sensor_preset(const std::string& preset) {
  GroundConfig config;
  if (preset == "vlp-16") {
    // 16 beams 2 degrees apart: the floor rings are sparse (7 within 15 m at 0.55 m height,
    // 4 m apart beyond 6 m), so nodes hold fewer points and the search must cross wider gaps
    // (simulated office: ground recall 0.947 with the defaults, 0.960 with these).
    config.num_min_pts = 5;
    config.max_gap = 4.5;
    config.ring_spacing_deg = 2.0;
  } else if (preset == "hesai-xt32") {
    // 32 beams 1 degree apart: half the os1-64's rings, about as far apart again (simulated
    // office: ground recall 0.964 with the defaults, 0.971 with these).
    config.num_min_pts = 6;
    config.max_gap = 3.0;
    config.ring_spacing_deg = 1.0;
  }
  // "os1-64" (the defaults' sensor) and "os0-128" (twice the beams over twice the field of
  // view: rings as close as the os1-64's): the defaults.
  return config;
}

std::string preset_for_ring_spacing(double spacing_deg) {
  if (!(spacing_deg > 0.0)) return "";
  // Each preset's own beam spacing (per_sensor_preset's ring_spacing_deg), so the two agree.
  const char* best = "";
  double best_ratio = 1e300;
  for (const char* preset : {"vlp-16", "hesai-xt32", "os1-64"}) {
    const double ratio = std::abs(std::log(spacing_deg / per_sensor_preset(preset).ring_spacing_deg));
    if (ratio < best_ratio) {
      best_ratio = ratio;
      best = preset;
    }
  }
  return best;
}

namespace {

/// The ground plane of each traversable node: its own when the search reached it, the
/// smoothed one when smoothing restored it.
void ground_planes(const TriGridField& field, const std::vector<std::uint8_t>& traversable,
                   const std::vector<std::uint8_t>& reached, const std::vector<SmoothedNode>& smoothed,
                   std::vector<TriGridNode>* out) {
  const std::size_t num_nodes = field.nodes.size();
  std::vector<TriGridNode>& ground = *out;
  ground.assign(num_nodes, TriGridNode{});
  for (std::size_t k = 0; k < num_nodes; ++k) {
    const TriGridNode& node = field.nodes[k];
    if (!traversable[k] || reached[k]) {
      ground[k] = node;
      continue;
    }
    ground[k].centre = Eigen::Vector3f(node.centre.x(), node.centre.y(), smoothed[k].height);
    ground[k].normal = smoothed[k].normal;
  }
}

/// Labels the points ground (the ground band of traversable nodes) or obstacle (up to
/// th_obstacle above the nearest traversable node's plane), and marks in `feet` the obstacle
/// returns low enough to stand on a wall's or a box's foot.
void label_points(const TriGridField& field, const std::vector<std::uint8_t>& traversable,
                  const std::vector<TriGridNode>& ground, const std::vector<int>& nearest,
                  const GroundConfig& config, std::vector<GroundLabel>* labels, FootMap* feet) {
  const double foot_rise_per_metre = config.foot_rings * std::tan(config.ring_spacing_deg * M_PI / 180.0);
  for (std::size_t i = 0; i < labels->size(); ++i) {
    const int k = field.point_node[i];
    if (k < 0 || nearest[k] < 0) continue;
    const Eigen::Vector3f& p = field.points[i];
    const TriGridNode& plane = ground[nearest[k]];
    if (traversable[k] && std::abs(plane.distance(p)) <= config.th_dist) {
      (*labels)[i] = GroundLabel::kGround;
      continue;
    }
    const double height = p.z() - plane.height_at(p.x(), p.y());
    if (height <= config.th_dist || height > config.th_obstacle) continue;
    (*labels)[i] = GroundLabel::kObstacle;
    // Far away the rings on a wall are farther apart than foot_height: reach foot_rings of them.
    const double reach = std::max(config.foot_height, foot_rise_per_metre * p.head<2>().norm());
    if (height <= config.th_dist + reach) feet->add(p);
  }
}

/// Relabels as obstacle the ground points within foot_radius of a foot mark.
void label_feet(const TriGridField& field, const FootMap& feet, std::vector<GroundLabel>* labels) {
  for (std::size_t i = 0; i < labels->size(); ++i)
    if ((*labels)[i] == GroundLabel::kGround && feet.near_mark(field.points[i]))
      (*labels)[i] = GroundLabel::kObstacle;
}

/// Per node, the sum of its ground points' x and y and their count.
void ground_sums(const TriGridField& field, const std::vector<GroundLabel>& labels,
                 std::vector<Eigen::Vector3d>* out) {
  std::vector<Eigen::Vector3d>& ground_sum = *out;  // x, y, count
  ground_sum.assign(field.nodes.size(), Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] != GroundLabel::kGround) continue;
    const Eigen::Vector3f& p = field.points[i];
    ground_sum[field.point_node[i]] += Eigen::Vector3d(p.x(), p.y(), 1.0);
  }
}

/// Node k as reported: a traversable node stands where its ground points are (a node cut by
/// a wall or a railing edge has its ground on one side); one left with no ground point is not
/// ground.
GroundNode ground_node(const TriGridNode& node, bool traversable, bool reached, const SmoothedNode& smoothed,
                       const TriGridNode& ground, const Eigen::Vector3d& ground_sum) {
  GroundNode out;
  out.centre = node.centre;
  const double count = ground_sum.z();
  if (traversable && count > 0.0) {
    const float x = static_cast<float>(ground_sum.x() / count),
                y = static_cast<float>(ground_sum.y() / count);
    out.centre = Eigen::Vector3f(x, y, ground.height_at(x, y));
    out.traversable = true;
  }
  out.normal = smoothed.has_surface ? smoothed.normal : node.normal;
  out.probability = smoothed.probability;
  out.num_points = node.num_points;
  out.ground_like = node.ground_like;
  out.reached = reached;
  return out;
}

}  // namespace

GroundScan segment_ground(const PointCloud& cloud, const Eigen::Matrix3d& R_map_sensor,
                          const GroundConfig& config) {
  thread_local Workspace ws;
  GroundScan scan;
  scan.R_level_sensor = level_rotation(R_map_sensor);
  TriGridField& field = ws.field;
  build_tri_grid_field(cloud, scan.R_level_sensor, config, &field);
  const std::vector<int> seeds = find_seed_nodes(field, config);
  const std::vector<std::uint8_t> reached = search_traversable(&field, seeds, config);
  std::vector<SmoothedNode>& smoothed = ws.smoothed;
  bgk_smooth(field, reached, config, &smoothed);
  const std::vector<std::uint8_t> traversable = decide_traversable(field, smoothed, seeds, config);
  ground_planes(field, traversable, reached, smoothed, &ws.ground);

  // A ground-band point under obstacle returns that rise from it (within foot_radius and
  // foot_height) is the foot of a wall or a box.
  nearest_traversable(field.grid, traversable, &ws.nearest, &ws.queue);
  scan.labels.assign(cloud.size(), GroundLabel::kOther);
  ws.feet.reset(config.foot_radius, config.max_range);
  label_points(field, traversable, ws.ground, ws.nearest, config, &scan.labels, &ws.feet);
  ws.feet.index();
  label_feet(field, ws.feet, &scan.labels);

  ground_sums(field, scan.labels, &ws.ground_sum);
  for (std::size_t k = 0; k < field.nodes.size(); ++k) {
    const TriGridNode& node = field.nodes[k];
    if (node.state == NodeState::kEmpty) continue;
    scan.nodes.push_back(
        ground_node(node, traversable[k] != 0, reached[k] != 0, smoothed[k], ws.ground[k], ws.ground_sum[k]));
  }
  return scan;
}

}  // namespace tsgraphs::ground
