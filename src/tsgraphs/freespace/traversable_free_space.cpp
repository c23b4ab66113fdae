#include "tsgraphs/freespace/traversable_free_space.hpp"

#include <cmath>
#include <stdexcept>

#include "tsgraphs/freespace/planar_index.hpp"

namespace tsgraphs::freespace {
namespace {

// A vertex is removed when an obstacle point within lambda_th horizontally stands over it:
// at most obstacle_max_height above it, and not below it (the storey under a landing).
bool blocked(const Eigen::Vector3d& vertex, const std::vector<Eigen::Vector3d>& obstacles,
             const PlanarIndex& index, const TraversableFreeSpaceConfig& config) {
  bool over = false;
  index.visit_within(vertex, config.lambda_th, [&](int j) {
    const double dz = obstacles[static_cast<std::size_t>(j)].z() - vertex.z();
    over = dz >= 0.0 && dz <= config.obstacle_max_height;
    return !over;
  });
  return over;
}

}  // namespace

FreeSpace traversable_free_space(const std::vector<Eigen::Vector3d>& nodes,
                                 const std::vector<Eigen::Vector3d>& obstacles, const Eigen::Vector3d& robot,
                                 const TraversableFreeSpaceConfig& config) {
  check_config(config, "traversable_free_space");

  const std::size_t n = nodes.size();
  const PlanarIndex obstacle_index(obstacles, config.lambda_th > 0.0 ? config.lambda_th : config.edge_length);
  std::vector<int> scratch;
  std::vector<bool> kept(n, false);
  for (std::size_t i = 0; i < n; ++i)
    kept[i] = nodes[i].allFinite() && !blocked(nodes[i], obstacles, obstacle_index, config);

  // Edges between kept neighbours only: removing a vertex removes its edges.
  const PlanarIndex node_index(nodes, config.edge_length);
  std::vector<std::vector<int>> neighbours(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!kept[i]) continue;
    node_index.within(nodes[i], config.edge_length, scratch);
    for (const int j : scratch) {
      const auto js = static_cast<std::size_t>(j);
      if (js == i || !kept[js]) continue;
      if (std::abs(nodes[js].z() - nodes[i].z()) <= config.max_height_step) neighbours[i].push_back(j);
    }
  }

  FreeSpace out = connected_components(nodes, kept, neighbours);
  identify_robot_cluster(out, nodes, robot, config.robot_radius, config.robot_height_tolerance);
  compute_robot_path_distance(out, nodes, kept, neighbours);
  return out;
}

}  // namespace tsgraphs::freespace
