// The simulator end to end: labels and poses agree with the scene, determinism (seed,
// threads), the sequence folder it writes, and the command line's exit codes.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using namespace tsgraphs::sim;
using namespace tsgraphs::scene;
using tsgraphs::test::fresh_temp_dir;
using tsgraphs::test::TempDirTest;

namespace {

// A small two-room floor with a door, a box, a ramp down to a lower storey seen through a
// void; a short closed path.
const char* kScene = R"(name: small
seed: 11
sensor: {preset: vlp-16, columns: 360, tilt_deg: 10.0, range_noise_std: 0.01}
levels:
  - {name: B, elevation: -2.0, ceiling: 1.8, slab: [[0,0],[16,0],[16,10],[0,10]]}
  - name: G
    elevation: 0.0
    ceiling: 2.8
    slab: [[0,0],[16,0],[16,10],[0,10]]
    voids: [[[10,6],[14,6],[14,9],[10,9]]]
walls:
  - {level: G, from: [8, 0], to: [8, 10], openings: [{at: 3.0, width: 1.0, height: 2.1}]}
  - {level: G, from: [0, 0], to: [16, 0]}
  - {level: G, from: [16, 0], to: [16, 10]}
  - {level: G, from: [16, 10], to: [0, 10]}
  - {level: G, from: [0, 10], to: [0, 0]}
railings:
  - {level: G, from: [10, 6], to: [14, 6], style: bars}
boxes:
  - {level: G, min: [2, 6, 0], max: [3, 8, 1.5], yaw_deg: 20, label: shelf}
rooms:
  - {name: west, level: G, polygon: [[0,0],[8,0],[8,10],[0,10]]}
  - {name: east, level: G, polygon: [[8,0],[16,0],[16,10],[8,10]]}
trajectory:
  level: G
  waypoints: [[3, 3], [6.5, 3], [9.5, 3], [12, 3]]
  closed: true
  laps: 1
)";

using test::read_file;

using Cli = TempDirTest;

}  // namespace

TEST(Simulator, PointsLieOnTheSurfacesTheirLabelsName) {
  const Scene scene = parse_scene(kScene, "small.yaml", ".");
  const Simulator sim(scene, 1);
  ASSERT_GT(sim.num_scans(), 10u);
  std::map<std::uint32_t, int> count;
  for (std::size_t k = 0; k < sim.num_scans(); k += 5) {
    const PointCloud cloud = sim.scan(k);
    ASSERT_EQ(cloud.labels.size(), cloud.size());
    ASSERT_EQ(cloud.intensity.size(), cloud.size());
    const Pose3& T = sim.true_poses()[k];
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const Eigen::Vector3d w = T * cloud.points[i].cast<double>();
      const std::uint32_t label = cloud.labels[i];
      ++count[label];
      EXPECT_GE(cloud.intensity[i], 0.0f);
      EXPECT_LE(cloud.intensity[i], 1.0f);
      // With the 10-degree tilt, only a right pose makes floors flat in the world frame.
      if (label == 1) {
        const bool on_g = std::abs(w.z() - 0.0) < 0.06;
        const bool on_b = std::abs(w.z() + 2.0) < 0.06;
        ASSERT_TRUE(on_g || on_b) << "floor point at z " << w.z();
        if (on_b) {  // the storey below is seen only through the void
          EXPECT_GT(w.x(), 9.5);
          EXPECT_LT(w.x(), 14.5);
        }
      } else if (label == 3) {
        ASSERT_TRUE(std::abs(w.z() - 2.8) < 0.06 || std::abs(w.z() + 0.2) < 0.06) << "ceiling at z " << w.z();
      }
    }
  }
  EXPECT_GT(count[1], 1000);  // floor
  EXPECT_GT(count[3], 100);   // ceiling
  EXPECT_GT(count[4], 1000);  // walls
  EXPECT_GT(count[5], 10);    // railing
  EXPECT_GT(count[6], 10);    // box
  EXPECT_EQ(count[0], 0);
}

TEST(Simulator, OdometryDriftsFromTruthAndStartsOnIt) {
  const Scene scene = parse_scene(kScene, "small.yaml", ".");
  const Simulator sim(scene, 5);
  ASSERT_EQ(sim.odometry_poses().size(), sim.num_scans());
  EXPECT_TRUE(sim.odometry_poses().front().isApprox(sim.true_poses().front(), 1e-12));
  EXPECT_FALSE(sim.odometry_poses().back().isApprox(sim.true_poses().back(), 1e-6));
  // The tilt stays in both: the sensor's z axis leans 10 degrees from vertical.
  const double lean = std::acos(sim.odometry_poses().back().linear().col(2).z()) * 180.0 / M_PI;
  EXPECT_NEAR(lean, 10.0, 1.0);
}

TEST(Simulator, SameSeedSameScansWhateverTheThreads) {
  const Scene scene = parse_scene(kScene, "small.yaml", ".");
  PointCloud one_thread, two_threads, other_seed;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one_thread = Simulator(scene, 3).scan(4);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two_threads = Simulator(scene, 3).scan(4);
    other_seed = Simulator(scene, 4).scan(4);
  }
  ASSERT_EQ(one_thread.size(), two_threads.size());
  for (std::size_t i = 0; i < one_thread.size(); ++i) ASSERT_EQ(one_thread.points[i], two_threads.points[i]);
  EXPECT_EQ(one_thread.labels, two_threads.labels);
  bool differs = other_seed.size() != one_thread.size();
  for (std::size_t i = 0; !differs && i < one_thread.size(); ++i)
    differs = one_thread.points[i] != other_seed.points[i];
  EXPECT_TRUE(differs);
}

TEST(Simulator, WritesIdenticalSequencesForTheSameSeed) {
  const Scene scene = parse_scene(kScene, "small.yaml", ".");
  const fs::path a = fresh_temp_dir("a"), b = fresh_temp_dir("b");
  write_sequence(Simulator(scene, 9), a.string());
  write_sequence(Simulator(scene, 9), b.string());
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), a);
    ASSERT_TRUE(fs::exists(b / rel)) << rel;
    EXPECT_EQ(read_file(e.path()), read_file(b / rel)) << rel;
    ++files;
  }
  const Simulator sim(scene, 9);
  EXPECT_EQ(files, 2 * sim.num_scans() + 6);  // .bin + .label per scan, and 6 text files
  // And the reader sees what the simulator made.
  const io::SequenceReader seq(a.string());
  ASSERT_EQ(seq.size(), sim.num_scans());
  EXPECT_TRUE(seq.info().groundtruth[3].isApprox(sim.true_poses()[3], 1e-8));
  EXPECT_TRUE(seq.info().odometry[3].isApprox(sim.odometry_poses()[3], 1e-8));
  ASSERT_EQ(seq.info().rooms.size(), 2u);
  EXPECT_EQ(seq.info().rooms[1].name, "east");
  EXPECT_EQ(seq.info().rooms[1].level, "G");
  EXPECT_EQ(seq.info().lap_starts, std::vector<double>{0.0});
  EXPECT_EQ(read_file(seq.scene_path()), kScene);
  const PointCloud scan = seq.scan(3);
  const PointCloud direct = sim.scan(3);
  ASSERT_EQ(scan.size(), direct.size());
  EXPECT_EQ(scan.labels, direct.labels);
  EXPECT_EQ(scan.points[10], direct.points[10]);
  fs::remove_all(a);
  fs::remove_all(b);
}

namespace {

int run(const std::string& args, std::string* err) { return test::run_tsgraphs(args, nullptr, err); }

}  // namespace

TEST_F(Cli, BadSceneExitsTwoWithOneLineNamingFileAndLine) {
  const fs::path scene = dir_ / "bad.yaml";
  std::ofstream(scene) << "levels:\n  - name: L0\n    slab: [[0,0],[5,0],[5,5],[0,5]]\n    colour: red\n"
                          "trajectory: {waypoints: [[1,1],[2,2]]}\n";
  std::string err;
  EXPECT_EQ(run("simulate " + scene.string() + " --out " + (dir_ / "seq").string(), &err), 2);
  EXPECT_THAT(err, ::testing::HasSubstr(scene.string() + ":4: unknown key 'levels[0].colour'"));
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
  EXPECT_FALSE(fs::exists(dir_ / "seq"));
  // A folder that is not an earlier sequence is never overwritten.
  fs::create_directories(dir_ / "mine");
  std::ofstream(dir_ / "mine" / "notes.txt") << "keep";
  std::ofstream(scene)
      << "levels:\n  - name: L0\n    slab: [[0,0],[5,0],[5,5],[0,5]]\n"
         "trajectory: {waypoints: [[1,1],[2,2]], laps: 1}\nsensor: {channels: 4, columns: 16}\n";
  EXPECT_EQ(run("-q simulate " + scene.string() + " --out " + (dir_ / "mine").string(), &err), 2);
  EXPECT_EQ(read_file(dir_ / "mine" / "notes.txt"), "keep");
  // A good run writes the folder; a second run replaces it; no temporary folder is left.
  EXPECT_EQ(run("-q simulate " + scene.string() + " --out " + (dir_ / "seq").string() + " --seed 4", &err), 0)
      << err;
  EXPECT_TRUE(fs::exists(dir_ / "seq" / "times.txt"));
  EXPECT_EQ(run("-q simulate " + scene.string() + " --out " + (dir_ / "seq").string() + " --laps 2", &err), 0)
      << err;
  EXPECT_EQ(io::SequenceReader((dir_ / "seq").string()).info().lap_starts.size(), 2u);
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 3);  // bad.yaml, mine, seq
  EXPECT_EQ(run("simulate no_such_scene --out " + (dir_ / "x").string(), &err), 2);
  EXPECT_THAT(err, ::testing::HasSubstr("no such scene file (built-in scenes:"));
  EXPECT_EQ(run("simulate", &err), 2);
  // Output places that cannot be written are bad input too.
  EXPECT_EQ(run("-q simulate " + scene.string() + " --out /proc/no_such_place/seq", &err), 2);
  EXPECT_THAT(err, ::testing::HasSubstr("/proc/no_such_place/seq: cannot create the output folder"));
  EXPECT_EQ(run("draw-scene " + scene.string() + " --out /nonexistent/dir/x.svg", &err), 2);
  EXPECT_EQ(run("simulate " + dir_.string() + " --out " + (dir_ / "x").string(), &err), 2);
  EXPECT_THAT(err, ::testing::HasSubstr(dir_.string() + ": cannot open file"));
}

TEST_F(Cli, KilledRunLeavesNoSequenceAndTheNextRunCleansUp) {
  const fs::path scene = dir_ / "long.yaml";
  // 400 m of path: thousands of scans, far longer than the moment we kill it.
  std::ofstream(scene) << "levels: [{name: L0, slab: [[0,0],[110,0],[110,10],[0,10]]}]\n"
                          "walls: [{level: L0, from: [0, 0], to: [110, 0]}]\n"
                          "sensor: {channels: 32, columns: 512}\n"
                          "trajectory: {waypoints: [[2, 5], [102, 5]], laps: 2}\n";
  const fs::path out = dir_ / "seq";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::freopen("/dev/null", "w", stderr);
    ::execl(TSGRAPHS_BINARY, TSGRAPHS_BINARY, "-q", "simulate", scene.c_str(), "--out", out.c_str(), nullptr);
    ::_exit(127);
  }
  // Wait until scans are being written, then kill it hard.
  bool writing = false;
  for (int i = 0; i < 400 && !writing; ++i) {
    ::usleep(25000);
    for (const auto& e : fs::directory_iterator(dir_)) {
      if (e.path().filename().string().rfind("seq.tmp-", 0) == 0 &&
          fs::exists(e.path() / "scans" / "000005.bin"))
        writing = true;
    }
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(writing) << "the simulation never started writing";
  ASSERT_TRUE(WIFSIGNALED(status)) << "the simulation finished before it was killed";
  EXPECT_FALSE(fs::exists(out));  // nothing that looks like a sequence
  // The next run into the same place completes and removes the dead run's temporary folder.
  std::ofstream(scene) << "levels: [{name: L0, slab: [[0,0],[10,0],[10,10],[0,10]]}]\n"
                          "sensor: {channels: 4, columns: 16}\n"
                          "trajectory: {waypoints: [[2, 5], [8, 5]], laps: 1}\n";
  std::string err;
  EXPECT_EQ(run("-q simulate " + scene.string() + " --out " + out.string(), &err), 0) << err;
  EXPECT_TRUE(fs::exists(out / "times.txt"));
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"long.yaml", "seq"}));
}
