#include "tsgraphs/ground/bgk_smoothing.hpp"

#include <array>
#include <cmath>

#include "tsgraphs/ground/traversable_search.hpp"

namespace tsgraphs::ground {

namespace {

/// Traversability of the prior's pseudo-observations: no evidence either way.
constexpr double kPriorTraversability = 0.5;

/// One entry of the kernel table: a node at (row + d_row, column + d_column, triangle) and its weight.
struct KernelEntry {
  int d_row = 0, d_column = 0, triangle = 0;
  double weight = 0.0;
};

/// The kernel's non-zero weights around a node of each triangle type: node centroids form a
/// lattice, so the weights depend only on the offset and are computed once.
std::array<std::vector<KernelEntry>, 4> kernel_table(const TriGrid& grid, double length_scale) {
  std::array<std::vector<KernelEntry>, 4> table;
  const int reach = static_cast<int>(std::ceil(length_scale / grid.resolution())) + 1;
  const int mid = grid.cells_per_side() / 2;
  for (int t = 0; t < 4; ++t) {
    const Eigen::Vector2d from = grid.centroid(grid.node(mid, mid, t));
    for (int dr = -reach; dr <= reach; ++dr) {
      for (int dc = -reach; dc <= reach; ++dc) {
        for (int u = 0; u < 4; ++u) {
          const int to = grid.node(mid + dr, mid + dc, u);
          if (to < 0) continue;
          const double w = sparse_kernel((grid.centroid(to) - from).norm(), length_scale);
          if (w > 0.0) table[t].push_back({dr, dc, u, w});
        }
      }
    }
  }
  return table;
}

}  // namespace

double sparse_kernel(double distance, double length_scale) {
  if (!(distance < length_scale)) return 0.0;
  const double r = distance / length_scale;
  const double a = 2.0 * M_PI * r;
  return (2.0 + std::cos(a)) / 3.0 * (1.0 - r) + std::sin(a) / (2.0 * M_PI);
}

float node_level(const TriGridNode& node) { return node.ground_like ? node.centre.z() : node.lowest; }

std::vector<SmoothedNode> bgk_smooth(const TriGridField& field, const std::vector<std::uint8_t>& reached,
                                     const GroundConfig& config) {
  std::vector<SmoothedNode> out;
  bgk_smooth(field, reached, config, &out);
  return out;
}

void bgk_smooth(const TriGridField& field, const std::vector<std::uint8_t>& reached,
                const GroundConfig& config, std::vector<SmoothedNode>* smoothed) {
  const TriGrid& grid = field.grid;
  std::vector<SmoothedNode>& out = *smoothed;
  out.assign(field.nodes.size(), SmoothedNode{});
  const auto table = kernel_table(grid, config.bgk_length_scale);
  for (int i = 0; i < static_cast<int>(field.nodes.size()); ++i) {
    const TriGridNode& node = field.nodes[i];
    if (node.state == NodeState::kEmpty) continue;
    const int r = grid.row(i), c = grid.column(i);
    const float x = node.centre.x(), y = node.centre.y();
    double sum_w = 0.0, sum_wy = 0.0, surface_w = 0.0, sum_height = 0.0;
    Eigen::Vector3d sum_normal = Eigen::Vector3d::Zero();
    for (const KernelEntry& e : table[TriGrid::triangle(i)]) {
      const int j = grid.node(r + e.d_row, c + e.d_column, e.triangle);
      if (j < 0) continue;
      const TriGridNode& other = field.nodes[j];
      if (other.state != NodeState::kModelled) continue;
      sum_w += e.weight;
      if (!reached[j]) continue;
      sum_wy += e.weight;
      surface_w += e.weight;
      sum_height += e.weight * other.height_at(x, y);
      sum_normal += e.weight * other.normal.cast<double>();
    }
    SmoothedNode& s = out[i];
    s.probability =
        static_cast<float>((sum_wy + config.bgk_prior * kPriorTraversability) / (sum_w + config.bgk_prior));
    if (surface_w > 0.0) {
      s.has_surface = true;
      s.height = static_cast<float>(sum_height / surface_w);
      s.normal = sum_normal.normalized().cast<float>();
    }
  }
}

std::vector<std::uint8_t> decide_traversable(const TriGridField& field,
                                             const std::vector<SmoothedNode>& smoothed,
                                             const std::vector<int>& seeds, const GroundConfig& config) {
  const std::size_t n = field.nodes.size();
  std::vector<std::uint8_t> candidate(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const TriGridNode& node = field.nodes[i];
    const SmoothedNode& s = smoothed[i];
    if (node.state == NodeState::kEmpty || !s.has_surface) continue;
    // A node whose own plane is steep (a wall, a railing, a slab's edge) is not floor whatever
    // its neighbours say; the floor at a wall's foot joins by the search's adoption instead.
    if (node.state == NodeState::kModelled && !node.ground_like) continue;
    if (s.probability < config.th_traversable) continue;
    if (std::abs(node_level(node) - s.height) > config.bgk_max_height_gap) continue;
    candidate[i] = 1;
  }
  // Only what is linked to the robot's seeds stays.
  const std::vector<std::uint8_t> traversable = flood_from(
      field, seeds, config, [&](int i) { return candidate[i] != 0; }, [](int, int) { return true; });
  return traversable;
}

}  // namespace tsgraphs::ground
