#pragma once
/// Where a run's poses come from, decided once for `run`, `convert`, the suite, the demo and the
/// odometry bench: the input's odometry, or the LiDAR odometry's, started from the input's first
/// pose, the sensor's mount on a level base, or level with the floor under the first scan.
#include <optional>
#include <string>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/io/scan_sequence.hpp"
#include "tsgraphs/odometry/floor_levelling.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/pipeline/sequence_runner.hpp"

namespace tsgraphs::pipeline {

struct OdometryChoice {
  OdometryOptions options;
  std::optional<odometry::FloorLevel> level;  ///< the floor the map frame was levelled on, if it was
  std::string warning;                        ///< why the map frame is the first scan's, if it is
};

/// `mode`: "input" (the sequence's poses; an InputError naming it when it has none), "lidar"
/// (estimated), or "auto" (the input's when it has them). `sensor_to_base`: the mount, when known.
OdometryChoice choose_odometry(const io::ScanSequence& sequence, const std::string& mode,
                               const std::optional<Pose3>& sensor_to_base,
                               const odometry::FloorLevellingConfig& levelling);

/// The LiDAR odometry every command estimates with: the config's `lidar_odometry` and
/// `deskew.registration`, its first pose `first_pose`.
odometry::LidarOdometry make_lidar_odometry(const PipelineConfig& config, const Pose3& first_pose);

}  // namespace tsgraphs::pipeline
