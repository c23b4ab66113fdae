// Sweep registration: a hand-held sweep, registered to a map with its motion among the
// unknowns, finds the turning inside it and straightens its walls; kept every 0.5 s, it tells
// the sweeps' motion better than the poses around them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tsgraphs/odometry/deskew.hpp"
#include "tsgraphs/odometry/sweep_deskewer.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

namespace {

// A 12 x 9 m room with a pillar, walked by a hand-held sensor turning in place at the corners
// (90 deg/s: 9 degrees within one 10 Hz sweep).
const char* kScene = R"(name: sweep_room
seed: 4
sensor: {preset: os1-64, columns: 512, mount_height: 1.5}
platform: {type: handheld, bob: 0.03, step_hz: 1.8, sway_deg: 4, yaw_jitter_deg: 3}
levels:
  - {name: G, elevation: 0.0, ceiling: 3.0, slab: [[0,0],[12,0],[12,9],[0,9]]}
walls:
  - {level: G, from: [0, 0], to: [12, 0]}
  - {level: G, from: [12, 0], to: [12, 9]}
  - {level: G, from: [12, 9], to: [0, 9]}
  - {level: G, from: [0, 9], to: [0, 0]}
  - {level: G, from: [5, 4], to: [6, 4]}
  - {level: G, from: [6, 4], to: [6, 5]}
  - {level: G, from: [6, 5], to: [5, 5]}
  - {level: G, from: [5, 5], to: [5, 4]}
trajectory:
  level: G
  laps: 1
  speed: 1.2
  yaw_rate_deg: 90
  waypoints: [[2, 2], [10, 2], [10, 7], [2, 7]]
)";

// RMS distance of the outer wall returns, placed in the world from the stamp's pose, to the
// room's walls (faces 0.1 m inside the centre lines).
double wall_rms(const PointCloud& scan, const Pose3& stamp_pose) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (scan.labels[i] != static_cast<std::uint32_t>(PointLabel::kWall)) continue;
    const Eigen::Vector3d p = stamp_pose * scan.points[i].cast<double>();
    if (p.x() > 4.0 && p.x() < 7.0 && p.y() > 3.0 && p.y() < 6.0) continue;  // the pillar
    const double d = std::min(
        {std::abs(p.x() - 0.1), std::abs(p.x() - 11.9), std::abs(p.y() - 0.1), std::abs(p.y() - 8.9)});
    sum += d * d;
    ++n;
  }
  return n == 0 ? 0.0 : std::sqrt(sum / static_cast<double>(n));
}

}  // namespace

// The rate of turn about each axis over the motion `m` of `seconds` (deg/s).
Eigen::Vector3d rates_deg(const Pose3& m, double seconds) {
  const Eigen::AngleAxisd aa(m.linear());
  return aa.axis() * aa.angle() / seconds * 180.0 / M_PI;
}

TEST(SweepRegistration, FindsTheMotionInsideASweepFromAMapOfTheSweepsAround) {
  const sim::Simulator sim(scene::parse_scene(kScene, "sweep_room.yaml", "."), 1);
  const double period = sim.times()[1] - sim.times()[0];
  // The sweep that turns most (in place at a corner: about 9 deg).
  std::size_t k = 0;
  double most = 0.0;
  for (std::size_t j = 5; j + 5 < sim.num_scans(); ++j) {
    const double turn =
        Eigen::AngleAxisd((sim.true_poses()[j].inverse() * sim.true_poses()[j + 1]).linear()).angle();
    if (turn > most) {
      most = turn;
      k = j;
    }
  }
  ASSERT_GT(most * 180.0 / M_PI, 7.0) << "the path turns in place";
  odometry::SweepDeskewer deskewer(odometry::LidarOdometryConfig{}, {});
  for (std::size_t j = k - 4; j <= k + 4; j += 2) {
    if (j == k) continue;
    PointCloud still = sim.scan_at(sim.true_poses()[j], j);
    still.times.assign(still.size(), 0.0f);
    deskewer.deskew(still, sim.true_poses()[j], Pose3::Identity(), 0.0);
  }
  const Pose3& stamp = sim.true_poses()[k];
  const PointCloud swept = sim.scan(k);
  ASSERT_TRUE(swept.has_times());
  // No motion given: the registration finds it.
  const PointCloud straight = deskewer.deskew(swept, stamp, Pose3::Identity(), 0.0);
  ASSERT_TRUE(deskewer.last().registered);
  const Eigen::Vector3d truth = rates_deg(stamp.inverse() * sim.true_poses()[k + 1], period);
  const Eigen::Vector3d found = deskewer.last().turn_rate * 180.0 / M_PI;
  EXPECT_LT((found - truth).norm(), 8.0)
      << "found " << found.transpose() << " deg/s, true " << truth.transpose();
  const Eigen::Vector3d true_velocity = (stamp.inverse() * sim.true_poses()[k + 1]).translation() / period;
  EXPECT_LT((deskewer.last().velocity - true_velocity).norm(), 0.5);  // 0.05 m over the sweep
  EXPECT_GT(wall_rms(swept, stamp), 0.1);
  EXPECT_LT(wall_rms(straight, stamp), 0.03) << "before " << wall_rms(swept, stamp);
  EXPECT_EQ(straight.times, swept.times);
  EXPECT_EQ(straight.labels, swept.labels);
  // A scan without times is left as it is.
  PointCloud untimed = swept;
  untimed.times.clear();
  EXPECT_EQ(deskewer.deskew(untimed, stamp, Pose3::Identity(), 0.0).points, untimed.points);
}

TEST(SweepRegistration, KeptEveryHalfSecondItTellsTheSweepsMotionBetterThanThePosesAroundIt) {
  const sim::Simulator sim(scene::parse_scene(kScene, "sweep_room.yaml", "."), 1);
  const double period = sim.times()[1] - sim.times()[0];
  // A 10 Hz hand-held sensor kept at 2 Hz: each sweep registered to the ones before, from the
  // motion between the kept poses (what the poses alone would de-skew with).
  odometry::SweepDeskewer deskewer(odometry::LidarOdometryConfig{}, {});
  double sq_prior = 0.0, sq_found = 0.0, worst_prior = 0.0, worst_found = 0.0, sum_prior = 0.0,
         sum_found = 0.0;
  double sq_prior_velocity = 0.0, sq_found_velocity = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k + 5 < sim.num_scans(); k += 5) {
    const Pose3& stamp = sim.true_poses()[k];
    const Pose3 between = stamp.inverse() * sim.true_poses()[k + 5];
    const PointCloud swept = sim.scan(k);
    const PointCloud straight = deskewer.deskew(swept, stamp, between, 5 * period);
    const PointCloud from_poses = odometry::deskew(swept, between, 5 * period);
    worst_prior = std::max(worst_prior, wall_rms(from_poses, stamp));
    worst_found = std::max(worst_found, wall_rms(straight, stamp));
    sum_prior += wall_rms(from_poses, stamp);
    sum_found += wall_rms(straight, stamp);
    if (k == 0) continue;  // nothing to register to yet
    ASSERT_TRUE(deskewer.last().registered) << "scan " << k;
    const Eigen::Vector3d truth = rates_deg(stamp.inverse() * sim.true_poses()[k + 1], period);
    sq_prior += (rates_deg(between, 5 * period) - truth).squaredNorm();
    sq_found += (deskewer.last().turn_rate * 180.0 / M_PI - truth).squaredNorm();
    const Eigen::Vector3d true_velocity = (stamp.inverse() * sim.true_poses()[k + 1]).translation() / period;
    sq_prior_velocity += (between.translation() / (5 * period) - true_velocity).squaredNorm();
    sq_found_velocity += (deskewer.last().velocity - true_velocity).squaredNorm();
    ++n;
  }
  ASSERT_GT(n, 20u);
  const double rms_prior = std::sqrt(sq_prior / n), rms_found = std::sqrt(sq_found / n);
  EXPECT_LT(rms_found, 0.7 * rms_prior)
      << "turn rate error, deg/s: poses " << rms_prior << ", registered " << rms_found;
  // The velocity is seen weakly within a sweep: the registration must not trade it for the
  // tilting it tells poorly (its prior held at 1 m/s: 0.53 m/s off here where the poses are
  // 0.28 m/s off; 0.6-1.6 m/s on generated buildings, docs/benchmarks.md).
  const double rms_prior_velocity = std::sqrt(sq_prior_velocity / n),
               rms_found_velocity = std::sqrt(sq_found_velocity / n);
  EXPECT_LT(rms_found_velocity, 1.25 * rms_prior_velocity)
      << "velocity error, m/s: poses " << rms_prior_velocity << ", registered " << rms_found_velocity;
  EXPECT_LT(worst_found, 0.8 * worst_prior)
      << "walls' rms, worst sweep: poses " << worst_prior << ", registered " << worst_found;
  EXPECT_LT(sum_found, sum_prior) << "walls' rms, sum: poses " << sum_prior << ", registered " << sum_found;
  std::printf(
      "turn rate error %.1f -> %.1f deg/s; velocity error %.3f -> %.3f m/s; walls' rms worst %.3f -> %.3f m, "
      "mean %.4f -> %.4f m\n",
      rms_prior, rms_found, rms_prior_velocity, rms_found_velocity, worst_prior, worst_found,
      sum_prior / (n + 1), sum_found / (n + 1));
}
