#pragma once
/// The situational graph's variables and factors as plain data (no solver types): keyframes,
/// plane landmarks, rooms and corridor segments, floors; odometry, keyframe-plane, loop-closure,
/// room-planes and floor-room edges. GraphOptimizer solves it in place.
#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <vector>

#include "tsgraphs/core/plane.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/core/room_kind.hpp"

namespace tsgraphs::graph {

struct KeyframeNode {
  int id = -1;
  std::size_t scan_index = 0;      ///< index of the scan in the input sequence
  double stamp = 0.0;              ///< s
  Pose3 pose = Pose3::Identity();  ///< current estimate, map <- keyframe (sensor)
  Pose3 odom = Pose3::Identity();  ///< the input odometry at this keyframe
  double accum_distance = 0.0;     ///< odometry distance travelled from the start (m)
  /// Retired (keyframe_retirement.hpp): out of the factors, which were folded into its
  /// neighbours'; its pose follows an older keyframe's, pose = anchor's pose * T_anchor_keyframe.
  bool retired = false;
  int anchor = -1;
  Pose3 T_anchor_keyframe = Pose3::Identity();
};

struct PlaneNode {
  int id = -1;
  Plane plane;           ///< map frame, S-Graphs sign convention (normal towards its observers)
  bool vertical = true;  ///< wall face; false: floor or ceiling
};

/// Standard deviations of a relative pose measurement, isotropic in translation and rotation.
struct PoseSigmas {
  double trans = 0.0;    ///< m
  double rot_deg = 0.0;  ///< deg
};

/// Relative pose measurement T_from_to between keyframes (odometry or loop closure).
struct BetweenEdge {
  int from = -1, to = -1;
  Pose3 measurement = Pose3::Identity();  ///< T_from_to
  double fitness = 0.0;                   ///< registration fitness (loop closures)
  /// Its own noise when retired keyframes were folded into it (`folded` of them); zero: the
  /// optimizer's configured sigmas for its kind.
  PoseSigmas sigmas = {};
  int folded = 0;
};

/// A plane measured in a keyframe's frame.
struct PlaneEdge {
  int keyframe = -1, plane = -1;
  Plane measurement;  ///< keyframe frame
  int num_inliers = 0;
};

/// Planes a room-planes edge of this kind names: 4 for a room (two facing pairs), 2 for a
/// corridor segment (one facing pair).
inline std::size_t planes_of(RoomKind kind) { return kind == RoomKind::room ? 4 : 2; }

struct RoomNode {
  int id = -1;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< current estimate, map x-y (m)
  int level = 0;                                     ///< storey index
  RoomKind kind = RoomKind::room;
};

/// One per storey, at the mean of its rooms' centres.
struct FloorNode {
  int id = -1;
  int level = 0;                                     ///< storey index
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< current estimate, map x-y (m)
};

/// A room's walls (S-Graphs' room-4-planes / room-2-planes factor): the centre lies on the
/// mid-plane of each facing pair. Planes are vertical, normals into the room.
struct RoomPlanesEdge {
  int room = -1;
  RoomKind kind = RoomKind::room;
  /// room: 4 ids, the first pair then the second pair; corridor: 2 ids, the one pair.
  std::vector<int> planes;
  /// Corridor only: the measured centre (the free-space cluster's), map x-y; only its position
  /// along the corridor counts, the midline fixes the rest.
  Eigen::Vector2d cluster_center = Eigen::Vector2d::Zero();
};

struct FloorRoomEdge {
  int floor = -1, room = -1;
};

class SituationalGraph {
 public:
  /// Adds a keyframe; its id is its index. The first keyframe is the anchor (held fixed).
  int add_keyframe(KeyframeNode node);
  /// Adds a plane landmark with the next free id.
  int add_plane(const Plane& plane, bool vertical);
  void add_odometry_edge(const BetweenEdge& edge) { odometry_.push_back(edge); }
  void add_loop_edge(const BetweenEdge& edge) { loops_.push_back(edge); }
  void add_plane_edge(const PlaneEdge& edge) { plane_edges_.push_back(edge); }
  /// Removes plane `drop`, re-pointing its edges at `keep`. A room edge that would then name one
  /// plane twice no longer describes a room and is removed.
  void merge_planes(int keep, int drop);

  /// Retires keyframe `id` (keyframe_retirement.hpp says which): its plane edges are dropped
  /// (what it saw, earlier keyframes hold), its odometry edges in and out become one edge from
  /// its predecessor to its successor, and each loop edge naming it is moved to its successor,
  /// composed with the odometry between them. Composing A then B adds the variances, and the
  /// translation's gets A's rotation variance times |t_B|^2 (the lever arm), an isotropic
  /// bound of the exact propagation (`odometry` and `loop`: the sigmas of edges without their own).
  /// Of the loop edges folded onto one keyframe only the most certain stays. Its pose then
  /// follows keyframe `anchor`. Throws std::invalid_argument unless `id` is retired-able: not
  /// the first, not retired, with one odometry edge in and one out; and `anchor` < `id` is a
  /// keyframe that is not retired.
  void retire_keyframe(int id, int anchor, const PoseSigmas& odometry, const PoseSigmas& loop);
  /// Sets every retired keyframe's pose from its anchor's (after an optimisation).
  void update_retired_poses();
  /// Keyframes not retired.
  std::size_t num_active_keyframes() const { return keyframes_.size() - num_retired_; }

  /// Adds a room with the next free id (ids are never reused).
  int add_room(const RoomNode& room);
  /// Adds the floor of `floor.level` with the next free id; throws std::invalid_argument when
  /// that level has one.
  int add_floor(const FloorNode& floor);
  /// Id of the floor of `level`, -1 if none.
  int floor_of_level(int level) const;
  /// Throws std::invalid_argument for an unknown room or plane, a plane count that does not fit
  /// the kind (4 or 2), or a plane named twice.
  void add_room_edge(const RoomPlanesEdge& edge);
  /// Joins a room to a floor (once: a repeated pair is ignored); throws std::invalid_argument
  /// for an unknown floor or room.
  void add_floor_room_edge(const FloorRoomEdge& edge);
  /// Removes a room and every edge to it.
  void remove_room(int id);
  /// Removes a floor and its floor-room edges.
  void remove_floor(int id);
  /// Removes room `drop`, re-pointing its edges at `keep` (a floor edge `keep` already has is
  /// not repeated).
  void merge_rooms(int keep, int drop);

  std::vector<KeyframeNode>& keyframes() { return keyframes_; }
  const std::vector<KeyframeNode>& keyframes() const { return keyframes_; }
  std::map<int, PlaneNode>& planes() { return planes_; }
  const std::map<int, PlaneNode>& planes() const { return planes_; }
  const std::vector<BetweenEdge>& odometry_edges() const { return odometry_; }
  const std::vector<BetweenEdge>& loop_edges() const { return loops_; }
  const std::vector<PlaneEdge>& plane_edges() const { return plane_edges_; }
  std::map<int, RoomNode>& rooms() { return rooms_; }
  const std::map<int, RoomNode>& rooms() const { return rooms_; }
  std::map<int, FloorNode>& floors() { return floors_; }
  const std::map<int, FloorNode>& floors() const { return floors_; }
  const std::vector<RoomPlanesEdge>& room_edges() const { return room_edges_; }
  const std::vector<FloorRoomEdge>& floor_room_edges() const { return floor_room_edges_; }

 private:
  std::vector<KeyframeNode> keyframes_;
  std::size_t num_retired_ = 0;
  std::map<int, PlaneNode> planes_;
  int next_plane_id_ = 0;
  std::vector<BetweenEdge> odometry_;
  std::vector<BetweenEdge> loops_;
  std::vector<PlaneEdge> plane_edges_;
  std::map<int, RoomNode> rooms_;
  std::map<int, FloorNode> floors_;
  int next_room_id_ = 0, next_floor_id_ = 0;
  std::vector<RoomPlanesEdge> room_edges_;
  std::vector<FloorRoomEdge> floor_room_edges_;
};

}  // namespace tsgraphs::graph
