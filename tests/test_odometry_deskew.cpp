// De-skewing: a simulated sweep taken while the sensor turns in place and walks (the walls of a
// box room bent by the motion) is made straight again from the points' times and the motion
// between the scans' poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tsgraphs/odometry/deskew.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

namespace {

// A 12 x 9 m room walked by a hand-held sensor turning in place at the corners (90 deg/s:
// 9 degrees within one 10 Hz sweep).
const char* kScene = R"(name: deskew_room
seed: 4
sensor: {preset: os1-64, columns: 512, mount_height: 1.5}
platform: {type: handheld}
levels:
  - {name: G, elevation: 0.0, ceiling: 3.0, slab: [[0,0],[12,0],[12,9],[0,9]]}
walls:
  - {level: G, from: [0, 0], to: [12, 0]}
  - {level: G, from: [12, 0], to: [12, 9]}
  - {level: G, from: [12, 9], to: [0, 9]}
  - {level: G, from: [0, 9], to: [0, 0]}
trajectory:
  level: G
  laps: 1
  speed: 1.2
  yaw_rate_deg: 90
  waypoints: [[2, 2], [10, 2], [10, 7], [2, 7]]
)";

// RMS distance of the wall returns, placed in the world from the stamp's pose, to the room's
// walls (faces 0.1 m inside the centre lines).
double wall_rms(const PointCloud& scan, const Pose3& stamp_pose) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (scan.labels[i] != static_cast<std::uint32_t>(PointLabel::kWall)) continue;
    const Eigen::Vector3d p = stamp_pose * scan.points[i].cast<double>();
    const double d = std::min(
        {std::abs(p.x() - 0.1), std::abs(p.x() - 11.9), std::abs(p.y() - 0.1), std::abs(p.y() - 8.9)});
    sum += d * d;
    ++n;
  }
  return n == 0 ? 0.0 : std::sqrt(sum / static_cast<double>(n));
}

}  // namespace

TEST(Deskew, RestoresStraightWallsFromASweepTakenWhileTurning) {
  const sim::Simulator sim(scene::parse_scene(kScene, "deskew_room.yaml", "."), 1);
  // The scan that turns most within its sweep.
  std::size_t worst = 0;
  double most = 0.0;
  for (std::size_t k = 0; k + 1 < sim.num_scans(); ++k) {
    const double turn =
        Eigen::AngleAxisd((sim.true_poses()[k].inverse() * sim.true_poses()[k + 1]).linear()).angle();
    if (turn > most) {
      most = turn;
      worst = k;
    }
  }
  ASSERT_GT(most * 180.0 / M_PI, 7.0) << "the path turns in place";
  const PointCloud swept = sim.scan(worst);
  ASSERT_TRUE(swept.has_times());
  ASSERT_EQ(swept.times.size(), swept.size());
  const double period = sim.times()[1] - sim.times()[0];
  EXPECT_GE(*std::min_element(swept.times.begin(), swept.times.end()), 0.0f);
  EXPECT_LT(*std::max_element(swept.times.begin(), swept.times.end()), period);

  const Pose3& stamp = sim.true_poses()[worst];
  const double before = wall_rms(swept, stamp);
  const PointCloud straight = odometry::deskew(swept, stamp.inverse() * sim.true_poses()[worst + 1],
                                               sim.times()[worst + 1] - sim.times()[worst]);
  const double after = wall_rms(straight, stamp);
  EXPECT_GT(before, 0.1) << "turning by " << most * 180.0 / M_PI << " deg bends the walls";
  // What is left: the range noise (0.015 m) and the gait's change of pace within the sweep.
  EXPECT_LT(after, 0.03) << "before " << before;
  EXPECT_EQ(straight.times, swept.times);
  EXPECT_EQ(straight.labels, swept.labels);

  // The same scan taken at one instant (the wheeled platform's) needs nothing.
  EXPECT_LT(wall_rms(sim.scan_at(stamp, worst), stamp), 0.03);
  // Without times, or with no interval, nothing moves.
  PointCloud untimed = swept;
  untimed.times.clear();
  EXPECT_EQ(odometry::deskew(untimed, Pose3::Identity(), 0.1).points, untimed.points);
  EXPECT_EQ(odometry::deskew(swept, stamp, 0.0).points, swept.points);
}

TEST(Deskew, ScaledMotionIsTheSameRateOverAnotherSpan) {
  Pose3 delta = Pose3::Identity();
  delta.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.0, 0.6, 0.8)).toRotationMatrix();
  delta.translation() = Eigen::Vector3d(0.2, -0.1, 0.05);
  const Pose3 half = odometry::scale_motion(delta, 0.1, 0.05);
  EXPECT_NEAR(Eigen::AngleAxisd(half.linear()).angle(), 0.2, 1e-12);
  EXPECT_TRUE(half.translation().isApprox(delta.translation() / 2.0));
  EXPECT_TRUE(odometry::scale_motion(delta, 0.1, 0.1).isApprox(delta, 1e-12));
  EXPECT_TRUE(odometry::scale_motion(delta, 0.1, 0.0).isApprox(Pose3::Identity()));
  EXPECT_THROW(odometry::scale_motion(delta, 0.0, 0.1), std::invalid_argument);
}
