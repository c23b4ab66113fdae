#pragma once
/// The occupied points of the free-space step (DESIGN.md step 6): points more than
/// obstacle_min_height and at most obstacle_max_height above their local traversable ground
/// (walls, railings, furniture; not the ground, not the ceiling, not a storey seen through a void).
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "tsgraphs/freespace/traversable_free_space.hpp"

namespace tsgraphs::freespace {

/// Height of the ground that point p stands over (map frame), or nullopt where none is known.
using GroundHeight = std::function<std::optional<double>(const Eigen::Vector3d& p)>;

/// The points whose height above ground_height(p) is in (obstacle_min_height, obstacle_max_height],
/// in input order. Points with no known ground are not obstacles.
std::vector<Eigen::Vector3d> select_obstacles(const std::vector<Eigen::Vector3d>& points,
                                              const GroundHeight& ground_height,
                                              const TraversableFreeSpaceConfig& config = {});

/// As above, the local ground of a point being the highest traversable node within
/// ground_search_radius horizontally that is not above the point (the storey it stands on).
std::vector<Eigen::Vector3d> select_obstacles(const std::vector<Eigen::Vector3d>& points,
                                              const std::vector<Eigen::Vector3d>& nodes,
                                              const TraversableFreeSpaceConfig& config = {});

}  // namespace tsgraphs::freespace
