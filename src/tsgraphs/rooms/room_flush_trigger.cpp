#include "tsgraphs/rooms/room_flush_trigger.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

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

  // The shortest cross-section through the robot; a slice is the cluster points within
  // slice_half_width of the line through the robot across it.
  const int directions = std::max(1, config.width_directions);
  bool measured = false;
  for (int k = 0; k < directions; ++k) {
    const double angle = M_PI * static_cast<double>(k) / static_cast<double>(directions);
    const Vec2 across = Eigen::Rotation2Dd(angle) * Vec2(-dir.y(), dir.x());
    const Vec2 along(across.y(), -across.x());
    std::vector<double> section;
    for (const Eigen::Vector3d& p : cluster) {
      const Vec2 q = p.head<2>() - r;
      if (std::abs(q.dot(along)) <= config.slice_half_width) section.push_back(q.dot(across));
    }
    if (section.empty()) continue;
    const double width = run_through_zero(std::move(section), config.max_gap);
    out.width = measured ? std::min(out.width, width) : width;
    measured = true;
  }
  if (!measured) return out;
  out.valid = true;
  return out;
}

RoomFlushTrigger::RoomFlushTrigger(RoomFlushConfig config) : config_(config) {}

FlushReason RoomFlushTrigger::update(const AisleMeasurement& aisle, bool passed_doorway) {
  if (!aisle.valid) return FlushReason::none;
  carried_ = 1;
  if (widths_.empty() || passed_doorway) {
    const bool flush = !widths_.empty();
    reset();
    accumulate(aisle);
    return flush ? FlushReason::doorway : FlushReason::none;
  }
  const FlushReason reason = judge(aisle);
  if (reason == FlushReason::none) {
    // A blip much narrower than the space on both sides of it is a doorway between two spaces
    // (two rooms, too wide for their width change to count); any other blip joins the segment.
    const double around = std::min(segment_median_width(), aisle.width);
    const bool doorway =
        !pending_.empty() && std::all_of(pending_.begin(), pending_.end(), [&](const AisleMeasurement& a) {
          return a.width < config_.doorway_ratio * around;
        });
    if (doorway) {
      reset();
      accumulate(aisle);
      return FlushReason::doorway;
    }
    for (const AisleMeasurement& held : pending_) accumulate(held);
    pending_.clear();
    accumulate(aisle);
    return FlushReason::none;
  }
  if (pending_.empty()) pending_reason_ = reason;
  pending_.push_back(aisle);
  if (static_cast<int>(pending_.size()) < config_.confirm_keyframes) return FlushReason::none;
  // The new segment is measured from its latest keyframe: the earlier pending ones may be a
  // doorway or a corner between the two aisles.
  const AisleMeasurement latest = pending_.back();
  const int starting = static_cast<int>(pending_.size());
  const FlushReason fired = pending_reason_;
  reset();
  accumulate(latest);
  carried_ = starting;
  return fired;
}

FlushReason RoomFlushTrigger::judge(const AisleMeasurement& aisle) const {
  const double median = segment_median_width();
  // Two cross-sections wider than an aisle are both open space (a room, a hall): how wide
  // varies with where the robot stands, furniture and doors, and is no change of space.
  const bool open = median >= config_.max_aisle_width && aisle.width >= config_.max_aisle_width;
  if (!open && std::abs(aisle.width - median) > config_.width_change_ratio * median)
    return FlushReason::width_change;
  const bool narrow = median < config_.max_aisle_width && aisle.width < config_.max_aisle_width;
  if (narrow && aisle.direction_defined && axis_sum_.norm() > 0.0) {
    const double c = std::min(1.0, std::abs(aisle.direction.dot(axis_sum_.normalized())));
    if (std::acos(c) * kRadToDeg > config_.direction_change_deg) return FlushReason::direction_change;
  }
  return FlushReason::none;
}

void RoomFlushTrigger::reset() {
  carried_ = 1;
  widths_.clear();
  pending_.clear();
  pending_reason_ = FlushReason::none;
  axis_sum_ = Vec2::Zero();
}

double RoomFlushTrigger::segment_median_width() const {
  if (widths_.empty()) return 0.0;
  std::vector<double> sorted = widths_;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t mid = sorted.size() / 2;
  return sorted.size() % 2 == 1 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
}

void RoomFlushTrigger::accumulate(const AisleMeasurement& aisle) {
  widths_.push_back(aisle.width);
  if (!aisle.direction_defined) return;
  // Directions are axes: align each with the running sum before adding it.
  axis_sum_ += aisle.direction.dot(axis_sum_) < 0.0 ? -aisle.direction : aisle.direction;
}

}  // namespace tsgraphs::rooms
