#include "tsgraphs/freespace/planar_index.hpp"

#include <stdexcept>

namespace tsgraphs::freespace {
namespace {

constexpr double kMaxCellsPerPoint = 4.0;  // a sparser grid costs more to build than it saves

}  // namespace

PlanarIndex::PlanarIndex(const std::vector<Eigen::Vector3d>& points, double cell) : cell_(cell) {
  if (!(cell > 0.0) || !std::isfinite(cell))
    throw std::invalid_argument("PlanarIndex: cell must be > 0 and finite");
  xy_.reserve(points.size());
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = -lo;
  for (const Eigen::Vector3d& p : points) {
    xy_.push_back(p.head<2>());
    if (!p.head<2>().allFinite()) continue;
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  if (!(lo.x() <= hi.x())) {  // no finite point: nothing is ever near
    xy_.clear();
    return;
  }
  const Eigen::Vector2d extent = hi - lo;
  const double budget = kMaxCellsPerPoint * static_cast<double>(points.size()) + 64.0;
  if ((extent.x() / cell_ + 1.0) * (extent.y() / cell_ + 1.0) > budget)
    cell_ = std::max(cell_,
                     std::sqrt(extent.x() * extent.y() / budget) + std::max(extent.x(), extent.y()) / budget);
  origin_ = lo;
  cols_ = static_cast<long>(std::floor(extent.x() / cell_)) + 1;
  rows_ = static_cast<long>(std::floor(extent.y() / cell_)) + 1;
  // Counting sort by cell, stable: indices increase within a cell.
  std::vector<long> key(xy_.size(), -1);
  start_.assign(static_cast<std::size_t>(cols_ * rows_) + 1, 0);
  for (std::size_t i = 0; i < xy_.size(); ++i) {
    if (!xy_[i].allFinite()) continue;
    const long c = std::min(cols_ - 1, static_cast<long>(std::floor((xy_[i].x() - origin_.x()) / cell_)));
    const long r = std::min(rows_ - 1, static_cast<long>(std::floor((xy_[i].y() - origin_.y()) / cell_)));
    key[i] = r * cols_ + c;
    ++start_[static_cast<std::size_t>(key[i]) + 1];
  }
  for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
  order_.resize(start_.back());
  std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < xy_.size(); ++i)
    if (key[i] >= 0) order_[next[static_cast<std::size_t>(key[i])]++] = static_cast<int>(i);
}

void PlanarIndex::within(const Eigen::Vector3d& p, double radius, std::vector<int>& out) const {
  out.clear();
  visit_within(p, radius, [&out](int i) {
    out.push_back(i);
    return true;
  });
  std::sort(out.begin(), out.end());
}

}  // namespace tsgraphs::freespace
