// The platform as the pipeline resolves it (measured unless given, a fallback said aloud, the
// seed radius past the first floor ring, the preset's ground fields but the user's own), the
// `platform` parameters, and the warning when a layer stays empty.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "tsgraphs/pipeline/pipeline.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/pipeline/platform.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;
using namespace tsgraphs::pipeline;

namespace {

const char* kScene = R"(name: platform_room
seed: 3
sensor: {preset: os1-64, columns: 512}
levels:
  - {name: G, elevation: 0.0, ceiling: 3.0, slab: [[0,0],[12,0],[12,9],[0,9]]}
walls:
  - {level: G, from: [0, 0], to: [12, 0]}
  - {level: G, from: [12, 0], to: [12, 9]}
  - {level: G, from: [12, 9], to: [0, 9]}
  - {level: G, from: [0, 9], to: [0, 0]}
trajectory:
  level: G
  waypoints: [[2, 2], [9, 2]]
)";

class PlatformTest : public ::testing::Test {
 protected:
  PlatformTest() : sim_(scene::parse_scene(kScene, "platform_room.yaml", "."), 1) {}
  /// The sensor at `height` over (x, y), level; without the floor, only the returns above the
  /// sensor's horizon (the walls' feet would show the floor).
  PointCloud scan(double x, double y, double height, bool with_floor = true, std::uint64_t k = 0) const {
    PointCloud s = sim_.scan_at(pose(x, y, height), k);
    if (with_floor) return s;
    PointCloud kept;
    for (const Eigen::Vector3f& p : s.points)
      if (p.z() > 0.0f) kept.points.push_back(p);
    return kept;
  }
  static Pose3 pose(double x, double y, double height) {
    Pose3 T = Pose3::Identity();
    T.translation() = Eigen::Vector3d(x, y, height);
    return T;
  }
  sim::Simulator sim_;
};

bool has_warning(const Pipeline& p, const std::string& text) {
  return std::any_of(p.warnings().begin(), p.warnings().end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

/// Runs `n` scans back and forth along the room, 1.2 m apart (each a keyframe).
void walk(Pipeline& p, int n, const std::function<PointCloud(double x)>& scan_at) {
  for (int k = 0; k < n; ++k) {
    const int step = k % 12 < 6 ? k % 12 : 11 - k % 12;
    const double x = 2.0 + 1.2 * step;
    Pose3 odom = Pose3::Identity();
    odom.translation() = Eigen::Vector3d(x - 2.0 + 1e-3 * k, 0.0, 0.0);  // moving: every scan a keyframe
    p.process(static_cast<std::size_t>(k), 0.1 * k, scan_at(x), odom);
  }
}

}  // namespace

TEST_F(PlatformTest, MeasuredUnlessGiven) {
  const std::vector<PointCloud> scans = {scan(4, 4, 1.7), scan(5, 4, 1.7, true, 1)};
  const Platform measured = resolve_platform({}, {}, {}, scans);
  EXPECT_EQ(measured.sensor_height_source, "measured");
  EXPECT_NEAR(measured.sensor_height, 1.7, 0.03);
  // From 1.7 m an os1-64's lowest beam (-22.5 deg) meets the floor 4.1 m out: 1.5 m more.
  EXPECT_EQ(measured.seed_radius_source, "beams");
  EXPECT_NEAR(measured.seed_radius, 1.7 / std::tan(22.5 * M_PI / 180.0) + 1.5, 0.1);
  EXPECT_EQ(measured.preset, "os1-64");
  EXPECT_TRUE(measured.warnings.empty());
  // The far links of the ground follow the beams measured (45 deg over 64 rings), not a preset's.
  EXPECT_NEAR(apply_platform(measured, {}).ring_spacing_deg, 45.0 / 63.0, 0.02);
  EXPECT_NE(describe(measured).find("1.70 m above the floor (measured in 2 of 2 scans"), std::string::npos)
      << describe(measured);

  PlatformConfig given;
  given.sensor_height = 0.9;
  given.seed_radius = 4.0;
  given.preset = "vlp-16";
  const Platform p = resolve_platform(given, {}, {}, scans);
  EXPECT_EQ(p.sensor_height_source, "config");
  EXPECT_DOUBLE_EQ(p.sensor_height, 0.9);
  EXPECT_DOUBLE_EQ(p.seed_radius, 4.0);
  EXPECT_EQ(p.preset_source, "config");
  // The preset's ground fields, but not those the user's file set.
  const ground::GroundConfig g = apply_platform(p, {}, {"max_gap"});
  EXPECT_DOUBLE_EQ(g.sensor_height, 0.9);
  EXPECT_DOUBLE_EQ(g.seed_radius, 4.0);
  EXPECT_EQ(g.num_min_pts, ground::per_sensor_preset("vlp-16").num_min_pts);
  EXPECT_DOUBLE_EQ(g.max_gap, ground::GroundConfig{}.max_gap);
}

TEST_F(PlatformTest, NoFloorFallsBackAloud) {
  const Platform p = resolve_platform({}, {}, {}, {scan(4, 4, 0.55, false)});
  EXPECT_EQ(p.sensor_height_source, "fallback");
  EXPECT_DOUBLE_EQ(p.sensor_height, PlatformConfig{}.fallback_sensor_height);
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_NE(p.warnings[0].find("no floor found under the 1 scans measured"), std::string::npos)
      << p.warnings[0];
  // Nothing at all: no beam layout either, and both are said.
  EXPECT_EQ(resolve_platform({}, {}, {}, {}).warnings.size(), 2u);
}

TEST_F(PlatformTest, ParameterFileTakesAutoOrANumber) {
  const PipelineConfig c =
      parse_pipeline_config("platform:\n  sensor_height: 1.62\n  preset: none\n", "p.yaml");
  ASSERT_TRUE(c.platform.sensor_height.has_value());
  EXPECT_DOUBLE_EQ(*c.platform.sensor_height, 1.62);
  EXPECT_FALSE(c.platform.seed_radius.has_value());
  EXPECT_FALSE(parse_pipeline_config("platform:\n  sensor_height: auto\n", "p.yaml").platform.sensor_height);
  const auto error = [](const std::string& text) {
    return test::input_error_of([&] { parse_pipeline_config(text, "p.yaml"); });
  };
  EXPECT_NE(error("platform:\n  sensor_height: tall\n")
                .find("p.yaml:2: platform.sensor_height: expected a number or auto"),
            std::string::npos);
  EXPECT_NE(error("platform:\n  sensor_height: -1\n").find("p.yaml:2"), std::string::npos);
  EXPECT_NE(
      error("platform:\n  preset: kinect\n").find("p.yaml:2: platform.preset: must be auto, none, os1-64"),
      std::string::npos);
  // The key's old place says where it went.
  EXPECT_NE(
      error("ground:\n  sensor_height: 1.6\n").find("ground.sensor_height is now platform.sensor_height"),
      std::string::npos);
  // The ground keys a file sets are kept from the platform's preset.
  EXPECT_EQ(parse_pipeline_config("ground:\n  max_gap: 3.3\n", "p.yaml").ground_keys_given,
            std::set<std::string>{"max_gap"});
  // A resolved run's parameters read back to the same platform.
  PipelineConfig resolved;
  resolved.platform.sensor_height = 1.25;
  resolved.platform.seed_radius = 4.5;
  const std::string text = dump_pipeline_config(resolved);
  EXPECT_NE(text.find("sensor_height: 1.25"), std::string::npos);
  EXPECT_EQ(dump_pipeline_config(parse_pipeline_config(text, "dumped.yaml")), text);
  EXPECT_NE(dump_pipeline_config(PipelineConfig{}).find("sensor_height: auto"), std::string::npos);
}

TEST_F(PlatformTest, WarnsOnceWhenNoFloorGivesNoGroundThenCounts) {
  PipelineConfig config;
  config.diagnostics.empty_layer_keyframes = 5;
  Pipeline p(config);
  walk(p, 8, [this](double x) { return scan(x, 4.5, 0.55, false); });
  p.finish();
  EXPECT_TRUE(has_warning(p, "no floor found under the 1 scans measured"));
  EXPECT_TRUE(has_warning(p,
                          "no traversable ground in 5 keyframes in a row (to keyframe 4): no floor found "
                          "below the sensor there"));
  EXPECT_TRUE(has_warning(p, "no traversable ground in 7 of 7 keyframes in all"))
      << ::testing::PrintToString(p.warnings());
  const auto n = std::count_if(p.warnings().begin(), p.warnings().end(),
                               [](const std::string& w) { return w.find("in a row") != std::string::npos; });
  EXPECT_EQ(n, 1) << "once, then a count";
  EXPECT_FALSE(has_warning(p, "no wall")) << "the room's walls are seen";
}

TEST_F(PlatformTest, NoWallSaysSoAndARunWithoutARoomSaysWhyAtItsEnd) {
  PipelineConfig config;
  config.diagnostics.empty_layer_keyframes = 5;
  // The S-Graphs+ mode: rooms from walls only (the traversable mode's sight map makes a space of
  // rays alone, even under a bare ceiling: see the issue's note).
  config.rooms.layer.free_space_method = room_layer::FreeSpaceMethod::esdf;
  config.rooms.layer.room_trigger = room_layer::RoomTrigger::timer;
  Pipeline p(config);
  // Only the ceiling's returns: nothing to walk on, nothing standing.
  walk(p, 8, [this](double x) {
    const PointCloud s = sim_.scan_at(pose(x, 4.5, 0.55), 0);
    PointCloud ceiling;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s.labels[i] == static_cast<std::uint32_t>(PointLabel::kCeiling))
        ceiling.points.push_back(s.points[i]);
    return ceiling;
  });
  EXPECT_TRUE(has_warning(p, "no wall in 5 keyframes in a row (to keyframe 4): no vertical plane"))
      << ::testing::PrintToString(p.warnings());
  EXPECT_FALSE(has_warning(p, "no room")) << "said only at the end";
  p.finish();
  EXPECT_TRUE(has_warning(p, "no wall in 7 of 7 keyframes in all"));
  EXPECT_TRUE(has_warning(
      p, "no room in 7 keyframes: 0 traversable nodes and 0 walls mapped (no traversable ground)"))
      << ::testing::PrintToString(p.warnings());
}

TEST_F(PlatformTest, WarningNamesTheFloorItMeasuredAgainstTheHeightGiven) {
  PipelineConfig config;
  config.diagnostics.empty_layer_keyframes = 4;
  config.platform.sensor_height = 0.3;  // the user typed a legged robot's height; the sensor is hand-held
  Pipeline p(config);
  walk(p, 5, [this](double x) { return scan(x, 4.5, 1.6); });
  ASSERT_TRUE(has_warning(p, "no traversable ground in 4 keyframes in a row"))
      << (p.warnings().empty() ? "" : p.warnings()[0]);
  EXPECT_TRUE(
      has_warning(p, "the floor is 1.60 m below the sensor there and platform.sensor_height is 0.30 m"))
      << p.warnings()[0];

  // Measured, the same scans give ground and no such warning.
  config.platform.sensor_height.reset();
  Pipeline measured(config);
  walk(measured, 5, [this](double x) { return scan(x, 4.5, 1.6); });
  EXPECT_NEAR(measured.platform()->sensor_height, 1.6, 0.03);
  EXPECT_FALSE(has_warning(measured, "no traversable ground"));
  EXPECT_GT(measured.node_map().size(), 0u);
}
