#include "tsgraphs/pipeline/odometry_choice.hpp"

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::pipeline {

OdometryChoice choose_odometry(const io::ScanSequence& sequence, const std::string& mode,
                               const std::optional<Pose3>& sensor_to_base,
                               const odometry::FloorLevellingConfig& levelling) {
  const std::vector<Pose3>& input = sequence.info().odometry;
  OdometryChoice choice;
  if (mode == "input") {
    if (input.empty())
      throw input_error(
          sequence.dir(), 0,
          "has no odometry: give poses (--poses, --odom-topic or --odom-tum), or --odometry lidar to "
          "estimate them from the scans");
    return choice;
  }
  if (mode != "lidar" && mode != "auto")
    throw input_error("--odometry", 0, "'" + mode + "': expected auto, input or lidar");
  if (mode == "auto" && !input.empty()) return choice;
  choice.options.estimate = true;
  if (!input.empty()) {
    choice.options.initial_pose = input.front();
  } else if (sensor_to_base) {
    choice.options.initial_pose = *sensor_to_base;
  } else if (sequence.size() > 0) {
    odometry::FloorLevel level;
    try {
      level = odometry::level_from_floor(sequence.scan(0), levelling);
    } catch (const InputError&) {
      // An unreadable first scan: the run skips it with its own warning; no floor to level on.
    }
    if (level.found) {
      choice.options.initial_pose = level.sensor_pose;
      choice.level = level;
    } else {
      choice.warning =
          "no floor found under the first scan: the map frame is the first scan's (give --sensor-to-base "
          "if the sensor is tilted)";
    }
  }
  return choice;
}

odometry::LidarOdometry make_lidar_odometry(const PipelineConfig& config, const Pose3& first_pose) {
  return odometry::LidarOdometry(config.lidar_odometry, first_pose, config.deskew.registration);
}

}  // namespace tsgraphs::pipeline
