#pragma once
/// Horizontal (x, y) neighbour search over a fixed set of 3-D points: a bucket grid of their
/// projections, its cell the radius it is mostly queried with, so that a query looks at the
/// 3 x 3 cells round the point. Used by the free-space graph (node neighbours, obstacles near a
/// node) and by the obstacle selection (ground nodes under a point); the points lie within the
/// free space's radius of the robot, so the grid is small and dense.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace tsgraphs::freespace {

class PlanarIndex {
 public:
  /// Copies the horizontal coordinates of `points`; indices refer to this vector. `cell` (> 0,
  /// m): the radius of most queries; it is enlarged where the points are spread so far that the
  /// grid would have more cells than a few per point.
  PlanarIndex(const std::vector<Eigen::Vector3d>& points, double cell);

  /// Calls f(i) for each point i strictly closer than `radius` to p horizontally, in no fixed
  /// order, until f returns false.
  template <class F>
  void visit_within(const Eigen::Vector3d& p, double radius, F&& f) const;

  /// Calls f(first, last) for each grid cell that may hold points strictly closer than
  /// `radius` to p horizontally: [first, last) are its point indices, increasing (the caller
  /// tests the distance; points given in a chosen order keep it within a cell), until f
  /// returns false.
  template <class F>
  void visit_cells(const Eigen::Vector3d& p, double radius, F&& f) const;

  /// Horizontal squared distance from p to point i.
  double squared_distance(const Eigen::Vector3d& p, int i) const {
    return (p.head<2>() - xy_[static_cast<std::size_t>(i)]).squaredNorm();
  }

  /// Indices of the points strictly closer than `radius` to p horizontally, increasing
  /// (replaces the content of `out`).
  void within(const Eigen::Vector3d& p, double radius, std::vector<int>& out) const;

 private:
  std::vector<Eigen::Vector2d> xy_;  ///< by point index
  std::vector<int> order_;           ///< point indices by cell, increasing within one
  std::vector<std::size_t> start_;   ///< cell k's points are order_[start_[k] .. start_[k + 1])
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  long cols_ = 0, rows_ = 0;
};

template <class F>
void PlanarIndex::visit_cells(const Eigen::Vector3d& p, double radius, F&& f) const {
  if (xy_.empty() || !(radius > 0.0) || !p.head<2>().allFinite()) return;
  const double reach = std::ceil(radius / cell_);
  const double fc = std::floor((p.x() - origin_.x()) / cell_), fr = std::floor((p.y() - origin_.y()) / cell_);
  const double last_c = static_cast<double>(cols_ - 1), last_r = static_cast<double>(rows_ - 1);
  if (fc + reach < 0.0 || fc - reach > last_c || fr + reach < 0.0 || fr - reach > last_r) return;
  const long c0 = static_cast<long>(std::max(0.0, fc - reach)),
             c1 = static_cast<long>(std::min(last_c, fc + reach));
  const long r0 = static_cast<long>(std::max(0.0, fr - reach)),
             r1 = static_cast<long>(std::min(last_r, fr + reach));
  for (long r = r0; r <= r1; ++r) {
    for (long c = c0; c <= c1; ++c) {
      const std::size_t k = static_cast<std::size_t>(r * cols_ + c);
      if (start_[k] < start_[k + 1] && !f(order_.data() + start_[k], order_.data() + start_[k + 1])) return;
    }
  }
}

template <class F>
void PlanarIndex::visit_within(const Eigen::Vector3d& p, double radius, F&& f) const {
  const double r2 = radius * radius;
  visit_cells(p, radius, [&](const int* first, const int* last) {
    for (const int* i = first; i != last; ++i)
      if (squared_distance(p, *i) < r2 && !f(*i)) return false;
    return true;
  });
}

}  // namespace tsgraphs::freespace
