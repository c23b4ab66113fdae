// LidarOdometry on simulated sequences: a small two-room floor scanned by a VLP-16 along a
// closed path (wheeled, and carried by hand at 2 Hz with swept scans), written as a sequence
// folder and read back; the drift against groundtruth.txt.
// ctest: slow (seconds a test: simulated runs or generated buildings)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"
#include "tsgraphs/pipeline/odometry_sequence.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

#include "test_support.hpp"

using namespace tsgraphs;
using tsgraphs::test::TempDirTest;

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kMaxDriftShare = 0.01;  // the issue's target: 1 % of the distance travelled
constexpr double kMaxYawErrorDeg = 1.0;

// Two rooms joined by a door, a shelf and a crate; the path crosses the door, loops in the east
// room and comes back.
const char* kScene = R"(name: odometry_rooms
seed: 3
sensor: {preset: vlp-16, columns: 900, tilt_deg: 5.0, range_noise_std: 0.01}
levels:
  - {name: G, elevation: 0.0, ceiling: 2.8, slab: [[0,0],[16,0],[16,10],[0,10]]}
walls:
  - {level: G, from: [8, 0], to: [8, 10], openings: [{at: 3.0, width: 1.0, height: 2.1}]}
  - {level: G, from: [0, 0], to: [16, 0]}
  - {level: G, from: [16, 0], to: [16, 10]}
  - {level: G, from: [16, 10], to: [0, 10]}
  - {level: G, from: [0, 10], to: [0, 0]}
boxes:
  - {level: G, min: [2, 6, 0], max: [3, 8, 1.5], yaw_deg: 20, label: shelf}
  - {level: G, min: [12, 6, 0], max: [13.5, 7, 1.0], yaw_deg: -10, label: crate}
rooms:
  - {name: west, level: G, polygon: [[0,0],[8,0],[8,10],[0,10]]}
  - {name: east, level: G, polygon: [[8,0],[16,0],[16,10],[8,10]]}
trajectory:
  level: G
  waypoints: [[3, 3], [6, 3], [13, 3], [13, 5], [10, 5], [10, 3.2]]
  closed: true
  laps: 1
)";

// The same floor walked twice by a person carrying a VLP-16 at 1.5 m, its 10 Hz sweeps kept
// at 2 Hz: sway, bob, turns of tens of degrees between scans, each sweep's points measured
// over its 0.1 s (motion distortion).
std::string hand_held_scene() {
  std::string scene = kScene;
  const std::string sensor = "sensor: {preset: vlp-16, columns: 900, tilt_deg: 5.0, range_noise_std: 0.01}";
  scene.replace(scene.find(sensor), sensor.size(),
                "sensor: {preset: vlp-16, columns: 900, tilt_deg: 5.0, range_noise_std: 0.01, record_hz: 2, "
                "mount_height: 1.5}\nplatform: {type: handheld, bob: 0.03, step_hz: 1.8, sway_deg: 4, "
                "yaw_jitter_deg: 3, motion_distortion: true}");
  scene.replace(scene.find("laps: 1"), 7, "laps: 2");
  return scene;
}

// Each scan's rotation from the one before against the truth's (deg), sorted.
std::vector<double> step_rotation_errors(const std::vector<Pose3>& poses, const std::vector<Pose3>& truth) {
  std::vector<double> out;
  for (std::size_t k = 1; k < poses.size(); ++k) {
    const Pose3 e = (truth[k - 1].inverse() * truth[k]).inverse() * (poses[k - 1].inverse() * poses[k]);
    out.push_back(Eigen::AngleAxisd(e.linear()).angle() * kRadToDeg);
  }
  std::sort(out.begin(), out.end());
  return out;
}

using OdometrySimulated = TempDirTest;

}  // namespace

TEST_F(OdometrySimulated, DriftIsBelowOnePercentOfThePath) {
  const scene::Scene scene = scene::parse_scene(kScene, "odometry_rooms.yaml", ".");
  const sim::Simulator simulator(scene, 1);
  const std::string seq_dir = (dir_ / "seq").string();
  sim::write_sequence(simulator, seq_dir);

  const io::SequenceReader seq(seq_dir);
  const auto& truth = seq.info().groundtruth;
  ASSERT_EQ(truth.size(), seq.size());
  ASSERT_GT(seq.size(), 100u);
  std::size_t reported = 0;
  const std::vector<Pose3> poses = pipeline::estimate_odometry(
      seq, odometry::LidarOdometryConfig{}, [&](std::size_t done, std::size_t) { reported = done; },
      truth.front());  // aligned at the first pose
  ASSERT_EQ(poses.size(), seq.size());
  EXPECT_EQ(reported, seq.size());

  double path = 0.0;
  for (std::size_t k = 1; k < truth.size(); ++k)
    path += (truth[k].translation() - truth[k - 1].translation()).norm();
  ASSERT_GT(path, 15.0);
  const double end_error = (poses.back().translation() - truth.back().translation()).norm();
  const double yaw_error = std::abs(wrap_angle(yaw_of(poses.back()) - yaw_of(truth.back()))) * kRadToDeg;
  EXPECT_LE(end_error, kMaxDriftShare * path) << "path " << path << " m";
  EXPECT_LE(yaw_error, kMaxYawErrorDeg);
  // And no scan on the way lost track.
  for (std::size_t k = 0; k < poses.size(); ++k) {
    ASSERT_LE((poses[k].translation() - truth[k].translation()).norm(), 2.0 * kMaxDriftShare * path)
        << "scan " << k;
  }
  RecordProperty("path_m", std::to_string(path));
  RecordProperty("end_error_m", std::to_string(end_error));
  std::printf("path %.2f m, end error %.3f m (%.2f %%), yaw error %.3f deg, %zu scans\n", path, end_error,
              100.0 * end_error / path, yaw_error, poses.size());
}

TEST_F(OdometrySimulated, ASweptHandHeldScanIsPlacedAtItsStamp) {
  const scene::Scene scene = scene::parse_scene(hand_held_scene(), "odometry_rooms_hand.yaml", ".");
  const sim::Simulator simulator(scene, 1);
  const std::string seq_dir = (dir_ / "seq").string();
  sim::write_sequence(simulator, seq_dir);
  const io::SequenceReader seq(seq_dir);
  const auto& truth = seq.info().groundtruth;
  ASSERT_GT(seq.size(), 80u);
  const auto run = [&](bool sweep_motion) {
    odometry::LidarOdometryConfig config;
    config.sweep_motion = sweep_motion;
    const std::vector<Pose3> poses = pipeline::estimate_odometry(seq, config, {}, truth.front());
    double worst_heading = 0.0, sum_sq = 0.0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
      worst_heading =
          std::max(worst_heading, std::abs(wrap_angle(yaw_of(poses[k]) - yaw_of(truth[k]))) * kRadToDeg);
      sum_sq += (poses[k].translation() - truth[k].translation()).squaredNorm();
    }
    const std::vector<double> steps = step_rotation_errors(poses, truth);
    return std::make_tuple(steps[steps.size() / 2], worst_heading,
                           std::sqrt(sum_sq / static_cast<double>(poses.size())));
  };
  // Registered with its motion, a sweep's pose is the stamp's; registered rigidly it is the
  // pose that fits the whole sweep, degrees away from the stamp's while the sensor turns.
  const auto [step, heading, ate] = run(true);
  const auto [step_rigid, heading_rigid, ate_rigid] = run(false);
  std::printf(
      "hand-held at 2 Hz: step rotation error median %.2f deg (rigid %.2f), worst heading %.1f deg "
      "(%.1f), ATE %.3f m (%.3f)\n",
      step, step_rigid, heading, heading_rigid, ate, ate_rigid);
  EXPECT_LT(step, 1.2);
  EXPECT_GT(step_rigid, 1.5 * step);
  EXPECT_LT(heading, 5.0);  // no wrong turn taken
  EXPECT_LT(ate, 0.15);
}

TEST_F(OdometrySimulated, GivenStampsASweepsVelocityStartsFromTheLastInterval) {
  // Every 10 Hz sweep kept: the last interval's velocity is close to the next sweep's, closer
  // than standing still is.
  std::string text = hand_held_scene();
  text.replace(text.find("record_hz: 2, "), 14, "");
  const sim::Simulator simulator(scene::parse_scene(text, "odometry_rooms_hand10.yaml", "."), 1);
  ASSERT_GT(simulator.num_scans(), 200u);
  // The sweep registration's velocity against the truth's over the sweep, rms (m/s): with the
  // scans' stamps (the prior is the last interval's velocity) and without (no prior motion).
  const auto velocity_error = [&](bool stamps) {
    odometry::LidarOdometry odometry(odometry::LidarOdometryConfig{}, simulator.true_poses().front(),
                                     odometry::SweepRegistrationConfig{});
    double sum_sq = 0.0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < 200; ++k) {
      const PointCloud scan = simulator.scan(k);
      const double t = simulator.times()[k];
      if (stamps)
        odometry.register_scan(scan, t);
      else
        odometry.register_scan(scan);
      if (k < 3 || !odometry.last_sweep().registered) continue;
      const double sweep = *std::max_element(scan.times.begin(), scan.times.end());
      const Pose3 during = simulator.true_poses()[k].inverse() * simulator.sensor_pose_at(t + sweep);
      sum_sq += (odometry.last_sweep().velocity - during.translation() / sweep).squaredNorm();
      ++n;
    }
    EXPECT_GT(n, 150u);
    return std::sqrt(sum_sq / static_cast<double>(std::max<std::size_t>(n, 1)));
  };
  const double with_stamps = velocity_error(true), without = velocity_error(false);
  std::printf("hand-held at 10 Hz: a sweep's velocity off by %.3f m/s with stamps, %.3f m/s without\n",
              with_stamps, without);
  // Measured: 0.67 against 0.88 m/s. What is left is the sweep's own (the registration trades
  // the velocity for what its constant rates cannot follow; docs/benchmarks.md).
  EXPECT_LT(with_stamps, 0.9 * without);
}
