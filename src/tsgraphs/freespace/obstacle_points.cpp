#include "tsgraphs/freespace/obstacle_points.hpp"

#include <algorithm>

#include "tsgraphs/freespace/planar_index.hpp"

namespace tsgraphs::freespace {

std::vector<Eigen::Vector3d> select_obstacles(const std::vector<Eigen::Vector3d>& points,
                                              const GroundHeight& ground_height,
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
  // The nodes highest first, so that within a grid cell the first one at or below a point and
  // near enough is that cell's answer (most of a cell's nodes are never looked at).
  std::vector<Eigen::Vector3d> by_height;  // a node with a NaN is never anyone's ground
  by_height.reserve(nodes.size());
  for (const Eigen::Vector3d& n : nodes)
    if (n.allFinite()) by_height.push_back(n);
  if (by_height.empty()) return {};  // no ground anywhere: no obstacle
  std::stable_sort(by_height.begin(), by_height.end(),
                   [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.z() > b.z(); });
  // A radius of 0 or less finds no ground: any cell does for the index.
  const PlanarIndex index(by_height, config.ground_search_radius > 0.0 ? config.ground_search_radius : 1.0);
  const double r2 = config.ground_search_radius * config.ground_search_radius;
  const double top = by_height.front().z(), bottom = by_height.back().z();
  const GroundHeight highest_node_below = [&](const Eigen::Vector3d& p) -> std::optional<double> {
    std::optional<double> ground;
    // Higher above every node than an obstacle reaches (the ceiling), or no higher above any
    // than the floor's roughness: no obstacle whatever its ground, so none is looked for.
    if (p.z() - top > config.obstacle_max_height || p.z() - bottom <= config.obstacle_min_height)
      return ground;
    index.visit_cells(p, config.ground_search_radius, [&](const int* first, const int* last) {
      // Past the nodes above p (a binary search on the cell's heights, highest first)...
      const int* i = std::partition_point(
          first, last, [&](int k) { return by_height[static_cast<std::size_t>(k)].z() > p.z(); });
      // ...the first near enough is the highest of the cell; none lower can beat what is found.
      for (; i != last; ++i) {
        const double z = by_height[static_cast<std::size_t>(*i)].z();
        if (ground && z <= *ground) break;
        if (index.squared_distance(p, *i) < r2) {
          ground = z;
          break;
        }
      }
      return true;
    });
    return ground;
  };
  return select_obstacles(points, highest_node_below, config);
}

}  // namespace tsgraphs::freespace
