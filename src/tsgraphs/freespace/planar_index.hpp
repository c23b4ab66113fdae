#pragma once
/// Horizontal (x, y) neighbour search over a fixed set of 3-D points: a nanoflann kd-tree on
/// their projections. Used by the free-space graph (node neighbours, obstacles near a node) and
/// by the obstacle selection (ground nodes under a point).
#include <Eigen/Core>
#include <memory>
#include <vector>

namespace tsgraphs::freespace {

class PlanarIndex {
 public:
  /// Copies the horizontal coordinates of `points`; indices refer to this vector.
  explicit PlanarIndex(const std::vector<Eigen::Vector3d>& points);
  ~PlanarIndex();
  PlanarIndex(const PlanarIndex&) = delete;
  PlanarIndex& operator=(const PlanarIndex&) = delete;

  /// Indices of the points strictly closer than `radius` to p horizontally, increasing
  /// (replaces the content of `out`).
  void within(const Eigen::Vector3d& p, double radius, std::vector<int>& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tsgraphs::freespace
