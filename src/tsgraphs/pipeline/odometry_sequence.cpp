#include "tsgraphs/pipeline/odometry_sequence.hpp"

#include <tbb/task_group.h>

namespace tsgraphs::pipeline {

std::vector<Pose3> estimate_odometry(const io::ScanSequence& sequence,
                                     const odometry::LidarOdometryConfig& config,
                                     const std::function<void(std::size_t, std::size_t)>& progress,
                                     const Pose3& initial_pose, std::vector<std::size_t>* lost,
                                     std::vector<double>* overlaps) {
  odometry::LidarOdometry odometry(config, initial_pose);
  return estimate_odometry(sequence, odometry, progress, lost, overlaps);
}

std::vector<Pose3> estimate_odometry(const io::ScanSequence& sequence, odometry::LidarOdometry& odometry,
                                     const std::function<void(std::size_t, std::size_t)>& progress,
                                     std::vector<std::size_t>* lost, std::vector<double>* overlaps) {
  const std::size_t n = sequence.size();
  std::vector<Pose3> poses;
  poses.reserve(n);
  if (n == 0) return poses;
  // Read the next scan while this one registers: reading and parsing a scan file is a fair
  // share of the per-scan time, and ScanSequence::scan may be called from another thread.
  PointCloud current = sequence.scan(0);
  for (std::size_t k = 0; k < n; ++k) {
    PointCloud next;
    tbb::task_group reader;
    if (k + 1 < n) reader.run([&] { next = sequence.scan(k + 1); });
    try {
      poses.push_back(odometry.register_scan(current, sequence.info().times[k]));
    } catch (...) {
      reader.wait();
      throw;
    }
    reader.wait();  // rethrows a read error
    if (overlaps) overlaps->push_back(odometry.last_icp().overlap);
    current = std::move(next);
    if (progress) progress(k + 1, n);
  }
  if (lost) *lost = odometry.lost_scans();
  return poses;
}

}  // namespace tsgraphs::pipeline
