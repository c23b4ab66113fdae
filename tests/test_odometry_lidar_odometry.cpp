// LidarOdometry on synthetic rooms with known motions, on two real HDL-32e scans, and its
// contract: the first pose, empty scans, determinism, bad configs.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>

#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"

using namespace tsgraphs;
using tsgraphs::odometry::LidarOdometry;
using tsgraphs::odometry::LidarOdometryConfig;

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kSurfaceSpacing = 0.05;  // m between synthetic surface samples

// Random samples of an axis-aligned box's faces, as dense as a grid of kSurfaceSpacing. Random,
// not on a grid: a grid would line up with the voxel grids and make the motions too easy, or
// too hard, for reasons no real scan shares.
void add_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::mt19937* rng,
             std::vector<Eigen::Vector3d>* out) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const double area = (hi[a] - lo[a]) * (hi[b] - lo[b]);
    const auto n = static_cast<std::size_t>(area / (kSurfaceSpacing * kSurfaceSpacing));
    for (const double fixed : {lo[axis], hi[axis]}) {
      for (std::size_t i = 0; i < n; ++i) {
        Eigen::Vector3d p;
        p[axis] = fixed;
        p[a] = lo[a] + unit(*rng) * (hi[a] - lo[a]);
        p[b] = lo[b] + unit(*rng) * (hi[b] - lo[b]);
        out->push_back(p);
      }
    }
  }
}

// A room with a corridor-like annex, a cupboard and a pillar, so that no direction is free.
std::vector<Eigen::Vector3d> synthetic_room() {
  std::mt19937 rng(7);
  std::vector<Eigen::Vector3d> pts;
  add_box({-4.0, -3.0, -1.0}, {5.0, 3.0, 2.0}, &rng, &pts);    // the room
  add_box({1.0, 1.8, -1.0}, {2.2, 3.0, 0.8}, &rng, &pts);      // a cupboard against a wall
  add_box({-2.0, -1.5, -1.0}, {-1.7, -1.2, 2.0}, &rng, &pts);  // a pillar
  add_box({3.0, -3.0, -1.0}, {3.6, -2.2, 0.5}, &rng, &pts);    // a crate
  return pts;
}

// The scan at `pose` (sensor in world): a random subset of the points in the sensor frame, so
// that no two scans sample the surfaces at the same places.
PointCloud scan_at(const std::vector<Eigen::Vector3d>& world, const Pose3& pose, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution keep(0.5);
  const Pose3 inv = pose.inverse();
  PointCloud cloud;
  for (const Eigen::Vector3d& p : world) {
    if (keep(rng)) cloud.points.push_back((inv * p).cast<float>());
  }
  return cloud;
}

// Known motion: 0.1 m forward, 0.03 m sideways and 1.5 degrees of yaw per scan, as a robot
// turning on an arc at 10 Hz.
std::vector<Pose3> arc_poses(std::size_t n) {
  std::vector<Pose3> poses;
  const Pose3 step = make_pose(Eigen::Vector3d(0.1, 0.03, 0.0), 1.5 / kRadToDeg);
  Pose3 T = make_pose(Eigen::Vector3d(-1.0, -0.5, 0.3), 0.2);
  for (std::size_t k = 0; k < n; ++k) {
    poses.push_back(T);
    T = T * step;
  }
  return poses;
}

std::vector<Pose3> run_synthetic(std::size_t n) {
  const auto world = synthetic_room();
  const auto truth = arc_poses(n);
  LidarOdometry odom;
  for (std::size_t k = 0; k < n; ++k)
    odom.register_scan(scan_at(world, truth[k], static_cast<std::uint32_t>(k)));
  return odom.poses();
}

Pose3 read_matrix(const std::string& path) {
  std::ifstream in(path);
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) in >> m(r, c);
  EXPECT_TRUE(static_cast<bool>(in)) << path;
  Pose3 T;
  T.matrix() = m;
  return T;
}

double angle_deg(const Pose3& T) { return Eigen::AngleAxisd(T.linear()).angle() * kRadToDeg; }

// A scan in a corridor 2 m wide running along x, its end walls 3 m behind and 20 m ahead:
// walls sampled at random, and the floor, 0.55 m below the sensor, as a LiDAR sees it: rings
// round the sensor, which move with it. Sensor frame, the sensor at `x` on the corridor's axis.
PointCloud corridor_scan(double x, std::uint32_t seed) {
  constexpr double kHalfWidth = 1.0, kBehind = -3.0, kAhead = 20.0, kFloor = -0.55, kCeiling = 2.3;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  PointCloud cloud;
  const auto add = [&](const Eigen::Vector3d& world) {
    cloud.points.push_back((world - Eigen::Vector3d(x, 0, 0)).cast<float>());
  };
  for (int i = 0; i < 20000; ++i) {  // the side walls
    const double along = kBehind + unit(rng) * (kAhead - kBehind),
                 z = kFloor + unit(rng) * (kCeiling - kFloor);
    add({along, i % 2 ? kHalfWidth : -kHalfWidth, z});
  }
  for (int i = 0; i < 3000; ++i) {  // the end walls
    const double y = -kHalfWidth + unit(rng) * 2 * kHalfWidth, z = kFloor + unit(rng) * (kCeiling - kFloor);
    add({i % 2 ? kAhead : kBehind, y, z});
  }
  for (const double radius : {0.9, 1.1, 1.4, 1.8, 2.3, 3.0, 4.0, 5.5, 7.5}) {  // the floor's rings
    for (double a = 0.0; a < 2 * M_PI; a += 0.005) {
      const Eigen::Vector3d p(x + radius * std::cos(a), radius * std::sin(a), kFloor);
      if (std::abs(p.y()) < kHalfWidth && p.x() > kBehind) add(p);
    }
  }
  return cloud;
}

// The error of the position after `scans` scans 0.1 m apart along the corridor.
double corridor_error(bool point_to_plane, std::size_t scans) {
  LidarOdometryConfig config;
  config.point_to_plane = point_to_plane;
  LidarOdometry odom(config);
  for (std::size_t k = 0; k < scans; ++k)
    odom.register_scan(corridor_scan(0.1 * static_cast<double>(k), 100 + k));
  return (odom.poses().back().translation() - Eigen::Vector3d(0.1 * static_cast<double>(scans - 1), 0, 0))
      .norm();
}

}  // namespace

TEST(LidarOdometry, FloorRingsThatMoveWithTheSensorDoNotHoldItBack) {
  // Along a corridor only the end walls say how far the sensor went; the floor's rings, which
  // move with it, match best where they were: point-to-point ICP (KISS-ICP's) is pulled
  // towards standing still, point-to-plane is not (a ring is a line: no voxel plane is fitted
  // to it until rings of several scans fill the floor in). Of the 1.9 m travelled,
  // point-to-plane loses 0.03 m here (the voxels where the floor meets a wall are matched
  // point to point), point-to-point 0.4 m.
  constexpr std::size_t kScans = 20;
  const double plane = corridor_error(true, kScans);
  const double point = corridor_error(false, kScans);
  std::printf("corridor, %zu scans 0.1 m apart: point-to-plane %.3f m, point-to-point %.3f m\n", kScans,
              plane, point);
  EXPECT_LT(plane, 0.05);
  EXPECT_GT(point, 4.0 * plane);
}

TEST(LidarOdometry, RecoversKnownMotionsInASyntheticRoom) {
  constexpr std::size_t kScans = 15;
  const auto truth = arc_poses(kScans);
  const auto poses = run_synthetic(kScans);
  ASSERT_EQ(poses.size(), kScans);
  EXPECT_TRUE(poses.front().isApprox(Pose3::Identity()));
  double worst_m = 0.0, worst_deg = 0.0;
  for (std::size_t k = 0; k < kScans; ++k) {
    const Pose3 expected = truth.front().inverse() * truth[k];
    const Pose3 error = expected.inverse() * poses[k];
    EXPECT_LT(error.translation().norm(), 0.01) << "scan " << k;
    EXPECT_LT(angle_deg(error), 0.1) << "scan " << k;
    worst_m = std::max(worst_m, error.translation().norm());
    worst_deg = std::max(worst_deg, angle_deg(error));
  }
  std::printf("synthetic room: worst %.4f m, %.4f deg\n", worst_m, worst_deg);
}

// The error of the second scan's pose when it holds, beside the room, something the first did
// not: a partition 0.3 m in front of the east wall, with the threshold a hand-held sensor
// recorded at 2 Hz teaches the odometry (6-8 m on a generated office: the prediction's
// uncertainty, not the sensor's noise).
Pose3 error_with_a_new_object(double fine_threshold) {
  const auto world = synthetic_room();
  std::mt19937 rng(11);
  std::vector<Eigen::Vector3d> leaf;
  add_box({4.65, -2.5, -1.0}, {4.7, 2.5, 2.0}, &rng, &leaf);
  std::vector<Eigen::Vector3d> later = world;
  later.insert(later.end(), leaf.begin(), leaf.end());
  const auto truth = arc_poses(2);
  LidarOdometryConfig config;
  config.fine_threshold = fine_threshold;
  config.initial_threshold = 7.0;
  LidarOdometry odom(config);
  odom.register_scan(scan_at(world, truth[0], 1));
  const Pose3 pose = odom.register_scan(scan_at(later, truth[1], 2));
  return (truth[0].inverse() * truth[1]).inverse() * pose;
}

TEST(LidarOdometry, AWideThresholdsWrongPairsStopPullingOnceConverged) {
  // With a 7 m threshold the kernel is 2.3 m wide: the partition's points pair with the wall
  // 0.3 m behind it at full weight and pull the pose towards it. Going on with
  // fine_threshold's kernel (0.17 m) leaves those pairs a weight of 6 % and the pose to the room.
  const Pose3 wide = error_with_a_new_object(0.0);
  const Pose3 fine = error_with_a_new_object(LidarOdometryConfig{}.fine_threshold);
  std::printf(
      "a partition 0.3 m from a wall: error %.4f m %.3f deg without the fine threshold, %.4f m %.3f deg "
      "with\n",
      wide.translation().norm(), angle_deg(wide), fine.translation().norm(), angle_deg(fine));
  EXPECT_GT(wide.translation().norm(), 0.02);
  EXPECT_LT(fine.translation().norm(), 0.005);
  EXPECT_LT(angle_deg(fine), 0.05);
}

TEST(LidarOdometry, SameInputSamePosesWhateverTheThreads) {
  constexpr std::size_t kScans = 6;
  std::vector<Pose3> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = run_synthetic(kScans);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = run_synthetic(kScans);
  }
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k)
    EXPECT_TRUE(one[k].matrix() == two[k].matrix()) << "scan " << k;
}

TEST(LidarOdometry, EmptyScanKeepsThePredictionAndTheMap) {
  const auto world = synthetic_room();
  const auto truth = arc_poses(3);
  LidarOdometry odom;
  EXPECT_TRUE(odom.register_scan(PointCloud{}).isApprox(Pose3::Identity()));  // nothing yet: identity
  odom.register_scan(scan_at(world, truth[0], 0));
  odom.register_scan(scan_at(world, truth[1], 1));
  const std::size_t map_points = odom.local_map().num_points();
  // Only non-finite and out-of-range points: nothing usable.
  PointCloud junk;
  junk.points = {Eigen::Vector3f(NAN, 0, 0), Eigen::Vector3f(0.01f, 0, 0), Eigen::Vector3f(500, 0, 0)};
  const Pose3 predicted = odom.predict();
  const Pose3 p2 = odom.register_scan(junk);
  EXPECT_TRUE(p2.isApprox(predicted, 1e-12));
  EXPECT_EQ(odom.local_map().num_points(), map_points);
  EXPECT_EQ(odom.poses().size(), 4u);
}

TEST(LidarOdometry, StartsAtTheFirstPoseItIsGiven) {
  const auto world = synthetic_room();
  const auto truth = arc_poses(6);
  LidarOdometry odom(LidarOdometryConfig{}, truth[0]);
  for (std::size_t k = 0; k < truth.size(); ++k)
    odom.register_scan(scan_at(world, truth[k], static_cast<std::uint32_t>(k)));
  EXPECT_TRUE(odom.poses().front().isApprox(truth[0], 1e-12));
  EXPECT_LT((odom.poses().back().translation() - truth.back().translation()).norm(), 0.02);
  EXPECT_LT(angle_deg(truth.back().inverse() * odom.poses().back()), 0.2);
}

TEST(LidarOdometry, ThePredictionRepeatsTheTurnAboutZAndHoldsTheTilt) {
  // A carried sensor: between two scans it turned 10 degrees about the vertical and rolled
  // 4 degrees. Its roll swings back at the next step, so the prediction holds it; the turn
  // about z and the step go on.
  const auto world = synthetic_room();
  const Pose3 first = make_pose(Eigen::Vector3d(-1.0, -0.5, 0.3), 0.2);
  const Eigen::AngleAxisd yaw(10.0 / kRadToDeg, Eigen::Vector3d::UnitZ());
  Pose3 second = first;
  second.translation() += Eigen::Vector3d(0.3, 0.1, 0.0);
  second.linear() = yaw * first.linear() * Eigen::AngleAxisd(4.0 / kRadToDeg, Eigen::Vector3d::UnitX());
  const auto predict = [&](bool repeat) {
    LidarOdometryConfig config;
    config.tilt_prediction = repeat ? odometry::TiltPrediction::repeat : odometry::TiltPrediction::hold;
    LidarOdometry odom(config, first);
    odom.register_scan(scan_at(world, first, 1));
    odom.register_scan(scan_at(world, second, 2));
    return odom.predict();
  };
  const auto tilt_deg = [](const Pose3& T) {
    return std::acos(std::clamp((T.linear() * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0)) * kRadToDeg;
  };
  const Pose3 held = predict(false);
  EXPECT_NEAR(tilt_deg(held), 4.0, 0.2);
  const Eigen::Matrix3d expected = yaw * second.linear();
  EXPECT_LT(Eigen::AngleAxisd(expected.transpose() * held.linear()).angle() * kRadToDeg, 0.2);
  const Eigen::Vector3d step = yaw * (second.translation() - first.translation());
  EXPECT_LT((held.translation() - (second.translation() + step)).norm(), 0.01);
  EXPECT_NEAR(tilt_deg(predict(true)), 8.0, 0.3);  // repeated, the roll doubles
}

TEST(LidarOdometry, AutoRepeatsTheTiltWhenItsChangeGoesOnAndHoldsItWhenItSwingsBack) {
  // 3 degrees of roll a scan: swinging back and forth (a carried sensor at 2 Hz) holding
  // predicts the next tilt better; rolling on (at 10 Hz the sway goes on between scans)
  // repeating does.
  const auto world = synthetic_room();
  const auto truth = arc_poses(8);
  const auto repeats_after = [&](bool swings) {
    LidarOdometryConfig config;
    config.tilt_window = 3;
    LidarOdometry odom(config, truth[0]);
    std::vector<bool> repeats;
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const double roll_deg = swings ? 3.0 * static_cast<double>(k % 2) : 3.0 * static_cast<double>(k);
      Pose3 tilted = truth[k];
      tilted.linear() = tilted.linear() * Eigen::AngleAxisd(roll_deg / kRadToDeg, Eigen::Vector3d::UnitX());
      odom.register_scan(scan_at(world, tilted, static_cast<std::uint32_t>(k)));
      repeats.push_back(odom.repeats_tilt());
    }
    return repeats;
  };
  const std::vector<bool> rolling = repeats_after(false), swinging = repeats_after(true);
  // Two poses make the first prediction, three scored scans fill the window.
  for (std::size_t k = 0; k < 4; ++k) EXPECT_FALSE(rolling[k]) << k;  // holds until it knows
  for (std::size_t k = 4; k < rolling.size(); ++k) EXPECT_TRUE(rolling[k]) << k;
  for (std::size_t k = 0; k < swinging.size(); ++k) EXPECT_FALSE(swinging[k]) << k;
}

TEST(LidarOdometry, GivenStampsThePredictionTurnsAtTheLastSweepsTurnRate) {
  // A walker at 2 Hz: standing still at the first scan, 5 degrees turned at the second, half a
  // second later, and turning at 40 deg/s during its sweep. Over the next half second that
  // rate turns 20 degrees; repeating the last turn, 5.
  const auto world = synthetic_room();
  const Pose3 first = make_pose(Eigen::Vector3d(-1.0, -0.5, 0.3), 0.2);
  Pose3 second = first;
  second.linear() = Eigen::AngleAxisd(5.0 / kRadToDeg, Eigen::Vector3d::UnitZ()) * first.linear();
  const double rate = 40.0 / kRadToDeg;
  // The swept scan: each point measured at its azimuth's time in a 0.1 s sweep around the stamp.
  PointCloud swept;
  std::mt19937 rng(2);
  std::bernoulli_distribution keep(0.5);
  for (const Eigen::Vector3d& p : world) {
    if (!keep(rng)) continue;
    const Eigen::Vector3d at_stamp = second.inverse() * p;
    const double t = 0.1 * (std::atan2(at_stamp.y(), at_stamp.x()) / (2.0 * M_PI));
    Pose3 at_time = second;
    at_time.linear() = second.linear() * Eigen::AngleAxisd(rate * t, Eigen::Vector3d::UnitZ());
    swept.points.push_back((at_time.inverse() * p).cast<float>());
    swept.times.push_back(static_cast<float>(t));
  }
  const auto turn_deg = [](const Pose3& from, const Pose3& to) {
    const Eigen::Quaterniond q(to.linear() * from.linear().transpose());
    return 2.0 * std::atan2(q.z(), q.w()) * kRadToDeg;
  };
  LidarOdometry odom(LidarOdometryConfig{}, first);
  odom.register_scan(scan_at(world, first, 1), 0.0);
  const Pose3 registered = odom.register_scan(swept, 0.5);
  ASSERT_TRUE(odom.last_sweep().registered);
  EXPECT_NEAR(turn_deg(first, registered), 5.0, 0.5);
  EXPECT_NEAR(turn_deg(registered, odom.predict(0.5)), 20.0, 3.0);
  EXPECT_NEAR(turn_deg(registered, odom.predict()), 5.0, 0.5);  // no time given: the last turn
  LidarOdometryConfig off;
  off.turn_from_sweep = false;
  LidarOdometry without(off, first);
  without.register_scan(scan_at(world, first, 1), 0.0);
  without.register_scan(swept, 0.5);
  EXPECT_NEAR(turn_deg(without.poses().back(), without.predict(0.5)), 5.0, 0.5);
}

TEST(LidarOdometry, RejectsBadConfigs) {
  auto bad = [](auto change) {
    LidarOdometryConfig c;
    change(c);
    return c;
  };
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.voxel_size = 0.0; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.max_range = c.min_range; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.min_range = -1.0; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.max_points_per_voxel = 0; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.initial_threshold = 0.0; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.max_iterations = 0; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.fine_threshold = -0.1; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.recovery_search_m = 20.0; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.recovery_points = 0; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.yaw_search_candidates = 0; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.min_correspondences = 3; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.max_range = c.min_range; })), std::invalid_argument);
  EXPECT_THROW(LidarOdometry(bad([](auto& c) { c.tilt_window = 0; })), std::invalid_argument);
  EXPECT_NO_THROW(LidarOdometry{});
}

TEST(LidarOdometry, RegistersTwoRealHdl32Scans) {
  const std::string dir = std::string(TSGRAPHS_TEST_DATA_DIR) + "/hdl32_pair/";
  const PointCloud target = io::read_pcd(dir + "251370668.pcd");
  const PointCloud source = io::read_pcd(dir + "251371071.pcd");
  const Pose3 expected = read_matrix(dir + "relative.txt");  // target <- source
  LidarOdometry odom;
  odom.register_scan(target);
  const Pose3 pose = odom.register_scan(source);  // the source sensor in the target's frame
  const Pose3 error = expected.inverse() * pose;
  EXPECT_LT(error.translation().norm(), 0.05) << pose.matrix();
  EXPECT_LT(angle_deg(error), 0.5) << pose.matrix();
  EXPECT_TRUE(odom.last_icp().converged);
  std::printf("hdl32 pair: %.4f m, %.4f deg from relative.txt\n", error.translation().norm(),
              angle_deg(error));
}

// A hand-held sensor at 2 Hz: standing still, then turning in place by 40 degrees between
// scans (the turns a constant-velocity prediction cannot follow: from a standstill it predicts
// none), then walking 0.6 m per scan while turning 20 degrees.
TEST(LidarOdometry, RecoversLargeTurnsBetweenScansAfterAStandstill) {
  const std::vector<Eigen::Vector3d> world = synthetic_room();
  std::vector<Pose3> truth;
  Pose3 T = make_pose(Eigen::Vector3d(-1.0, -0.5, 0.3), 0.2);
  for (int k = 0; k < 3; ++k) truth.push_back(T);
  for (int k = 0; k < 5; ++k) truth.push_back(T = T * make_pose(Eigen::Vector3d::Zero(), 40.0 / kRadToDeg));
  for (int k = 0; k < 4; ++k)
    truth.push_back(T = T * make_pose(Eigen::Vector3d(0.6, 0.0, 0.0), -20.0 / kRadToDeg));
  const auto run = [&](double search_deg) {
    LidarOdometryConfig config;
    config.yaw_search_deg = search_deg;
    if (search_deg == 0.0) config.recovery_search_m = 0.0;  // no search of any kind
    LidarOdometry odom(config);
    for (std::size_t k = 0; k < truth.size(); ++k)
      odom.register_scan(scan_at(world, truth[k], static_cast<std::uint32_t>(k)));
    const Pose3 rel_est = odom.poses().front().inverse() * odom.poses().back();
    const Pose3 rel_true = truth.front().inverse() * truth.back();
    const Pose3 err = rel_true.inverse() * rel_est;
    return std::make_pair(err.translation().norm(), Eigen::AngleAxisd(err.linear()).angle() * kRadToDeg);
  };
  const auto [trans, rot] = run(LidarOdometryConfig{}.yaw_search_deg);
  EXPECT_LT(trans, 0.05);
  EXPECT_LT(rot, 0.5);
  // Without searching the turns are lost.
  const auto [trans_off, rot_off] = run(0.0);
  EXPECT_GT(rot_off, 5.0) << "translation error " << trans_off;
}

TEST(LidarOdometry, AFirstStepBeyondICPsReachIsFoundBySearchingAround) {
  // The first step of a walk recorded at 2 Hz: 1.1 m and a 30 degree turn from a prediction
  // of standing still, among pillars (no wall or floor to slide along), beyond the voxel
  // neighbourhood ICP pairs points in. The scan ends lost; searched again from turns and
  // shifts of the prediction, it registers.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> where(-6.0, 6.0);
  std::vector<Eigen::Vector3d> world;
  for (int i = 0; i < 25; ++i) {
    // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
    const double cy = where(rng), cx = where(rng);
    const Eigen::Vector3d c(cx, cy, 0.0);
    add_box(c + Eigen::Vector3d(-0.2, -0.2, -1.0), c + Eigen::Vector3d(0.2, 0.2, 2.0), &rng, &world);
  }
  const Pose3 first = make_pose(Eigen::Vector3d(0.0, 0.0, 0.0), 0.2);
  const Pose3 second = first * make_pose(Eigen::Vector3d(1.0, -0.4, 0.0), 30.0 / kRadToDeg);
  const auto run = [&](double search_m) {
    LidarOdometryConfig config;
    config.recovery_search_m = search_m;
    LidarOdometry odom(config);
    odom.register_scan(scan_at(world, first, 1));
    const Pose3 pose = odom.register_scan(scan_at(world, second, 2));
    return std::make_pair((first.inverse() * second).inverse() * pose, odom.last_icp());
  };
  const auto [err, icp] = run(LidarOdometryConfig{}.recovery_search_m);
  std::printf("first step 1.08 m, 30 deg among pillars: error %.4f m %.3f deg, overlap %.2f\n",
              err.translation().norm(), angle_deg(err), icp.overlap);
  EXPECT_TRUE(icp.recovered);
  EXPECT_FALSE(icp.lost);
  EXPECT_LT(err.translation().norm(), 0.01);
  EXPECT_LT(angle_deg(err), 0.1);
  const auto [err_off, icp_off] = run(0.0);
  EXPECT_TRUE(icp_off.lost) << "error " << err_off.translation().norm() << " m, overlap " << icp_off.overlap;
  EXPECT_FALSE(icp_off.recovered);
}

TEST(LidarOdometry, AScanThatMatchesNothingIsReportedLostAndKeptOutOfTheMap) {
  const std::vector<Eigen::Vector3d> world = synthetic_room();
  const std::vector<Pose3> truth = arc_poses(4);
  LidarOdometry odom;
  for (std::size_t k = 0; k < 3; ++k)
    odom.register_scan(scan_at(world, truth[k], static_cast<std::uint32_t>(k)));
  EXPECT_TRUE(odom.lost_scans().empty());
  const std::size_t map_points = odom.local_map().num_points();
  // Another place altogether: a long hall the map has never seen.
  std::mt19937 rng(3);
  std::vector<Eigen::Vector3d> hall;
  add_box({-30.0, -10.0, -1.0}, {30.0, 10.0, 6.0}, &rng, &hall);
  odom.register_scan(scan_at(hall, Pose3::Identity(), 9));
  ASSERT_EQ(odom.lost_scans().size(), 1u);
  EXPECT_EQ(odom.lost_scans().front(), 3u);
  EXPECT_TRUE(odom.last_icp().lost);
  EXPECT_EQ(odom.local_map().num_points(), map_points);
}
