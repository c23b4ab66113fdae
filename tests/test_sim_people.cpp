// People walking through the scans (scene `people:`): they walk their path there and back,
// each scan sees them where they stand at its time (each column of a swept scan at the
// column's), their returns carry label 7, and the section loads, is checked and is written back.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "test_support.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/sim/people.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

namespace {

constexpr double kRadius = 0.25;  // the people's default radius (m)

std::string scene_with(const std::string& platform, const std::string& people) {
  return R"(name: people_walk
seed: 3
sensor: {preset: vlp-16, mount_height: 1.0, rate_hz: 5}
)" + platform +
         R"(
levels:
  - {name: G, elevation: 0.0, ceiling: 3.0, slab: [[0,0],[12,0],[12,8],[0,8]]}
walls:
  - {level: G, from: [0, 0], to: [12, 0]}
  - {level: G, from: [12, 0], to: [12, 8]}
  - {level: G, from: [12, 8], to: [0, 8]}
  - {level: G, from: [0, 8], to: [0, 0]}
)" + people +
         R"(
trajectory:
  level: G
  laps: 1
  waypoints: [[6, 4], [9, 4]]
)";
}

const std::string kCrossing = "people:\n  - {level: G, path: [[3, 1], [3, 7]], speed: 3.0}\n";

sim::Simulator simulate(const std::string& text) {
  return sim::Simulator(scene::parse_scene(text, "people.yaml", "."), 1);
}

TEST(People, WalkThereAndBackAlongTheirPath) {
  const scene::Scene scene = scene::parse_scene(
      scene_with("", "people:\n  - {level: G, path: [[1, 1], [5, 1], [5, 3]], speed: 2.0, offset: 1.0}\n"),
      "p.yaml", ".");
  const sim::People people(scene);
  ASSERT_EQ(people.size(), 1u);
  // 6 m of path at 2 m/s, 1 m along at t = 0.
  EXPECT_TRUE(people.position(0, 0.0).isApprox(Eigen::Vector3d(2, 1, 0)));
  EXPECT_TRUE(people.position(0, 2.0).isApprox(Eigen::Vector3d(5, 2, 0)));  // 5 m: round the corner
  EXPECT_TRUE(people.position(0, 2.5).isApprox(Eigen::Vector3d(5, 3, 0)));  // the end
  EXPECT_TRUE(people.position(0, 3.0).isApprox(Eigen::Vector3d(5, 2, 0)));  // and back
  EXPECT_TRUE(people.position(0, 5.5).isApprox(Eigen::Vector3d(1, 1, 0)));  // the start
  EXPECT_TRUE(people.position(0, 6.0).isApprox(Eigen::Vector3d(2, 1, 0)));  // and again
}

TEST(People, AScanSeesThemWhereTheyStandAtItsTime) {
  const sim::Simulator sim = simulate(scene_with("", kCrossing));
  const sim::People people(sim.scene());
  ASSERT_GT(sim.num_scans(), 10u);
  for (std::size_t k = 0; k < 10; ++k) {
    const PointCloud scan = sim.scan(k);
    const Eigen::Vector3d foot = people.position(0, sim.times()[k]);
    int seen = 0;
    for (std::size_t i = 0; i < scan.size(); ++i) {
      if (scan.labels[i] != static_cast<std::uint32_t>(PointLabel::kPerson)) continue;
      ++seen;
      const Eigen::Vector3d p = sim.true_poses()[k] * scan.points[i].cast<double>();
      EXPECT_LE((p.head<2>() - foot.head<2>()).norm(), kRadius + 0.05) << "scan " << k;
      EXPECT_GE(p.z(), -0.05);
      EXPECT_LE(p.z(), 1.75 + 0.05);
    }
    EXPECT_GT(seen, 10) << "scan " << k;
  }
  // Without people, nothing carries their label.
  const sim::Simulator empty = simulate(scene_with("", ""));
  const PointCloud scan = empty.scan(0);
  EXPECT_EQ(
      std::count(scan.labels.begin(), scan.labels.end(), static_cast<std::uint32_t>(PointLabel::kPerson)), 0);
}

TEST(People, ASweptScanSeesThemWhereTheyStandWhenEachColumnFires) {
  // Behind the sensor (it heads +x from (6, 4)), so the columns that see the person fire about
  // half a sweep (0.1 s, 0.3 m of walking) after the stamp.
  const sim::Simulator sim = simulate(scene_with("platform: {type: handheld}\n", kCrossing));
  const sim::People people(sim.scene());
  int seen = 0;
  double moved = 0.0;
  for (std::size_t k = 0; k < 5; ++k) {
    const PointCloud scan = sim.scan(k);
    ASSERT_EQ(scan.times.size(), scan.size());
    for (std::size_t i = 0; i < scan.size(); ++i) {
      if (scan.labels[i] != static_cast<std::uint32_t>(PointLabel::kPerson)) continue;
      ++seen;
      const double t = sim.times()[k] + scan.times[i];
      const Eigen::Vector3d p = sim.sensor_pose_at(t) * scan.points[i].cast<double>();
      EXPECT_LE((p.head<2>() - people.position(0, t).head<2>()).norm(), kRadius + 0.05);
      moved += (p.head<2>() - people.position(0, sim.times()[k]).head<2>()).norm();
    }
  }
  ASSERT_GT(seen, 20);
  EXPECT_GT(moved / seen, kRadius + 0.1);  // not where they stood at the stamp
}

TEST(People, TheSectionIsCheckedAndWrittenBack) {
  const scene::Scene scene =
      scene::parse_scene(scene_with("",
                                    "people:\n  - {level: G, path: [[1, 1], [5, 1.5]], speed: 0.8, offset: "
                                    "2.5, height: 1.6, radius: 0.2}\n"
                                    "  - {level: G, path: [[2, 2], [2, 6], [4, 6]]}\n"),
                         "p.yaml", ".");
  ASSERT_EQ(scene.people.size(), 2u);
  EXPECT_DOUBLE_EQ(scene.people[0].speed, 0.8);
  EXPECT_DOUBLE_EQ(scene.people[1].speed, 1.2);  // the defaults
  EXPECT_DOUBLE_EQ(scene.people[1].height, 1.75);
  EXPECT_DOUBLE_EQ(scene.people[1].radius, 0.25);
  const scene::Scene again = scene::parse_scene(scene::scene_yaml(scene, "round trip"), "again.yaml", ".");
  ASSERT_EQ(again.people.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(again.people[i].path, scene.people[i].path);
    EXPECT_DOUBLE_EQ(again.people[i].speed, scene.people[i].speed);
    EXPECT_DOUBLE_EQ(again.people[i].offset, scene.people[i].offset);
    EXPECT_DOUBLE_EQ(again.people[i].height, scene.people[i].height);
    EXPECT_DOUBLE_EQ(again.people[i].radius, scene.people[i].radius);
  }

  const auto error = [](const std::string& person) {
    return test::input_error_of(
        [&] { scene::parse_scene(scene_with("", "people:\n  - " + person + "\n"), "b.yaml", "."); });
  };
  EXPECT_NE(error("{level: G, path: [[1, 1]]}").find("b.yaml:"), std::string::npos);
  EXPECT_NE(error("{level: G, path: [[1, 1]]}").find("path: expected a list of at least two [x, y] points"),
            std::string::npos);
  EXPECT_NE(
      error("{level: G, path: [[1, 1], [20, 1]]}").find("people[0].path[1]: [20, 1] is outside every slab"),
      std::string::npos);
  EXPECT_NE(error("{level: G, path: [[1, 1], [1, 1]]}").find("repeats the previous point"),
            std::string::npos);
  EXPECT_NE(error("{level: G, path: [[1, 1], [2, 1]], speed: 0}").find("speed: must be > 0"),
            std::string::npos);
  EXPECT_NE(error("{level: G, path: [[1, 1], [2, 1]], speed: 50}").find("speed: must be <= 10"),
            std::string::npos);
  EXPECT_NE(error("{level: G, path: [[1, 1], [2, 1]], radius: 100}").find("radius: must be <= 5 m"),
            std::string::npos);
  EXPECT_NE(error("{level: G, path: [[1, 1], [2, 1]], offset: .nan}").find("offset: not a finite number"),
            std::string::npos);
  EXPECT_NE(error("{level: X, path: [[1, 1], [2, 1]]}").find("unknown level 'X'"), std::string::npos);
  EXPECT_NE(error("{level: G, path: [[1, 1], [2, 1]], sped: 1}").find("sped"), std::string::npos);
}

}  // namespace
