#include "tsgraphs/freespace/free_space.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace tsgraphs::freespace {

FreeSpace connected_components(const std::vector<Eigen::Vector3d>& positions, const std::vector<bool>& kept,
                               const std::vector<std::vector<int>>& neighbours) {
  FreeSpace out;
  const std::size_t n = positions.size();
  out.cluster_of.assign(n, -1);
  std::vector<int> stack;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (!kept[seed] || out.cluster_of[seed] >= 0) continue;
    const int id = static_cast<int>(out.clusters.size());
    FreeSpaceCluster cluster;
    out.cluster_of[seed] = id;
    stack.assign(1, static_cast<int>(seed));
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      cluster.vertices.push_back(v);
      for (const int w : neighbours[static_cast<std::size_t>(v)]) {
        const auto wi = static_cast<std::size_t>(w);
        if (!kept[wi] || out.cluster_of[wi] >= 0) continue;
        out.cluster_of[wi] = id;
        stack.push_back(w);
      }
    }
    // Deterministic, input-ordered members whatever the traversal order.
    std::sort(cluster.vertices.begin(), cluster.vertices.end());
    cluster.points.reserve(cluster.vertices.size());
    for (const int v : cluster.vertices) cluster.points.push_back(positions[static_cast<std::size_t>(v)]);
    out.clusters.push_back(std::move(cluster));
  }
  return out;
}

void identify_robot_cluster(FreeSpace& free_space, const std::vector<Eigen::Vector3d>& positions,
                            const Eigen::Vector3d& robot, double radius, double height_tolerance) {
  free_space.robot_vertex = -1;
  free_space.robot_cluster = -1;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (free_space.cluster_of[i] < 0) continue;
    const Eigen::Vector3d d = positions[i] - robot;
    if (d.head<2>().norm() > radius || std::abs(d.z()) > height_tolerance) continue;
    const double dist = d.norm();
    if (dist < best) {
      best = dist;
      free_space.robot_vertex = static_cast<int>(i);
    }
  }
  if (free_space.robot_vertex >= 0)
    free_space.robot_cluster = free_space.cluster_of[static_cast<std::size_t>(free_space.robot_vertex)];
}

void compute_robot_path_distance(FreeSpace& free_space, const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<bool>& kept,
                                 const std::vector<std::vector<int>>& neighbours) {
  std::vector<double>& dist = free_space.robot_path_distance;
  dist.assign(positions.size(), std::numeric_limits<double>::infinity());
  if (free_space.robot_vertex < 0) return;
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  dist[static_cast<std::size_t>(free_space.robot_vertex)] = 0.0;
  queue.emplace(0.0, free_space.robot_vertex);
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    const auto vi = static_cast<std::size_t>(v);
    if (d > dist[vi]) continue;
    for (const int w : neighbours[vi]) {
      const auto wi = static_cast<std::size_t>(w);
      if (!kept[wi]) continue;
      const double through = d + (positions[wi] - positions[vi]).norm();
      if (through < dist[wi]) {
        dist[wi] = through;
        queue.emplace(through, w);
      }
    }
  }
}

}  // namespace tsgraphs::freespace
