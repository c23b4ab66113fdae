#pragma once
/// LiDAR odometry over a whole scan sequence (sequence folder, scan folder, bag).
#include <cstddef>
#include <functional>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/io/scan_sequence.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"

namespace tsgraphs::pipeline {

/// Registers every scan of `sequence` in order (as they are: deskew.hpp, sweep_motion) and
/// returns one sensor pose per scan:
/// the first is the odometry's first pose, so that a caller can anchor the odometry frame, e.g. at
/// the first ground-truth pose or the sensor's mount tilt (odometry::LidarOdometry: its z is taken as up).
/// `progress(done, total)` after each scan. Input errors of the sequence propagate. `lost`
/// (optional) gets the indices of the scans the odometry reported lost; `overlaps` (optional)
/// each scan's final voxel overlap.
std::vector<Pose3> estimate_odometry(const io::ScanSequence& sequence, odometry::LidarOdometry& odometry,
                                     const std::function<void(std::size_t, std::size_t)>& progress = {},
                                     std::vector<std::size_t>* lost = nullptr,
                                     std::vector<double>* overlaps = nullptr);
/// The same with an odometry of `config` starting at `initial_pose`.
std::vector<Pose3> estimate_odometry(const io::ScanSequence& sequence,
                                     const odometry::LidarOdometryConfig& config,
                                     const std::function<void(std::size_t, std::size_t)>& progress = {},
                                     const Pose3& initial_pose = Pose3::Identity(),
                                     std::vector<std::size_t>* lost = nullptr,
                                     std::vector<double>* overlaps = nullptr);

}  // namespace tsgraphs::pipeline
