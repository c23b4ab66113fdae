#include "tsgraphs/graph/situational_graph.hpp"

#include <stdexcept>

namespace tsgraphs::graph {

int SituationalGraph::add_keyframe(KeyframeNode node) {
  node.id = static_cast<int>(keyframes_.size());
  keyframes_.push_back(node);
  return node.id;
}

int SituationalGraph::add_plane(const Plane& plane, bool vertical) {
  PlaneNode node;
  node.id = next_plane_id_++;
  node.plane = plane;
  node.vertical = vertical;
  planes_.emplace(node.id, node);
  return node.id;
}

void SituationalGraph::merge_planes(int keep, int drop) {
  if (keep == drop || !planes_.count(keep) || !planes_.count(drop))
    throw std::invalid_argument("merge_planes: unknown plane or keep == drop");
  for (PlaneEdge& e : plane_edges_)
    if (e.plane == drop) e.plane = keep;
  planes_.erase(drop);
}

}  // namespace tsgraphs::graph
