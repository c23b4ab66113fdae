#pragma once
/// The situational graph's variables and factors as plain data (no solver types): keyframes,
/// plane landmarks, odometry, keyframe-plane and loop-closure edges. Rooms and floors join in
/// later layers. GraphOptimizer solves it in place.
#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <vector>

#include "tsgraphs/core/plane.hpp"
#include "tsgraphs/core/pose.hpp"

namespace tsgraphs::graph {

struct KeyframeNode {
  int id = -1;
  std::size_t scan_index = 0;   ///< index of the scan in the input sequence
  double stamp = 0.0;           ///< s
  Pose3 pose = Pose3::Identity();   ///< current estimate, map <- keyframe (sensor)
  Pose3 odom = Pose3::Identity();   ///< the input odometry at this keyframe
  double accum_distance = 0.0;  ///< odometry distance travelled from the start (m)
};

struct PlaneNode {
  int id = -1;
  Plane plane;          ///< map frame, S-Graphs sign convention (normal towards its observers)
  bool vertical = true; ///< wall face; false: floor or ceiling
};

/// Relative pose measurement T_from_to between keyframes (odometry or loop closure).
struct BetweenEdge {
  int from = -1, to = -1;
  Pose3 measurement = Pose3::Identity();  ///< T_from_to
  double fitness = 0.0;                   ///< registration fitness (loop closures)
};

/// A plane measured in a keyframe's frame.
struct PlaneEdge {
  int keyframe = -1, plane = -1;
  Plane measurement;  ///< keyframe frame
  int num_inliers = 0;
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
  /// Removes plane `drop`, re-pointing its edges at `keep`.
  void merge_planes(int keep, int drop);

  std::vector<KeyframeNode>& keyframes() { return keyframes_; }
  const std::vector<KeyframeNode>& keyframes() const { return keyframes_; }
  std::map<int, PlaneNode>& planes() { return planes_; }
  const std::map<int, PlaneNode>& planes() const { return planes_; }
  const std::vector<BetweenEdge>& odometry_edges() const { return odometry_; }
  const std::vector<BetweenEdge>& loop_edges() const { return loops_; }
  const std::vector<PlaneEdge>& plane_edges() const { return plane_edges_; }

 private:
  std::vector<KeyframeNode> keyframes_;
  std::map<int, PlaneNode> planes_;
  int next_plane_id_ = 0;
  std::vector<BetweenEdge> odometry_;
  std::vector<BetweenEdge> loops_;
  std::vector<PlaneEdge> plane_edges_;
};

}  // namespace tsgraphs::graph
