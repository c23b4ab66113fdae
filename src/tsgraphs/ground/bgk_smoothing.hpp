#pragma once
/// Bayesian generalised kernel (BGK) smoothing of the tri-grid over neighbouring nodes, with
/// the sparse kernel of Melkumyan & Ramos (2009) as in Shan et al. (BGK terrain mapping, 2018)
/// and B-TMS (Oh et al. 2024): a smoothed ground height and normal from the reached nodes,
/// and a traversability probability from every modelled node. An isolated misclassified floor
/// node among traversable ones is restored and an isolated traversable blip among non-ground
/// is removed; smoothing never adds a node that is cut off from the robot's region or whose
/// own height is off the smoothed surface (a void, a bench top).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/ground/tri_grid_ground.hpp"

namespace tsgraphs::ground {

/// The sparse kernel: 1 at distance 0, falling smoothly to 0 at `length_scale` and 0 beyond.
double sparse_kernel(double distance, double length_scale);

/// The smoothed state of one node.
struct SmoothedNode {
  bool has_surface = false;  ///< a reached node lies within the kernel's support
  float height = 0.0f;       ///< smoothed ground height at the node's centroid (reached nodes' planes)
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< smoothed ground normal
  float probability = 0.5f;                           ///< smoothed traversability in [0, 1]
};

/// BGK over the nodes within bgk_length_scale (centroid to centroid) of each non-empty node:
/// probability = (sum k y + bgk_prior / 2) / (sum k + bgk_prior) over modelled nodes (y = 1
/// when reached); height and normal: kernel-weighted means over reached nodes, each plane
/// evaluated at the node's centroid. Empty nodes keep the defaults.
std::vector<SmoothedNode> bgk_smooth(const TriGridField& field, const std::vector<std::uint8_t>& reached,
                                     const GroundConfig& config);
/// The same into `smoothed`, reusing its buffer.
void bgk_smooth(const TriGridField& field, const std::vector<std::uint8_t>& reached,
                const GroundConfig& config, std::vector<SmoothedNode>* smoothed);

/// The own height of a node that smoothing compares with the smoothed surface: its plane at
/// the centroid when ground-like, else its robust lowest level.
float node_level(const TriGridNode& node);

/// The final decision: a node that is unknown or ground-like (a node whose own plane is steep
/// is never restored) is traversable when its smoothed probability is at least
/// th_traversable, its own height is within bgk_max_height_gap of the smoothed surface, and
/// it is linked (NodeLinker) through such nodes to a seed.
std::vector<std::uint8_t> decide_traversable(const TriGridField& field,
                                             const std::vector<SmoothedNode>& smoothed,
                                             const std::vector<int>& seeds, const GroundConfig& config);

}  // namespace tsgraphs::ground
