#pragma once
/// Breadth-first search of the traversable ground from the robot (TRAVEL's graph search, less
/// its restarts): it starts at ground-like nodes near the robot whose plane passes under the
/// robot at the sensor height, and accepts a linked node only when both are ground-like and
/// the local convexity/concavity test passes, or when the node's points say the reaching
/// ground continues level there (far away a scan ring crosses a node with too few points for
/// a plane of its own). Ground not reached from the robot (a storey
/// seen through a void, a bench top, a floor patch below) is never traversable.
#include <cstdint>
#include <deque>
#include <vector>

#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/ground/tri_grid_ground.hpp"

namespace tsgraphs::ground {

/// How far a link from a node `range` metres from the sensor may reach across empty or unknown
/// nodes: max_gap, or, where longer, the distance to the next floor ring out (a beam
/// ring_spacing_deg flatter, from sensor_height above the floor) plus a cell.
double link_gap(double range, const GroundConfig& config);

/// The links of the node graph: nodes sharing an edge, and, since far from the sensor the
/// floor is seen only on scan rings metres apart, nodes joined by a run of empty or unknown
/// (unmodelled) nodes that stays within link_gap() of the start. Walls stop runs: their nodes
/// have points.
class NodeLinker {
 public:
  NodeLinker(const TriGridField& field, const GroundConfig& config);
  /// The non-empty nodes linked to `node`, in a fixed order (replaces the content of `out`);
  /// returns how many of them, first in `out`, share an edge with `node`.
  int links(int node, std::vector<int>* out);
  /// False for a link across empty nodes (position >= the count links() returned) from or to
  /// a face's foot: such a line is only ground when the ground beside it reaches it.
  static bool usable(const TriGridNode& a, const TriGridNode& b, bool adjacent) {
    return adjacent || (!a.face_foot && !b.face_foot);
  }

 private:
  const TriGridField& field_;
  const GroundConfig& config_;
  std::vector<std::uint32_t> stamp_;  ///< last call that visited each node
  std::uint32_t call_ = 0;
  std::vector<int> queue_;
};

/// Flags, one per node, of the nodes reached from `seeds` over usable links: a node joins when
/// `accept(node)` and the link from a reached node passes `link_ok(from, to)`. The one flood
/// fill of the search and of BGK's connectivity step.
template <class Accept, class LinkOk>
std::vector<std::uint8_t> flood_from(const TriGridField& field, const std::vector<int>& seeds,
                                     const GroundConfig& config, Accept accept, LinkOk link_ok) {
  std::vector<std::uint8_t> reached(field.nodes.size(), 0);
  std::deque<int> queue;
  for (int s : seeds) {
    if (reached[s] || !accept(s)) continue;
    reached[s] = 1;
    queue.push_back(s);
  }
  NodeLinker linker(field, config);
  std::vector<int> links;
  while (!queue.empty()) {
    const int current = queue.front();
    queue.pop_front();
    const int num_adjacent = linker.links(current, &links);
    for (int k = 0; k < static_cast<int>(links.size()); ++k) {
      const int b = links[k];
      if (reached[b] || !accept(b)) continue;
      if (!NodeLinker::usable(field.nodes[current], field.nodes[b], k < num_adjacent)) continue;
      if (!link_ok(current, b)) continue;
      reached[b] = 1;
      queue.push_back(b);
    }
  }
  return reached;
}

/// Ground-like nodes within seed_radius (horizontal) of the robot whose plane, at the robot's
/// (x, y), is within seed_height_tolerance of -sensor_height, whose plane rises at most
/// seed_max_slope per metre, whose own height is within seed_height_tolerance +
/// seed_max_slope * distance of it, and which are no face's foot more than th_dist off it.
/// Ascending node order.
std::vector<int> find_seed_nodes(const TriGridField& field, const GroundConfig& config);

/// TRAVEL's local convexity/concavity test between two modelled nodes with centres c_a, c_b
/// (dmu = |c_b - c_a|): normals agree within 1 - sin(dmu th_lcc_normal), and each centre is
/// within min(dmu sin(th_lcc_planar), th_dist) of the other's plane (the cap keeps a long link
/// across empty nodes from climbing a step).
bool locally_convex(const TriGridNode& a, const TriGridNode& b, const GroundConfig& config);

/// The plane a node `to` that the search cannot join by its own plane (a far scan ring with
/// too few points for one, a wall's foot, a ceiling return outnumbering the floor's) takes
/// from the reached node `from`: level, at from's height. False, and `out` unchanged, unless at
/// least sparse_min_pts of to's points lie within th_dist of that level, no point of to or of
/// the nodes sharing an edge with it lies below (a drop, a void's edge, a stair down, the top
/// of a low wall), and no more of to's points stand above the level, within th_seeds, than lie
/// on it (the foot of something). On success `out` is to as a modelled ground-like node.
bool adopt_plane(const TriGridField& field, const TriGridNode& from, int to, const GroundConfig& config,
                 TriGridNode* out);

/// Reached flags, one per node: the seeds and every ground-like node reached from them over
/// links that pass the local convexity/concavity test, and every node that adopts the level
/// of the node reaching it (adopt_plane), which `field` then holds as modelled. What an adopted
/// node reaches, it reaches by adoption too.
std::vector<std::uint8_t> search_traversable(TriGridField* field, const std::vector<int>& seeds,
                                             const GroundConfig& config);

}  // namespace tsgraphs::ground
