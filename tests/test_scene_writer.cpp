// The scene writer: every built-in scene written and read back is the same scene.
#include <gtest/gtest.h>

#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;

namespace {

void expect_near(const Polygon2& a, const Polygon2& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LT((a[i] - b[i]).norm(), 1e-4);
}

}  // namespace

TEST(SceneWriter, BuiltinScenesRoundTrip) {
  for (const auto& [name, text] : builtin_scenes()) {
    SCOPED_TRACE(name);
    const Scene a = parse_scene(text, name + ".yaml", ".");
    const std::string written = scene_yaml(a, "a header\nof two lines");
    EXPECT_EQ(written.rfind("# a header\n# of two lines\n", 0), 0u);
    const Scene b = parse_scene(written, name + ".yaml", ".");
    EXPECT_EQ(scene_yaml(b, "a header\nof two lines"), written);  // the writer is a fixed point
    EXPECT_TRUE(b.warnings.empty());
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.seed, b.seed);
    EXPECT_EQ(a.sensor.preset, b.sensor.preset);
    EXPECT_EQ(a.sensor.vertical_angles_deg, b.sensor.vertical_angles_deg);
    EXPECT_EQ(a.sensor.columns, b.sensor.columns);
    EXPECT_NEAR(a.sensor.mount_height, b.sensor.mount_height, 1e-4);
    EXPECT_DOUBLE_EQ(a.odometry.trans_noise_per_m, b.odometry.trans_noise_per_m);
    ASSERT_EQ(a.levels.size(), b.levels.size());
    for (std::size_t i = 0; i < a.levels.size(); ++i) {
      EXPECT_EQ(a.levels[i].name, b.levels[i].name);
      EXPECT_NEAR(a.levels[i].elevation, b.levels[i].elevation, 1e-4);
      expect_near(a.levels[i].slab, b.levels[i].slab);
      ASSERT_EQ(a.levels[i].voids.size(), b.levels[i].voids.size());
    }
    ASSERT_EQ(a.walls.size(), b.walls.size());
    for (std::size_t i = 0; i < a.walls.size(); ++i) {
      EXPECT_LT((a.walls[i].from - b.walls[i].from).norm(), 1e-4);
      EXPECT_NEAR(a.walls[i].thickness, b.walls[i].thickness, 1e-4);
      EXPECT_NEAR(a.walls[i].height, b.walls[i].height, 1e-4);
      EXPECT_EQ(a.walls[i].joined_from, b.walls[i].joined_from);
      ASSERT_EQ(a.walls[i].openings.size(), b.walls[i].openings.size());
      for (std::size_t k = 0; k < a.walls[i].openings.size(); ++k)
        EXPECT_NEAR(a.walls[i].openings[k].at, b.walls[i].openings[k].at, 1e-4);
    }
    ASSERT_EQ(a.railings.size(), b.railings.size());
    for (std::size_t i = 0; i < a.railings.size(); ++i) EXPECT_EQ(a.railings[i].style, b.railings[i].style);
    ASSERT_EQ(a.boxes.size(), b.boxes.size());
    for (std::size_t i = 0; i < a.boxes.size(); ++i) {
      EXPECT_LT((a.boxes[i].max - b.boxes[i].max).norm(), 1e-4);
      EXPECT_NEAR(a.boxes[i].yaw_deg, b.boxes[i].yaw_deg, 1e-4);
      EXPECT_EQ(a.boxes[i].label, b.boxes[i].label);
    }
    ASSERT_EQ(a.ramps.size(), b.ramps.size());
    ASSERT_EQ(a.rooms.size(), b.rooms.size());
    for (std::size_t i = 0; i < a.rooms.size(); ++i) {
      EXPECT_EQ(a.rooms[i].name, b.rooms[i].name);
      expect_near(a.rooms[i].polygon, b.rooms[i].polygon);
    }
    ASSERT_EQ(a.trajectory.waypoints.size(), b.trajectory.waypoints.size());
    for (std::size_t i = 0; i < a.trajectory.waypoints.size(); ++i) {
      EXPECT_LT((a.trajectory.waypoints[i].xy - b.trajectory.waypoints[i].xy).norm(), 1e-4);
      EXPECT_EQ(a.trajectory.waypoints[i].level, b.trajectory.waypoints[i].level);
    }
    EXPECT_EQ(a.trajectory.laps, b.trajectory.laps);
    EXPECT_EQ(a.trajectory.closed, b.trajectory.closed);
  }
}

TEST(SceneWriter, ASensorGivenByHandAndNamesThatNeedQuotes) {
  const char* text = R"(name: "a \"quoted\" name: with colons"
sensor: {channels: 8, columns: 90, vertical_fov_deg: [-10, 10], max_range: 30, rate_hz: 5}
levels: [{name: "floor #1", slab: [[0,0],[5,0],[5,5],[0,5]]}]
railings: [{level: "floor #1", from: [1, 1], to: [4, 1], style: glass, transmission: 0.35}]
trajectory: {waypoints: [[1, 3], [4, 3]]}
)";
  const Scene a = parse_scene(text, "hand.yaml", ".");
  const Scene b = parse_scene(scene_yaml(a), "hand.yaml", ".");
  EXPECT_EQ(b.name, a.name);
  EXPECT_EQ(b.levels[0].name, "floor #1");
  EXPECT_EQ(b.sensor.channels, 8);
  EXPECT_EQ(b.sensor.vertical_angles_deg, a.sensor.vertical_angles_deg);
  EXPECT_DOUBLE_EQ(b.sensor.rate_hz, 5.0);
  EXPECT_DOUBLE_EQ(b.sensor.max_range, 30.0);
  EXPECT_EQ(b.railings[0].style, RailingStyle::kGlass);
  EXPECT_DOUBLE_EQ(b.railings[0].transmission, 0.35);
}

TEST(SceneWriter, AWindowsPaneIsWrittenAndAnOpenOpeningSaysNothingOfIt) {
  const char* text = R"(name: windows
levels: [{name: L0, slab: [[0,0],[10,0],[10,5],[0,5]]}]
walls: [{level: L0, from: [0, 4], to: [10, 4], openings: [{at: 2, width: 1.2, height: 1.2, sill: 0.9, transmission: 0.65}, {at: 5, width: 1.0}]}]
trajectory: {waypoints: [[1, 2], [9, 2]]}
)";
  const std::string yaml = scene_yaml(parse_scene(text, "w.yaml", "."));
  EXPECT_NE(yaml.find("sill: 0.9, transmission: 0.65}"), std::string::npos) << yaml;
  EXPECT_EQ(yaml.find("transmission: 1"), std::string::npos) << yaml;
  const Scene b = parse_scene(yaml, "w.yaml", ".");
  EXPECT_DOUBLE_EQ(b.walls[0].openings[0].transmission, 0.65);
  EXPECT_DOUBLE_EQ(b.walls[0].openings[1].transmission, 1.0);
}
