#include "tsgraphs/graph/situational_graph.hpp"

#include <algorithm>
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
  for (RoomPlanesEdge& e : room_edges_)
    std::replace(e.planes.begin(), e.planes.end(), drop, keep);
  room_edges_.erase(std::remove_if(room_edges_.begin(), room_edges_.end(), names_a_plane_twice),
                    room_edges_.end());
  planes_.erase(drop);
}

int SituationalGraph::add_room(const RoomNode& room) {
  RoomNode node = room;
  node.id = next_room_id_++;
  rooms_.emplace(node.id, node);
  return node.id;
}

int SituationalGraph::add_floor(const FloorNode& floor) {
  if (floor_of_level(floor.level) >= 0)
    throw std::invalid_argument("add_floor: level " + std::to_string(floor.level) +
                                " has a floor");
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
