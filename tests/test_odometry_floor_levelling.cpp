// Levelling the map on the floor under the first scan: simulated scans from tilted sensors
// (the true tilt and height recovered), and scans with no floor to level on.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tsgraphs/odometry/floor_levelling.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;
using tsgraphs::odometry::FloorLevellingConfig;
using tsgraphs::odometry::level_from_floor;

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// A room with a desk, seen by an os1-64.
const char* kScene = R"(name: levelling_room
seed: 2
sensor: {preset: os1-64, columns: 512}
levels:
  - {name: G, elevation: 0.0, ceiling: 2.8, slab: [[0,0],[10,0],[10,8],[0,8]]}
walls:
  - {level: G, from: [0, 0], to: [10, 0]}
  - {level: G, from: [10, 0], to: [10, 8]}
  - {level: G, from: [10, 8], to: [0, 8]}
  - {level: G, from: [0, 8], to: [0, 0]}
boxes:
  - {level: G, min: [6, 5, 0], max: [7.5, 6, 0.75], label: desk}
trajectory:
  level: G
  waypoints: [[2, 2], [8, 2]]
)";

// The sensor at (4, 3, height), turned by yaw, then pitched and rolled (sensor frame).
Pose3 tilted(double height, double yaw_deg, double pitch_deg, double roll_deg) {
  Pose3 T = Pose3::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw_deg / kRadToDeg, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch_deg / kRadToDeg, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll_deg / kRadToDeg, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(4.0, 3.0, height);
  return T;
}

class FloorLevelling : public ::testing::Test {
 protected:
  FloorLevelling() : simulator_(scene::parse_scene(kScene, "levelling_room.yaml", "."), 1) {}
  sim::Simulator simulator_;
};

}  // namespace

TEST_F(FloorLevelling, RecoversTheTiltAndHeightOfTiltedSensors) {
  struct Case {
    double height, yaw, pitch, roll;
  };
  for (const Case c :
       {Case{0.55, 0, 0, 0}, Case{0.55, 30, 10, 0}, Case{1.4, -70, -12, 8}, Case{1.7, 120, 5, -20}}) {
    SCOPED_TRACE("height " + std::to_string(c.height) + " pitch " + std::to_string(c.pitch) + " roll " +
                 std::to_string(c.roll));
    const Pose3 truth = tilted(c.height, c.yaw, c.pitch, c.roll);
    const auto level = level_from_floor(simulator_.scan_at(truth, 0));
    ASSERT_TRUE(level.found);
    EXPECT_NEAR(level.height, c.height, 0.02);
    // Up in the sensor's frame is up in the level frame: the tilt is undone within 0.3 degrees.
    const Eigen::Vector3d up_in_sensor = truth.linear().transpose() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d up = level.sensor_pose.linear() * up_in_sensor;
    EXPECT_LT(std::acos(std::min(1.0, up.z())) * kRadToDeg, 0.3);
    EXPECT_NEAR(level.tilt_deg, std::acos(std::min(1.0, up_in_sensor.z())) * kRadToDeg, 0.3);
    EXPECT_NEAR(level.sensor_pose.translation().z(), c.height, 0.02);
    // A floor point of the scan lies at z = 0 in the level frame.
    const Eigen::Vector3d floor_point = truth.inverse() * Eigen::Vector3d(4.0, 5.0, 0.0);
    EXPECT_NEAR((level.sensor_pose * floor_point).z(), 0.0, 0.03);
  }
}

TEST_F(FloorLevelling, NoFloorFoundIsSaidNotGuessed) {
  // Too tilted for max_tilt_deg (30): the floor is not taken for a floor.
  EXPECT_FALSE(level_from_floor(simulator_.scan_at(tilted(0.55, 0, 45, 0), 0)).found);
  // Nothing below the sensor: a scan of a ceiling only.
  PointCloud ceiling;
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j) ceiling.points.emplace_back(0.2f * i, 0.2f * j, 2.0f);
  const auto none = level_from_floor(ceiling);
  EXPECT_FALSE(none.found);
  EXPECT_TRUE(none.sensor_pose.isApprox(Pose3::Identity()));
  EXPECT_FALSE(level_from_floor(PointCloud{}).found);
  FloorLevellingConfig bad;
  bad.max_tilt_deg = 95.0;
  EXPECT_THROW(level_from_floor(ceiling, bad), std::invalid_argument);
}
