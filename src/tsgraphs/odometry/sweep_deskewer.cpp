#include "tsgraphs/odometry/sweep_deskewer.hpp"

#include <cmath>
#include <stdexcept>

#include "tsgraphs/odometry/deskew.hpp"

namespace tsgraphs::odometry {
namespace {

const SweepRegistrationConfig& validated(const SweepRegistrationConfig& c) {
  check_config(c, "SweepRegistrationConfig");
  return c;
}

}  // namespace

SweepDeskewer::SweepDeskewer(const LidarOdometryConfig& map_config, const SweepRegistrationConfig& config)
    : map_config_(map_config),
      config_(validated(config)),
      map_(map_config.voxel_size, static_cast<std::size_t>(map_config.max_points_per_voxel),
           map_config.surface()) {}

PointCloud SweepDeskewer::deskew(const PointCloud& scan, const Pose3& pose, const Pose3& prior_motion,
                                 double prior_interval) {
  if (!scan.has_times()) return scan;
  if (scan.times.size() != scan.size()) throw std::invalid_argument("SweepDeskewer: one time per point");
  SweepMotion prior;
  prior.pose = pose;
  if (prior_interval > 0.0) prior = SweepMotion::from_motion(pose, prior_motion, prior_interval);

  std::vector<Eigen::Vector3d> points;
  std::vector<double> times;
  for (const std::size_t i : in_range(scan, map_config_.min_range, map_config_.max_range)) {
    if (!std::isfinite(scan.times[i])) continue;
    points.push_back(scan.points[i].cast<double>());
    times.push_back(scan.times[i]);
  }
  std::vector<Eigen::Vector3d> source;
  std::vector<double> source_times;
  for (const std::size_t i : first_per_voxel(points, config_.voxel_size)) {
    source.push_back(points[i]);
    source_times.push_back(times[i]);
  }
  last_ = align_sweep_to_map(source, source_times, map_, prior, config_);
  if (last_.registered) ++num_registered_;
  // deskew() scales a motion over a duration: the motion over one second is the rates.
  PointCloud out = odometry::deskew(scan, last_.after(1.0), 1.0);

  // The map takes the de-skewed sweep at the pose it was given: the odometry's frame.
  std::vector<Eigen::Vector3d> kept;
  for (const std::size_t i : in_range(out, map_config_.min_range, map_config_.max_range))
    kept.push_back(out.points[i].cast<double>());
  std::vector<Eigen::Vector3d> frame;
  for (const std::size_t i : first_per_voxel(kept, map_config_.voxel_size * map_config_.map_voxel_factor))
    frame.push_back(pose * kept[i]);
  window_.push_back(std::move(frame));
  while (window_.size() > static_cast<std::size_t>(config_.window)) window_.pop_front();
  // Rebuilt with the newest sweep first: a full voxel keeps its first points.
  map_.clear();
  for (auto it = window_.rbegin(); it != window_.rend(); ++it) map_.add_points(*it);
  return out;
}

}  // namespace tsgraphs::odometry
