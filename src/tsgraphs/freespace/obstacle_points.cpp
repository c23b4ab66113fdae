#include "tsgraphs/freespace/obstacle_points.hpp"

#include "tsgraphs/freespace/planar_index.hpp"

namespace tsgraphs::freespace {

std::vector<Eigen::Vector3d> select_obstacles(const std::vector<Eigen::Vector3d>& points, const GroundHeight& ground_height,
                                              const TraversableFreeSpaceConfig& config) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    const std::optional<double> ground = ground_height(p);
    if (!ground) continue;
    const double h = p.z() - *ground;
    if (h > config.obstacle_min_height && h <= config.obstacle_max_height) out.push_back(p);
  }
  return out;
}

std::vector<Eigen::Vector3d> select_obstacles(const std::vector<Eigen::Vector3d>& points,
                                              const std::vector<Eigen::Vector3d>& nodes,
                                              const TraversableFreeSpaceConfig& config) {
  // A radius of 0 or less finds no ground: any cell does for the index.
  const PlanarIndex index(nodes, config.ground_search_radius > 0.0 ? config.ground_search_radius : 1.0);
  const GroundHeight highest_node_below = [&](const Eigen::Vector3d& p) -> std::optional<double> {
    std::optional<double> ground;
    index.visit_within(p, config.ground_search_radius, [&](int i) {
      const double z = nodes[static_cast<std::size_t>(i)].z();
      if (z <= p.z() && (!ground || z > *ground)) ground = z;
      return true;
    });
    return ground;
  };
  return select_obstacles(points, highest_node_below, config);
}

}  // namespace tsgraphs::freespace
