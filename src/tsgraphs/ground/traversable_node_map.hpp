#pragma once
/// The global traversable node map (DESIGN.md step 4): the traversable nodes of every
/// keyframe fused in the map frame, on a hashed 2-D grid with height layers (levels). Each
/// node is held in the frame of the keyframe that first saw it, so when optimisation
/// corrects keyframe poses the nodes move with them (global update); revisits fuse into
/// existing nodes, so memory grows with the explored area, not with time.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::ground {

struct NodeMapConfig {
  double cell_size = 0.25;
  double level_tolerance = 0.5;
  int max_keyframes_per_node = 8;
  double min_probability = 0.5;

  template <class V>
  void visit(V& v) {
    v("cell_size", cell_size, between(0.01, 100.0), "m; grid cell of the global map");
    v("level_tolerance", level_tolerance, above(0.0, 100.0),
      "m; observations this near a node's height fuse with it; farther: another layer (storey)");
    v("max_keyframes_per_node", max_keyframes_per_node, between(1, 10000),
      "the most recent keyframes that saw a node, kept per node");
    v("min_probability", min_probability, between(0.0, 1.0),
      "only observations at least this traversable are fused");
  }
};

/// One traversable node observed from a keyframe, in that keyframe's (sensor) frame.
struct NodeObservation {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< on the ground
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double probability = 1.0;  ///< traversability
};

/// A node of the global map.
struct GlobalNode {
  int id = -1;
  int anchor_keyframe = -1;                                 ///< the keyframe whose frame holds it
  Eigen::Vector3d local = Eigen::Vector3d::Zero();          ///< fused position in the anchor's frame
  Eigen::Vector3d local_normal = Eigen::Vector3d::UnitZ();  ///< fused normal in the anchor's frame
  Eigen::Vector3d position = Eigen::Vector3d::Zero();       ///< map frame (anchor pose * local)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();        ///< map frame
  double probability = 0.0;    ///< fused traversability: mean of the observations' probabilities
  int observations = 0;        ///< observations fused; the weight of the means above
  std::vector<int> keyframes;  ///< the most recent keyframes that saw it, oldest first
};

/// The node pointers that the queries return stay valid until the next fuse() or update().
class TraversableNodeMap {
 public:
  /// Throws std::invalid_argument unless cell_size > 0 and level_tolerance >= 0.
  explicit TraversableNodeMap(NodeMapConfig config = {});

  /// Fuses the nodes seen from keyframe `keyframe_id` at pose T_map_keyframe: each observation
  /// joins the node of its cell within level_tolerance of its height (nearest height, then lowest
  /// id) or makes a new node anchored at this keyframe. Observations below min_probability, with a
  /// non-finite position or a zero or non-finite normal are skipped. Fusing a known keyframe with
  /// another pose first moves the nodes it anchors, as update() would.
  void fuse(int keyframe_id, const Pose3& T_map_keyframe, const std::vector<NodeObservation>& nodes);
  /// Global update after optimisation: every node moves with its anchor keyframe; nodes that
  /// come to share a cell and a layer are merged into the lower id (merged ids are never reused,
  /// and the merged node's storage is released).
  /// `keyframe_pose` is called once for every keyframe fused so far.
  void update(const std::function<Pose3(int)>& keyframe_pose);

  /// Nodes within `radius` (horizontal) of `p` and within level_tolerance of its height, nearest first
  /// (ties by id).
  std::vector<const GlobalNode*> nodes_near(const Eigen::Vector3d& p, double radius) const;
  /// Nodes whose height is in [z_min, z_max] (one level of a building), in id order.
  std::vector<const GlobalNode*> nodes_in_height_range(double z_min, double z_max) const;
  /// Every node, in id order.
  std::vector<const GlobalNode*> nodes() const;
  /// The node with this id, or nullptr (never made, or merged away).
  const GlobalNode* node(int id) const;
  std::size_t size() const { return nodes_.size(); }
  const NodeMapConfig& config() const { return config_; }

 private:
  struct KeyframeRecord {
    Pose3 pose = Pose3::Identity();  ///< latest pose given, by fuse() or update()
    std::uint64_t fused_at = 0;      ///< sequence number of its last fuse(): orders a node's keyframes
  };

  std::uint64_t cell_key(const Eigen::Vector3d& p) const;
  /// The index of the node of cell `key` within level_tolerance of height z (nearest, then lowest
  /// id); -1 if none.
  int find_layer(std::uint64_t key, double z) const;
  void add_to_cell(int index, std::uint64_t key);
  /// Puts keyframe_id last in node.keyframes (once), keeping the max_keyframes_per_node most recent.
  void note_keyframe(GlobalNode& node, int keyframe_id) const;
  /// Folds node `gone` into `keep` (means weighted by observations); the caller drops `gone`.
  void merge(GlobalNode& keep, const GlobalNode& gone) const;

  NodeMapConfig config_;
  std::vector<GlobalNode> nodes_;  ///< the live nodes in id order (update() drops merged ones)
  std::vector<int> next_in_cell_;  ///< by index in nodes_: the next layer of its cell, -1 at the end
  std::unordered_map<std::uint64_t, int>
      cells_;  ///< cell key -> index of the first node of the cell's layers
  std::unordered_map<int, KeyframeRecord> keyframes_;  ///< every keyframe given, by id
  std::uint64_t fuse_calls_ = 0;
  int next_id_ = 0;  ///< ids are never reused
};

}  // namespace tsgraphs::ground
