#pragma once
/// The result shared by both free-space methods (DESIGN.md step 6 and the S-Graphs+ baseline):
/// candidate vertices (traversable node centres, or the cells of an ESDF slice), the ones
/// kept grouped into connected components (free-space clusters), and which cluster holds the robot.
#include <Eigen/Core>
#include <vector>

namespace tsgraphs::freespace {

/// One connected component of kept vertices.
struct FreeSpaceCluster {
  std::vector<int> vertices;            ///< candidate vertex indices, increasing
  std::vector<Eigen::Vector3d> points;  ///< their positions (map frame), same order
};

struct FreeSpace {
  std::vector<FreeSpaceCluster> clusters;  ///< ordered by their smallest vertex index
  std::vector<int> cluster_of;             ///< per candidate vertex: its cluster, -1 if removed (or not free)
  int robot_vertex = -1;                   ///< the kept vertex identified as the robot's, -1 if none near it
  int robot_cluster = -1;                  ///< the cluster containing robot_vertex, -1 if none
  /// Per candidate vertex: the length of the shortest path to it from robot_vertex through kept
  /// vertices (m), infinity where there is none. Unlike straight-line distance it does not
  /// reach through a wall into the next room, only round it, through the door.
  std::vector<double> robot_path_distance;

  /// The robot's cluster, or nullptr.
  const FreeSpaceCluster* robot() const {
    return robot_cluster >= 0 ? &clusters[static_cast<std::size_t>(robot_cluster)] : nullptr;
  }
};

/// Groups the kept vertices into connected components. `neighbours[i]` are the vertices joined
/// to i by an edge (both directions must be listed); `kept[i]` says whether i survives;
/// `positions[i]` is its position. Fills clusters and cluster_of; robot fields are left at -1.
FreeSpace connected_components(const std::vector<Eigen::Vector3d>& positions, const std::vector<bool>& kept,
                               const std::vector<std::vector<int>>& neighbours);

/// Sets robot_vertex and robot_cluster: among kept vertices within `radius` horizontally of
/// `robot` and within `height_tolerance` of its height, the one nearest in 3-D (ties: lowest index).
void identify_robot_cluster(FreeSpace& free_space, const std::vector<Eigen::Vector3d>& positions,
                            const Eigen::Vector3d& robot, double radius, double height_tolerance);

/// Fills robot_path_distance (Dijkstra over the edges of `neighbours` between kept vertices,
/// each as long as the distance between its ends); all infinity without a robot vertex.
void compute_robot_path_distance(FreeSpace& free_space, const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<bool>& kept,
                                 const std::vector<std::vector<int>>& neighbours);

}  // namespace tsgraphs::freespace
