// LidarOdometry on a simulated sequence: a small two-room floor scanned by a VLP-16 along a
// closed path, written as a sequence folder and read back; the drift against groundtruth.txt.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/odometry/lidar_odometry_sequence.hpp"
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
  const std::vector<Pose3> poses = odometry::estimate_odometry(
      seq, odometry::LidarOdometryConfig{}, [&](std::size_t done, std::size_t) { reported = done; },
      truth.front());  // aligned at the first pose
  ASSERT_EQ(poses.size(), seq.size());
  EXPECT_EQ(reported, seq.size());

  double path = 0.0;
  for (std::size_t k = 1; k < truth.size(); ++k) path += (truth[k].translation() - truth[k - 1].translation()).norm();
  ASSERT_GT(path, 15.0);
  const double end_error = (poses.back().translation() - truth.back().translation()).norm();
  const double yaw_error = std::abs(wrap_angle(yaw_of(poses.back()) - yaw_of(truth.back()))) * kRadToDeg;
  EXPECT_LE(end_error, kMaxDriftShare * path) << "path " << path << " m";
  EXPECT_LE(yaw_error, kMaxYawErrorDeg);
  // And no scan on the way lost track.
  for (std::size_t k = 0; k < poses.size(); ++k) {
    ASSERT_LE((poses[k].translation() - truth[k].translation()).norm(), 2.0 * kMaxDriftShare * path) << "scan " << k;
  }
  RecordProperty("path_m", std::to_string(path));
  RecordProperty("end_error_m", std::to_string(end_error));
  std::printf("path %.2f m, end error %.3f m (%.2f %%), yaw error %.3f deg, %zu scans\n", path, end_error,
              100.0 * end_error / path, yaw_error, poses.size());
}
