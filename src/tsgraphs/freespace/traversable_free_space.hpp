#pragma once
/// Free space on traversable ground (DESIGN.md step 6, the paper's contribution): a graph whose
/// vertices are the centres of the traversable nodes near the robot and whose edges join
/// neighbouring nodes; vertices closer than lambda_th (horizontally) to an obstacle point are
/// removed; the connected components are the free-space clusters, and the robot's is the one
/// holding the vertex under it. Doorways narrower than 2 lambda_th and railings cut the free
/// space; a void has no traversable ground, so it is never free space.
#include <Eigen/Core>
#include <vector>

#include "tsgraphs/freespace/free_space.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::freespace {

struct TraversableFreeSpaceConfig {
  double edge_length = 0.375;
  double max_height_step = 0.2;
  double lambda_th = 0.4;
  double obstacle_min_height = 0.2;
  double obstacle_max_height = 2.0;
  double ground_search_radius = 0.75;
  double robot_radius = 1.0;
  double robot_height_tolerance = 1.0;

  template <class V>
  void visit(V& v) {
    v("edge_length", edge_length, above(0.0, 100.0),
      "nodes closer than this horizontally are neighbours (m): 1.5 x the node map's 0.25 m cells, so "
      "diagonals join");
    v("max_height_step", max_height_step, between(0.0, 100.0),
      "...if their heights differ by at most this (m): storeys and a bench top stay apart");
    v("lambda_th", lambda_th, between(0.0, 100.0),
      "vertices closer than this (horizontally) to an obstacle point are removed (m): about the robot's half "
      "width");
    v("obstacle_min_height", obstacle_min_height, between(0.0, 100.0),
      "obstacle points: more than this above the local ground (m)...");
    v("obstacle_max_height", obstacle_max_height, above(0.0, 100.0),
      "...and at most this (m): walls, railings, furniture, not the ceiling");
    v.require(obstacle_max_height > obstacle_min_height, "obstacle_max_height",
              "must be > obstacle_min_height");
    v("ground_search_radius", ground_search_radius, between(0.0, 100.0),
      "obstacle selection: the local ground of a point is the highest node at or below it within this "
      "horizontally (m)");
    v("robot_radius", robot_radius, between(0.0, 1000.0),
      "the robot's vertex: nearest kept vertex within this horizontally (m)...");
    v("robot_height_tolerance", robot_height_tolerance, between(0.0, 1000.0),
      "...and within this of the robot position's height (m; covers the sensor's height above the floor)");
  }
};

/// The free space of traversable `nodes` (node centres on the ground, map frame, e.g. from
/// ground::TraversableNodeMap::nodes_near) among `obstacles` (map frame, e.g. from
/// select_obstacles()). A vertex is removed when an obstacle point is closer than lambda_th
/// horizontally and lies above the vertex by at most obstacle_max_height (a railing 1 m up
/// bounds the walkway; the storey above does not empty the one below). Candidate vertex i is
/// nodes[i]. `robot` is the robot's position (sensor or base), map frame.
/// Throws std::invalid_argument unless edge_length > 0, lambda_th >= 0, max_height_step >= 0.
FreeSpace traversable_free_space(const std::vector<Eigen::Vector3d>& nodes,
                                 const std::vector<Eigen::Vector3d>& obstacles, const Eigen::Vector3d& robot,
                                 const TraversableFreeSpaceConfig& config = {});

}  // namespace tsgraphs::freespace
