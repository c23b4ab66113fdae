#include "tsgraphs/graph/situational_graph.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

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

namespace {

constexpr double kDegToRad = M_PI / 180.0;

PoseSigmas sigmas_of(const BetweenEdge& e, const PoseSigmas& fallback) {
  return e.folded > 0 ? e.sigmas : fallback;
}

// The noise of A then B, B's translation being `lever` (see retire_keyframe's comment).
PoseSigmas compose(const PoseSigmas& a, const PoseSigmas& b, double lever) {
  const double rot_a = a.rot_deg * kDegToRad;
  return {std::sqrt(a.trans * a.trans + b.trans * b.trans + rot_a * rot_a * lever * lever),
          std::sqrt(a.rot_deg * a.rot_deg + b.rot_deg * b.rot_deg)};
}

bool names_a_plane_twice(const RoomPlanesEdge& e) {
  std::vector<int> ids = e.planes;
  std::sort(ids.begin(), ids.end());
  return std::adjacent_find(ids.begin(), ids.end()) != ids.end();
}

}  // namespace

void SituationalGraph::merge_planes(int keep, int drop) {
  if (keep == drop || !planes_.count(keep) || !planes_.count(drop))
    throw std::invalid_argument("merge_planes: unknown plane or keep == drop");
  for (PlaneEdge& e : plane_edges_)
    if (e.plane == drop) e.plane = keep;
  for (RoomPlanesEdge& e : room_edges_) std::replace(e.planes.begin(), e.planes.end(), drop, keep);
  room_edges_.erase(std::remove_if(room_edges_.begin(), room_edges_.end(), names_a_plane_twice),
                    room_edges_.end());
  planes_.erase(drop);
}

void SituationalGraph::retire_keyframe(int id, int anchor, const PoseSigmas& odometry,
                                       const PoseSigmas& loop) {
  const int n = static_cast<int>(keyframes_.size());
  if (id <= 0 || id >= n || keyframes_[id].retired || anchor < 0 || anchor >= id ||
      keyframes_[anchor].retired)
    throw std::invalid_argument("retire_keyframe: keyframe " + std::to_string(id) + " (anchor " +
                                std::to_string(anchor) + ") cannot be retired");
  std::vector<std::size_t> in, out;  // odometry edges into and out of it
  for (std::size_t i = 0; i < odometry_.size(); ++i) {
    if (odometry_[i].to == id) in.push_back(i);
    if (odometry_[i].from == id) out.push_back(i);
  }
  if (in.size() != 1 || out.size() != 1)
    throw std::invalid_argument("retire_keyframe: keyframe " + std::to_string(id) +
                                " needs one odometry edge in and one out");
  const BetweenEdge a = odometry_[in[0]], b = odometry_[out[0]];  // predecessor -> id, id -> successor
  const int successor = b.to;
  const PoseSigmas sb = sigmas_of(b, odometry);

  BetweenEdge joined;
  joined.from = a.from;
  joined.to = successor;
  joined.measurement = a.measurement * b.measurement;
  joined.sigmas = compose(sigmas_of(a, odometry), sb, b.measurement.translation().norm());
  joined.folded = a.folded + b.folded + 1;
  odometry_[in[0]] = joined;
  odometry_.erase(odometry_.begin() + static_cast<std::ptrdiff_t>(out[0]));

  // Loop edges naming it move to its successor: T_o_s = T_o_id * T_id_s, T_s_c = T_id_s^-1 * T_id_c.
  for (BetweenEdge& e : loops_) {
    if (e.to == id) {
      e.sigmas = compose(sigmas_of(e, loop), sb, b.measurement.translation().norm());
      e.measurement = e.measurement * b.measurement;
      e.to = successor;
      ++e.folded;
    } else if (e.from == id) {
      e.sigmas = compose(sb, sigmas_of(e, loop), e.measurement.translation().norm());
      e.measurement = b.measurement.inverse() * e.measurement;
      e.from = successor;
      ++e.folded;
    }
  }
  loops_.erase(
      std::remove_if(loops_.begin(), loops_.end(), [](const BetweenEdge& e) { return e.from == e.to; }),
      loops_.end());
  // Folded loops on the successor: only the most certain stays (each carries odometry noise
  // that grows with every keyframe it is moved past; keeping them all would pile them up).
  const auto folded_on_successor = [successor](const BetweenEdge& e) {
    return e.folded > 0 && (e.from == successor || e.to == successor);
  };
  const auto best =
      std::min_element(loops_.begin(), loops_.end(), [&](const BetweenEdge& x, const BetweenEdge& y) {
        const bool fx = folded_on_successor(x), fy = folded_on_successor(y);
        if (fx != fy) return fx;
        return x.sigmas.trans < y.sigmas.trans;
      });
  if (best != loops_.end() && folded_on_successor(*best)) {
    const BetweenEdge kept = *best;
    loops_.erase(std::remove_if(loops_.begin(), loops_.end(), folded_on_successor), loops_.end());
    loops_.push_back(kept);
  }

  plane_edges_.erase(std::remove_if(plane_edges_.begin(), plane_edges_.end(),
                                    [id](const PlaneEdge& e) { return e.keyframe == id; }),
                     plane_edges_.end());
  KeyframeNode& k = keyframes_[id];
  k.retired = true;
  k.anchor = anchor;
  k.T_anchor_keyframe = keyframes_[anchor].pose.inverse() * k.pose;
  ++num_retired_;
}

void SituationalGraph::update_retired_poses() {
  // Anchors are older than what they anchor: in id order an anchor is set before its keyframes.
  for (KeyframeNode& k : keyframes_)
    if (k.retired) k.pose = keyframes_[k.anchor].pose * k.T_anchor_keyframe;
}

int SituationalGraph::add_room(const RoomNode& room) {
  RoomNode node = room;
  node.id = next_room_id_++;
  rooms_.emplace(node.id, node);
  return node.id;
}

int SituationalGraph::add_floor(const FloorNode& floor) {
  if (floor_of_level(floor.level) >= 0)
    throw std::invalid_argument("add_floor: level " + std::to_string(floor.level) + " has a floor");
  FloorNode node = floor;
  node.id = next_floor_id_++;
  floors_.emplace(node.id, node);
  return node.id;
}

int SituationalGraph::floor_of_level(int level) const {
  for (const auto& [id, floor] : floors_)
    if (floor.level == level) return id;
  return -1;
}

void SituationalGraph::add_room_edge(const RoomPlanesEdge& edge) {
  if (!rooms_.count(edge.room)) throw std::invalid_argument("add_room_edge: unknown room");
  if (edge.planes.size() != planes_of(edge.kind))
    throw std::invalid_argument("add_room_edge: a room names 4 planes, a corridor 2");
  for (int id : edge.planes)
    if (!planes_.count(id)) throw std::invalid_argument("add_room_edge: unknown plane");
  if (names_a_plane_twice(edge)) throw std::invalid_argument("add_room_edge: a plane named twice");
  room_edges_.push_back(edge);
}

void SituationalGraph::add_floor_room_edge(const FloorRoomEdge& edge) {
  if (!floors_.count(edge.floor) || !rooms_.count(edge.room))
    throw std::invalid_argument("add_floor_room_edge: unknown floor or room");
  for (const FloorRoomEdge& e : floor_room_edges_)
    if (e.floor == edge.floor && e.room == edge.room) return;
  floor_room_edges_.push_back(edge);
}

void SituationalGraph::remove_room(int id) {
  if (!rooms_.erase(id)) throw std::invalid_argument("remove_room: unknown room");
  room_edges_.erase(std::remove_if(room_edges_.begin(), room_edges_.end(),
                                   [id](const RoomPlanesEdge& e) { return e.room == id; }),
                    room_edges_.end());
  floor_room_edges_.erase(std::remove_if(floor_room_edges_.begin(), floor_room_edges_.end(),
                                         [id](const FloorRoomEdge& e) { return e.room == id; }),
                          floor_room_edges_.end());
}

void SituationalGraph::remove_floor(int id) {
  if (!floors_.erase(id)) throw std::invalid_argument("remove_floor: unknown floor");
  floor_room_edges_.erase(std::remove_if(floor_room_edges_.begin(), floor_room_edges_.end(),
                                         [id](const FloorRoomEdge& e) { return e.floor == id; }),
                          floor_room_edges_.end());
}

void SituationalGraph::merge_rooms(int keep, int drop) {
  if (keep == drop || !rooms_.count(keep) || !rooms_.count(drop))
    throw std::invalid_argument("merge_rooms: unknown room or keep == drop");
  for (RoomPlanesEdge& e : room_edges_)
    if (e.room == drop) e.room = keep;
  std::vector<FloorRoomEdge> kept;
  for (FloorRoomEdge e : floor_room_edges_) {
    if (e.room == drop) e.room = keep;
    const bool repeated = std::any_of(kept.begin(), kept.end(), [&e](const FloorRoomEdge& k) {
      return k.floor == e.floor && k.room == e.room;
    });
    if (!repeated) kept.push_back(e);
  }
  floor_room_edges_ = std::move(kept);
  rooms_.erase(drop);
}

}  // namespace tsgraphs::graph
