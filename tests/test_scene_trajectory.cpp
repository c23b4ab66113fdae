// The planned path: lengths, corner arcs, turns in place, laps, scan count, ramp heights.
#include <gtest/gtest.h>

#include <cmath>

#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"
#include "tsgraphs/scene/trajectory.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;
using namespace tsgraphs::sim;

namespace {

Scene rectangle_path(int laps, double speed, double yaw_rate_deg) {
  const std::string text = R"(
sensor: {channels: 2, columns: 8}
levels: [{name: L0, slab: [[0,0],[30,0],[30,20],[0,20]]}]
trajectory:
  waypoints: [[2, 2], [22, 2], [22, 12], [2, 12]]
  closed: true
  laps: )" + std::to_string(laps) +
                           "\n  speed: " + std::to_string(speed) +
                           "\n  yaw_rate_deg: " + std::to_string(yaw_rate_deg) + "\n";
  return parse_scene(text, "rect.yaml", ".");
}

}  // namespace

TEST(Trajectory, CornersAreArcsAtTheYawRate) {
  const Scene scene = rectangle_path(1, 1.0, 90.0);
  const Trajectory traj(scene);
  // A closed rectangle of 60 m: four 90-degree corners, three on arcs (the start is not a
  // corner on the first lap) ... the last one at the start is not taken either (the path ends).
  EXPECT_EQ(traj.arc_turns(), 3);
  EXPECT_EQ(traj.turns_in_place(), 0);
  const double r = 1.0 / (M_PI / 2);  // speed / yaw rate
  const double cut_per_corner = 2 * r * std::tan(M_PI / 4) - r * M_PI / 2;
  EXPECT_NEAR(traj.length(), 60.0 - 3 * cut_per_corner, 1e-9);
  EXPECT_NEAR(traj.duration(), traj.length() / 1.0, 1e-9);
  // The yaw never changes faster than the configured rate (sampled at 100 Hz).
  double max_rate = 0.0;
  for (double t = 0.01; t <= traj.duration(); t += 0.01) {
    const double dyaw = wrap_angle(yaw_of(traj.body_pose(t)) - yaw_of(traj.body_pose(t - 0.01)));
    max_rate = std::max(max_rate, std::abs(dyaw) / 0.01);
  }
  EXPECT_LE(max_rate, M_PI / 2 * 1.001);
  EXPECT_GT(max_rate, M_PI / 2 * 0.99);
  // The path is continuous: no jump of more than speed * dt.
  for (double t = 0.01; t <= traj.duration(); t += 0.01) {
    EXPECT_LE((traj.body_pose(t).translation() - traj.body_pose(t - 0.01).translation()).norm(), 0.0100001);
  }
  // It returns to its start.
  EXPECT_NEAR((traj.body_pose(traj.duration()).translation() - traj.body_pose(0).translation()).norm(), 0.0,
              1e-9);
  EXPECT_NEAR(traj.body_pose(0).translation().z(), scene.sensor.mount_height, 1e-12);
}

TEST(Trajectory, ScanCountIsPathLengthOverSpeedTimesRate) {
  for (const double speed : {0.5, 1.0, 1.5}) {
    const Scene scene = rectangle_path(2, speed, 90.0);
    const Simulator sim(scene, 0);
    const Trajectory& traj = sim.trajectory();
    // Path length = the distance the sensor travels: the polyline less what the 7 arcs cut.
    const double r = speed / (M_PI / 2);
    EXPECT_NEAR(traj.length(), 2 * 60.0 - 7 * r * (2.0 - M_PI / 2), 1e-9);
    const double expected = traj.length() / speed * scene.sensor.rate_hz;
    // A scan at t = 0 and one every period to the end: the intervals are the duration in periods, rounded.
    EXPECT_NEAR(static_cast<double>(sim.num_scans() - 1), expected, 0.5) << "speed " << speed;
    EXPECT_NEAR(sim.time_scale(), 1.0, 0.5 / expected);
    // The last scan is taken at the end of the path, back at the start.
    EXPECT_NEAR((sim.true_poses().back().translation() - sim.true_poses().front().translation()).norm(), 0.0,
                1e-9);
    // Scans are one period apart.
    EXPECT_NEAR(sim.times()[1] - sim.times()[0], 0.1, 1e-12);
  }
}

TEST(Trajectory, LapsStartAtTheFirstWaypoint) {
  const Scene scene = rectangle_path(3, 1.0, 90.0);
  const Trajectory traj(scene);
  ASSERT_EQ(traj.lap_starts().size(), 3u);
  EXPECT_DOUBLE_EQ(traj.lap_starts()[0], 0.0);
  for (std::size_t k = 1; k < 3; ++k) {
    const Eigen::Vector3d p = traj.body_pose(traj.lap_starts()[k]).translation();
    // On the arc's middle at the start corner: within r (1 - cos 45) / cos 45 of it.
    EXPECT_LT((p.head<2>() - Eigen::Vector2d(2, 2)).norm(), 0.3);
    EXPECT_EQ(traj.lap_at(traj.lap_starts()[k] + 0.5), static_cast<int>(k));
  }
  // Lap 1 starts on the straight and ends half way round the start corner's arc; lap 2 runs
  // arc middle to arc middle: both are the polyline less the corners' cuts.
  const double cut = (2.0 - M_PI / 2) / (M_PI / 2);  // travel saved per 90-degree arc at 1 m/s
  EXPECT_NEAR(traj.lap_starts()[1], 60.0 - 3.5 * cut, 1e-9);
  EXPECT_NEAR(traj.lap_starts()[2] - traj.lap_starts()[1], 60.0 - 4.0 * cut, 1e-9);
}

TEST(Trajectory, SharpTurnsAreMadeInPlace) {
  // Out and back along one line: the U-turn at the far end is turned in place at the yaw
  // rate, and so is the one at the start between laps.
  const Scene scene = parse_scene(R"(
levels: [{name: L0, slab: [[0,0],[30,0],[30,20],[0,20]]}]
trajectory: {waypoints: [[2, 2], [12, 2]], laps: 2, speed: 1.0, yaw_rate_deg: 45}
)",
                                  "uturn.yaml", ".");
  const Trajectory traj(scene);
  EXPECT_EQ(traj.turns_in_place(), 3);
  EXPECT_NEAR(traj.length(), 40.0, 1e-9);
  EXPECT_NEAR(traj.duration(), 40.0 + 3 * 4.0, 1e-9);  // 180 deg at 45 deg/s = 4 s each
  const Pose3 mid_turn = traj.body_pose(10.0 + 2.0);
  EXPECT_NEAR((mid_turn.translation().head<2>() - Eigen::Vector2d(12, 2)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(yaw_of(mid_turn)), M_PI / 2, 1e-9);
}

TEST(Trajectory, OpenPathsGoOutAndBack) {
  const Scene scene = parse_scene(R"(
levels: [{name: L0, slab: [[0,0],[30,0],[30,20],[0,20]]}]
trajectory: {waypoints: [[2, 2], [12, 2], [12, 10]], closed: false, laps: 2}
)",
                                  "open.yaml", ".");
  const Trajectory traj(scene);
  EXPECT_EQ(traj.lap_starts().size(), 2u);
  const Eigen::Vector3d end = traj.body_pose(traj.duration()).translation();
  EXPECT_NEAR((end.head<2>() - Eigen::Vector2d(2, 2)).norm(), 0.0, 1e-9);
  const Eigen::Vector3d turn = traj.body_pose(traj.lap_starts()[1]).translation();
  EXPECT_NEAR((turn.head<2>() - Eigen::Vector2d(12, 10)).norm(), 0.0, 1e-9);
}

TEST(Trajectory, RampsCarryTheSensorBetweenLevels) {
  const Scene scene = parse_scene(R"(
levels:
  - {name: low, elevation: 0.0, slab: [[0,0],[30,0],[30,10],[0,10]]}
  - name: high
    elevation: 2.0
    slab: [[0,0],[30,0],[30,10],[0,10]]
    voids: [[[6,2],[22,2],[22,4],[6,4]]]
ramps:
  - {from_level: low, to_level: high, polygon: [[6,2],[22,2],[22,4],[6,4]], axis: [1, 0]}
trajectory:
  level: low
  waypoints: [[2, 3], [26, 3, high], [26, 7, high]]
  closed: false
  laps: 1
)",
                                  "ramp.yaml", ".");
  const Trajectory traj(scene);
  const double m = scene.sensor.mount_height;
  EXPECT_NEAR(traj.body_pose(0.0).translation().z(), m, 1e-9);
  // Half way up the 16 m ramp: 1 m up.
  const double t_mid = 12.0;  // at x = 14
  EXPECT_NEAR(traj.body_pose(t_mid).translation().x(), 14.0, 1e-9);
  EXPECT_NEAR(traj.body_pose(t_mid).translation().z(), 1.0 + m, 0.01);
  EXPECT_NEAR(traj.body_pose(traj.duration()).translation().z(), 2.0 + m, 1e-9);
  // No step: height changes at most by the slope times the distance.
  for (double t = 0.1; t <= traj.duration(); t += 0.1) {
    EXPECT_LE(std::abs(traj.body_pose(t).translation().z() - traj.body_pose(t - 0.1).translation().z()),
              0.1 * 2.0 / 16.0 + 1e-6);
  }
}

TEST(Trajectory, WarnsWhereThePathFallsOrLeavesTheFloor) {
  // Off the top of the ramp straight into a void of the upper level: a 2 m drop to the
  // lower floor, which the loader cannot see (the leg joins two storeys).
  const Scene scene = parse_scene(R"(
levels:
  - {name: low, elevation: 0.0, slab: [[0,0],[30,0],[30,10],[0,10]]}
  - name: high
    elevation: 2.0
    slab: [[0,0],[30,0],[30,10],[0,10]]
    voids: [[[6,2],[22,2],[22,4],[6,4]], [[23,2],[26,2],[26,4],[23,4]]]
ramps:
  - {from_level: high, to_level: low, polygon: [[6,2],[22,2],[22,4],[6,4]], axis: [1, 0]}
trajectory:
  level: low
  waypoints: [[2, 3], [28, 3, high], [28, 7, high]]
  closed: false
  laps: 1
)",
                                  "fall.yaml", ".");
  const Trajectory traj(scene);
  ASSERT_EQ(traj.warnings().size(), 1u);
  EXPECT_EQ(traj.warnings()[0], "the path drops 2.00 m at [23.00, 3.00] (off a ramp's side or into a void?)");
  // Past the void the lower floor is still the closest surface: the sensor stays down there.
  EXPECT_NEAR(traj.body_pose(traj.duration()).translation().z(), scene.sensor.mount_height, 1e-9);
  // The ramp rises along its axis whichever level is named first.
  EXPECT_NEAR(traj.body_pose(12.0).translation().z(), 1.0 + scene.sensor.mount_height, 0.01);
}
