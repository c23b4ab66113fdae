// GICP registration: the real HDL-32 pair against its published relative pose, simulated
// office scans against the true poses, a wrong pairing that the loop check must reject,
// and degenerate input (too few points, NaNs) that must fail softly.
#include <gtest/gtest.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <tuple>

#include "cloud_test_support.hpp"
#include "tsgraphs/pipeline/prefilter.hpp"
#include "tsgraphs/graph/loop_closure.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/registration/registration.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;
using namespace tsgraphs::registration;

namespace {

const std::string kPairDir = std::string(TSGRAPHS_TEST_DATA_DIR) + "/hdl32_pair";
constexpr double kDeg = M_PI / 180.0;
// The pipeline's prefilter voxel for keyframe clouds (m), repeated here to feed GICP alike.
constexpr double kPrefilterVoxel = 0.1;

struct PoseError {
  double trans, rot_deg;
};

PoseError pose_error(const Pose3& estimate, const Pose3& truth) {
  const Pose3 d = truth.inverse() * estimate;
  return {d.translation().norm(), Eigen::AngleAxisd(d.linear()).angle() / kDeg};
}

Pose3 read_matrix(const std::string& path) {
  std::ifstream in(path);
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) in >> m(r, c);
  EXPECT_TRUE(in.good()) << path;
  return Pose3(m);
}

// The pipeline's own prefilter (NaN drop, range crop, one centroid per voxel).
PointCloud voxel_prefilter(const PointCloud& cloud, double voxel) {
  pipeline::PrefilterConfig config;
  config.voxel_size = voxel;
  return pipeline::prefilter(cloud, config);
}

// Wall time and this thread's CPU time (the machine may be shared; CPU time is what one core spends).
struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = cpu_ms();
  static double cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
  }
  double wall_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall).count();
  }
  double cpu_elapsed_ms() const { return cpu_ms() - cpu; }
};

sim::Simulator& office() {
  static sim::Simulator sim(scene::parse_scene(*scene::builtin_scene_text("office"), "office.yaml", "."), 11);
  return sim;
}

// A sensor pose of the office at floor position (x, y) and heading yaw, at the mount height.
Pose3 office_pose(double x, double y, double yaw_deg) {
  return make_pose(Eigen::Vector3d(x, y, office().scene().sensor.mount_height), yaw_deg * kDeg);
}

PointCloud office_scan(const Pose3& pose, std::uint64_t noise_index) {
  return voxel_prefilter(office().scan_at(pose, noise_index), kPrefilterVoxel);
}

TEST(RegistrationGicp, RealHdl32PairFromIdentity) {
  // README: relative.txt maps 251371071 (source) into 251370668 (target).
  const PointCloud target = io::read_pcd(kPairDir + "/251370668.pcd");
  const PointCloud source = io::read_pcd(kPairDir + "/251371071.pcd");
  const Pose3 truth = read_matrix(kPairDir + "/relative.txt");
  ASSERT_GT(truth.translation().norm(), 0.4);  // identity is a real 0.5 m guess error

  const RegistrationConfig config;
  const Stopwatch watch;
  const RegistrationResult r = register_clouds(source, target, Pose3::Identity(), config);
  const double cpu_ms = watch.cpu_elapsed_ms(), wall_ms = watch.wall_ms();
  const PoseError e = pose_error(r.T_target_source, truth);
  std::printf(
      "hdl32 pair (%zu, %zu points): %.1f ms cpu (%.1f wall), error %.4f m %.4f deg, fitness %.4f, "
      "inliers %.3f\n",
      source.size(), target.size(), cpu_ms, wall_ms, e.trans, e.rot_deg, r.fitness, r.inlier_ratio);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(e.trans, 0.05);
  EXPECT_LT(e.rot_deg, 0.5);
  // Real returns (trees, people) but the same place: the loop check accepts it.
  const graph::LoopClosureConfig loop;
  EXPECT_LE(r.fitness, loop.max_fitness);
  EXPECT_GE(r.inlier_ratio, loop.min_inlier_ratio);
}

TEST(RegistrationGicp, SimulatedOfficeScansFromPerturbedGuess) {
  // Room_b, two sensor poses 1.5 m and 20 degrees apart.
  const Pose3 T_map_target = office_pose(10.0, 2.2, 10.0);
  const Pose3 T_map_source = office_pose(10.0 + 1.2, 2.2 + 0.9, 30.0);
  const Pose3 truth = T_map_target.inverse() * T_map_source;
  ASSERT_NEAR(truth.translation().norm(), 1.5, 1e-9);

  const PointCloud target = office_scan(T_map_target, 1);
  const PointCloud source = office_scan(T_map_source, 2);
  // Guess off by 0.5 m and 5 degrees.
  const Pose3 perturbation = make_pose(Eigen::Vector3d(0.3, -0.4, 0.0), 5.0 * kDeg);
  const Pose3 guess = truth * perturbation;
  const PoseError guess_error = pose_error(guess, truth);
  ASSERT_NEAR(guess_error.trans, 0.5, 1e-9);
  ASSERT_NEAR(guess_error.rot_deg, 5.0, 1e-9);

  const RegistrationConfig config;
  const RegistrationResult r = register_clouds(source, target, guess, config);
  const PoseError e = pose_error(r.T_target_source, truth);
  std::printf("office pair: error %.4f m %.4f deg, fitness %.4f, inliers %.3f\n", e.trans, e.rot_deg,
              r.fitness, r.inlier_ratio);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(e.trans, 0.03);
  EXPECT_LT(e.rot_deg, 0.3);
  const graph::LoopClosureConfig loop;
  EXPECT_LT(r.fitness, loop.max_fitness);
  EXPECT_GT(r.inlier_ratio, loop.min_inlier_ratio);
}

TEST(RegistrationGicp, Os1KeyframePairsAlongTheOfficeRun) {
  // Keyframes 2 m apart spread over the run (corridor, doors, rooms, turns), registered from
  // the odometry guess, and timed. Every pair that passes the loop check must be accurate.
  const sim::Simulator& sim = office();
  const RegistrationConfig config;
  const graph::LoopClosureConfig loop;
  std::size_t accepted = 0;
  constexpr std::size_t kPairs = 8;
  constexpr std::size_t kKeyframeGap = 20;  // scans: 2 m at the scene's 1 m/s and 10 Hz
  double cpu_sum = 0.0, cpu_max = 0.0;
  std::size_t points = 0;
  for (std::size_t p = 0; p < kPairs; ++p) {
    const std::size_t i = (p * 2 + 1) * sim.num_scans() / (2 * kPairs + 1), j = i + kKeyframeGap;
    const PointCloud target = voxel_prefilter(sim.scan(i), kPrefilterVoxel);
    const PointCloud source = voxel_prefilter(sim.scan(j), kPrefilterVoxel);
    const Pose3 guess = sim.odometry_poses()[i].inverse() * sim.odometry_poses()[j];
    const Pose3 truth = sim.true_poses()[i].inverse() * sim.true_poses()[j];
    const Stopwatch watch;
    const RegistrationResult r = register_clouds(source, target, guess, config);
    const double cpu_ms = watch.cpu_elapsed_ms();
    cpu_sum += cpu_ms;
    cpu_max = std::max(cpu_max, cpu_ms);
    points += source.size() + target.size();
    const PoseError e = pose_error(r.T_target_source, truth);
    const bool passes =
        r.converged && r.fitness <= loop.max_fitness && r.inlier_ratio >= loop.min_inlier_ratio;
    std::printf("  scans %zu, %zu: error %.4f m %.3f deg, fitness %.4f, inliers %.3f%s\n", i, j, e.trans,
                e.rot_deg, r.fitness, r.inlier_ratio, passes ? "" : " (fails the loop check)");
    if (!passes) continue;  // e.g. the two sides of a door: little overlap
    ++accepted;
    EXPECT_LT(e.trans, 0.03) << "scans " << i << ", " << j;
    EXPECT_LT(e.rot_deg, 0.3) << "scans " << i << ", " << j;
  }
  std::printf(
      "os1-64 keyframe pairs (%.1f m prefilter, %zu points per cloud on average): %.1f ms cpu mean, %.1f "
      "max\n",
      kPrefilterVoxel, points / (2 * kPairs), cpu_sum / kPairs, cpu_max);
  EXPECT_GE(accepted, kPairs / 2);
}

TEST(RegistrationGicp, WrongPairingFailsTheLoopCheck) {
  // Room_a (7.8 m x 4.8 m, a desk and a shelf) against room_e (12.8 m x 5.6 m, a table), with
  // the estimates claiming the same place: floor and ceiling match, the walls cannot.
  const PointCloud target = office_scan(office_pose(4.0, 2.5, 0.0), 3);
  const PointCloud source = office_scan(office_pose(17.5, 10.0, 0.0), 4);
  const RegistrationConfig config;
  const RegistrationResult r = register_clouds(source, target, Pose3::Identity(), config);
  std::printf("wrong pairing: converged %d, fitness %.4f, inliers %.3f\n", r.converged, r.fitness,
              r.inlier_ratio);
  const graph::LoopClosureConfig loop;
  const bool accepted =
      r.converged && r.fitness <= loop.max_fitness && r.inlier_ratio >= loop.min_inlier_ratio;
  EXPECT_FALSE(accepted);
  EXPECT_LT(r.inlier_ratio, loop.min_inlier_ratio);
}

TEST(RegistrationGicp, TooFewPointsFailSoftly) {
  const RegistrationConfig config;
  PointCloud tiny;
  for (int i = 0; i < 5; ++i) tiny.points.emplace_back(static_cast<float>(i), 0.0f, 0.0f);
  const PointCloud office_cloud = office_scan(office_pose(10.0, 2.2, 0.0), 5);
  const PointCloud empty;

  for (const auto& [source, target] : {std::pair<const PointCloud*, const PointCloud*>{&empty, &empty},
                                       {&empty, &office_cloud},
                                       {&office_cloud, &empty},
                                       {&tiny, &office_cloud},
                                       {&office_cloud, &tiny}}) {
    RegistrationResult r;
    EXPECT_NO_THROW(r = register_clouds(*source, *target, Pose3::Identity(), config));
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(r.inlier_ratio, 0.0);
  }

  // Many points in one voxel are one point after downsampling: too few as well.
  PointCloud clump;
  for (int i = 0; i < 1000; ++i) clump.points.emplace_back(0.01f * static_cast<float>(i % 10), 0.0f, 0.0f);
  EXPECT_FALSE(register_clouds(clump, clump, Pose3::Identity(), config).converged);

  // Enough points, but on one line: covariances are degenerate; the result stays finite.
  PointCloud line;
  for (int i = 0; i < 200; ++i) line.points.emplace_back(0.25f * static_cast<float>(i), 0.0f, 0.0f);
  RegistrationResult r;
  EXPECT_NO_THROW(r = register_clouds(line, line, make_pose(Eigen::Vector3d(0.3, 0.0, 0.0), 0.0), config));
  EXPECT_TRUE(r.T_target_source.matrix().allFinite());

  // Only NaN points: nothing left.
  PointCloud nans;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < 100; ++i) nans.points.emplace_back(nan, static_cast<float>(i), 0.0f);
  EXPECT_FALSE(register_clouds(nans, office_cloud, Pose3::Identity(), config).converged);
}

TEST(RegistrationGicp, NanPointsAreDroppedAndResultIsDeterministic) {
  const Pose3 T_map_target = office_pose(19.5, 6.1, 180.0);  // corridor, east part
  const Pose3 T_map_source = office_pose(18.5, 6.3, 170.0);
  const Pose3 truth = T_map_target.inverse() * T_map_source;
  const PointCloud target = office_scan(T_map_target, 6);
  PointCloud source = office_scan(T_map_source, 7);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < source.size(); i += 10) source.points[i] = Eigen::Vector3f(nan, 0.0f, inf);

  const RegistrationConfig config;
  const RegistrationResult a = register_clouds(source, target, Pose3::Identity(), config);
  const RegistrationResult b = register_clouds(source, target, Pose3::Identity(), config);
  ASSERT_TRUE(a.converged);
  EXPECT_TRUE(a.T_target_source.matrix().allFinite());
  const PoseError e = pose_error(a.T_target_source, truth);
  EXPECT_LT(e.trans, 0.03);
  EXPECT_LT(e.rot_deg, 0.3);
  EXPECT_EQ(a.T_target_source.matrix(), b.T_target_source.matrix());
  EXPECT_EQ(a.fitness, b.fitness);
  EXPECT_EQ(a.inlier_ratio, b.inlier_ratio);
}

TEST(RegistrationGicp, InvalidConfigThrows) {
  const PointCloud cloud = office_scan(office_pose(10.0, 2.2, 0.0), 8);
  RegistrationConfig config;
  config.k_correspondences = 2;
  EXPECT_THROW(register_clouds(cloud, cloud, Pose3::Identity(), config), std::invalid_argument);
  config = RegistrationConfig();
  config.voxel_size = -0.1;
  EXPECT_THROW(register_clouds(cloud, cloud, Pose3::Identity(), config), std::invalid_argument);
}

}  // namespace

TEST(RegistrationGicp, PreparedCloudsGiveTheSameResultEveryTime) {
  // Loop closure prepares a keyframe once and registers it against several candidates: a
  // prepared cloud reused must give exactly what preparing afresh gives, in any order.
  const Pose3 T_map_target = office_pose(19.5, 6.1, 180.0);
  const Pose3 T_map_other = office_pose(10.0, 2.2, 0.0);
  const Pose3 T_map_source = office_pose(18.5, 6.3, 170.0);
  const PointCloud target = office_scan(T_map_target, 6);
  const PointCloud other = office_scan(T_map_other, 8);
  const PointCloud source = office_scan(T_map_source, 7);
  const RegistrationConfig config;

  const PreparedCloud ps = prepare_cloud(source, config);
  const PreparedCloud pt = prepare_cloud(target, config);
  const PreparedCloud po = prepare_cloud(other, config);
  EXPECT_GT(ps.size(), 100u);
  EXPECT_LT(ps.size(), source.size());  // thinned to the registration voxel
  const RegistrationResult fresh = register_clouds(source, target, Pose3::Identity(), config);
  const RegistrationResult first = register_clouds(ps, pt, Pose3::Identity(), config);
  register_clouds(ps, po, Pose3::Identity(), config);  // the same source against another target
  const PreparedCloud copy = ps;                       // copies share the preparation
  const RegistrationResult again = register_clouds(copy, pt, Pose3::Identity(), config);
  ASSERT_TRUE(first.converged);
  EXPECT_EQ(first.T_target_source.matrix(), fresh.T_target_source.matrix());
  EXPECT_EQ(first.T_target_source.matrix(), again.T_target_source.matrix());
  EXPECT_EQ(first.fitness, again.fitness);
  EXPECT_EQ(first.inlier_ratio, again.inlier_ratio);
  const PoseError e = pose_error(first.T_target_source, T_map_target.inverse() * T_map_source);
  EXPECT_LT(e.trans, 0.03);
  EXPECT_LT(e.rot_deg, 0.3);

  // A cloud prepared for another voxel size or neighbourhood is refused, not misused.
  RegistrationConfig finer = config;
  finer.voxel_size = 0.1;
  EXPECT_THROW(register_clouds(ps, pt, Pose3::Identity(), finer), std::invalid_argument);
  EXPECT_THROW(register_clouds(PreparedCloud(), pt, Pose3::Identity(), config), std::invalid_argument);
  // Too few points to prepare: registration fails softly.
  PointCloud clump;
  for (int i = 0; i < 5; ++i) clump.points.emplace_back(0.1f * static_cast<float>(i), 0.0f, 0.0f);
  EXPECT_FALSE(register_clouds(prepare_cloud(clump, config), pt, Pose3::Identity(), config).converged);
}

TEST(RegistrationGicp, SurfacesThatLeaveADirectionFreeAreMeasured) {
  // Along a corridor whose ends are out of view nothing pins the match: GICP stays wherever it
  // was put, and the result must say so; with its end walls in view the length is pinned.
  const RegistrationConfig config;
  const Pose3 guess = make_pose(Eigen::Vector3d(0.3, 0.0, 0.0), 0.0);  // 0.3 m off along the corridor

  const PointCloud open = test_support::corridor(20.0f, false);
  const RegistrationResult slid = register_clouds(open, open, guess, config);
  ASSERT_TRUE(slid.converged);
  EXPECT_LT(slid.fitness, 0.01);  // a perfect-looking match...
  EXPECT_GT(slid.inlier_ratio, 0.95);
  EXPECT_GT(slid.T_target_source.translation().x(), 0.1);  // ...that kept most of the error
  EXPECT_LT(slid.weakest_direction_share, 0.002);

  const PointCloud closed = test_support::corridor(8.0f, true);
  const RegistrationResult pinned = register_clouds(closed, closed, guess, config);
  ASSERT_TRUE(pinned.converged);
  EXPECT_LT(pinned.T_target_source.translation().norm(), 0.02);
  EXPECT_GT(pinned.weakest_direction_share, 0.05);  // the end walls are 10 m^2 of its 82 m^2
}
