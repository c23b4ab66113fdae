#include "tsgraphs/rooms/room_flush_trigger.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Eigenvalues>

namespace tsgraphs::rooms {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

/// Length of the run of sorted `values` around the one nearest 0, where consecutive values are
/// at most `max_gap` apart.
double run_through_zero(std::vector<double> values, double max_gap) {
  std::sort(values.begin(), values.end());
  std::size_t start = 0;
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (std::abs(values[i]) < std::abs(values[start])) start = i;
  }
  std::size_t lo = start;
  while (lo > 0 && values[lo] - values[lo - 1] <= max_gap) --lo;
  std::size_t hi = start;
  while (hi + 1 < values.size() && values[hi + 1] - values[hi] <= max_gap) ++hi;
  return values[hi] - values[lo];
}

}  // namespace

AisleMeasurement measure_aisle(const std::vector<Eigen::Vector3d>& cluster, const Eigen::Vector3d& robot,
                               const AisleMeasureConfig& config) {
  AisleMeasurement out;
  const Vec2 r = robot.head<2>();
  std::vector<Vec2> near;
  for (const Eigen::Vector3d& p : cluster) {
    if ((p.head<2>() - r).norm() <= config.neighbourhood_radius) near.push_back(p.head<2>());
  }
  if (static_cast<int>(near.size()) < config.min_points) return out;

  Vec2 mean = Vec2::Zero();
  for (const Vec2& q : near) mean += q;
  mean /= static_cast<double>(near.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Vec2& q : near) cov += (q - mean) * (q - mean).transpose();
  cov /= static_cast<double>(near.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);  // eigenvalues ascending
  Vec2 dir = eig.eigenvectors().col(1);
  if (dir.x() < 0.0 || (dir.x() == 0.0 && dir.y() < 0.0)) dir = -dir;  // one sign for one axis
  const double minor = std::max(eig.eigenvalues()(0), 0.0);
  const double major = std::max(eig.eigenvalues()(1), 0.0);
  out.direction = dir;
  out.direction_defined = major > 0.0 && std::sqrt(major) >= config.min_anisotropy * std::sqrt(minor);

  const Vec2 across(-dir.y(), dir.x());
  std::vector<double> section;
  for (const Eigen::Vector3d& p : cluster) {
    const Vec2 q = p.head<2>() - r;
    if (std::abs(q.dot(dir)) <= config.slice_half_width) section.push_back(q.dot(across));
  }
  if (section.empty()) return out;
  out.width = run_through_zero(std::move(section), config.max_gap);
  out.valid = true;
  return out;
}

RoomFlushTrigger::RoomFlushTrigger(RoomFlushConfig config) : config_(config) {}

FlushReason RoomFlushTrigger::update(const AisleMeasurement& aisle, bool passed_doorway) {
  if (!aisle.valid) return FlushReason::none;
  if (widths_.empty()) {
    start_segment(aisle);
    return FlushReason::none;
  }
  FlushReason reason = FlushReason::none;
  const double median = segment_median_width();
  if (passed_doorway) {
    reason = FlushReason::doorway;
  } else if (std::abs(aisle.width - median) > config_.width_change_ratio * median) {
    reason = FlushReason::width_change;
  } else if (aisle.direction_defined && axis_sum_.norm() > 0.0) {
    const double c = std::min(1.0, std::abs(aisle.direction.dot(axis_sum_.normalized())));
    if (std::acos(c) * kRadToDeg > config_.direction_change_deg) reason = FlushReason::direction_change;
  }
  if (reason == FlushReason::none) {
    accumulate(aisle);
  } else {
    start_segment(aisle);
  }
  return reason;
}

void RoomFlushTrigger::reset() {
  widths_.clear();
  axis_sum_ = Vec2::Zero();
}

double RoomFlushTrigger::segment_median_width() const {
  if (widths_.empty()) return 0.0;
  std::vector<double> sorted = widths_;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t mid = sorted.size() / 2;
  return sorted.size() % 2 == 1 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
}

void RoomFlushTrigger::start_segment(const AisleMeasurement& aisle) {
  reset();
  accumulate(aisle);
}

void RoomFlushTrigger::accumulate(const AisleMeasurement& aisle) {
  widths_.push_back(aisle.width);
  if (!aisle.direction_defined) return;
  // Directions are axes: align each with the running sum before adding it.
  axis_sum_ += aisle.direction.dot(axis_sum_) < 0.0 ? -aisle.direction : aisle.direction;
}

}  // namespace tsgraphs::rooms
