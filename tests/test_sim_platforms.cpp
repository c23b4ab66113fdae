// Simulated platforms (scene `platform:`): a hand-held sensor bobs and sways and sweeps its
// scans, a legged one trots, a wheeled one (the default) rolls level and takes each scan at one
// instant; the section loads, is checked and is written back; a swept sequence carries its
// per-point times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "test_support.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/scene/platform_presets.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

namespace {

std::string scene_with(const std::string& platform) {
  return R"(name: platform_walk
seed: 2
sensor: {preset: vlp-16, mount_height: 1.4, rate_hz: 5}
)" + platform +
         R"(
levels:
  - {name: G, elevation: 0.0, ceiling: 3.0, slab: [[0,0],[10,0],[10,6],[0,6]]}
walls:
  - {level: G, from: [0, 0], to: [10, 0]}
  - {level: G, from: [10, 0], to: [10, 6]}
  - {level: G, from: [10, 6], to: [0, 6]}
  - {level: G, from: [0, 6], to: [0, 0]}
trajectory:
  level: G
  laps: 1
  waypoints: [[2, 2], [8, 2], [8, 4], [2, 4]]
)";
}

struct Motion {
  double z_range = 0.0;       ///< max - min of the sensor's height (m)
  double max_tilt_deg = 0.0;  ///< the largest angle of the sensor's z from the vertical
};

// Over the first 10 s, every 10 ms (the scans alone may sample a gait at one phase).
Motion motion_of(const sim::Simulator& sim) {
  Motion m;
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < 1000; ++i) {
    const Pose3 p = sim.sensor_pose_at(0.01 * i);
    lo = std::min(lo, p.translation().z());
    hi = std::max(hi, p.translation().z());
    m.max_tilt_deg = std::max(m.max_tilt_deg, std::acos(std::min(1.0, p.linear()(2, 2))) * 180.0 / M_PI);
  }
  m.z_range = hi - lo;
  return m;
}

}  // namespace

TEST(SimPlatforms, HandHeldBobsSwaysAndSweepsWheeledRollsLevel) {
  const sim::Simulator wheeled(scene::parse_scene(scene_with(""), "w.yaml", "."), 1);
  const sim::Simulator handheld(scene::parse_scene(scene_with("platform: {type: handheld}"), "h.yaml", "."),
                                1);
  const sim::Simulator legged(scene::parse_scene(scene_with("platform: {type: legged}"), "l.yaml", "."), 1);
  const Motion w = motion_of(wheeled), h = motion_of(handheld), l = motion_of(legged);
  EXPECT_LT(w.z_range, 1e-9);
  EXPECT_LT(w.max_tilt_deg, 1e-6);
  // A 0.03 m bob and 4 degrees of sway; a trot's 0.01 m bob, 0.004 m vibration and 1.5 degrees.
  EXPECT_GT(h.z_range, 0.04);
  EXPECT_LE(h.z_range, 0.06 + 1e-9);
  EXPECT_GT(h.max_tilt_deg, 3.0);
  EXPECT_LT(h.max_tilt_deg, 4.5);
  EXPECT_GT(l.z_range, 0.01);
  EXPECT_LE(l.z_range, 0.028 + 1e-9);
  EXPECT_LT(l.max_tilt_deg, 1.7);
  // The same path: the platforms differ only by their gait.
  ASSERT_EQ(handheld.num_scans(), wheeled.num_scans());
  for (std::size_t k = 0; k < wheeled.num_scans(); k += 7)
    EXPECT_LT(
        (handheld.true_poses()[k].translation() - wheeled.true_poses()[k].translation()).head<2>().norm(),
        1e-9);

  EXPECT_FALSE(wheeled.scan(3).has_times());
  const PointCloud swept = handheld.scan(3);
  ASSERT_EQ(swept.times.size(), swept.size());
  EXPECT_GE(*std::min_element(swept.times.begin(), swept.times.end()), 0.0f);
  EXPECT_LT(*std::max_element(swept.times.begin(), swept.times.end()), 0.2f);  // 5 Hz
  EXPECT_GT(*std::max_element(swept.times.begin(), swept.times.end()), 0.19f);
  // The pose between scans follows the same gait.
  EXPECT_TRUE(handheld.sensor_pose_at(handheld.times()[3]).isApprox(handheld.true_poses()[3], 1e-9));
}

TEST(SimPlatforms, SectionLoadsIsCheckedAndIsWrittenBack) {
  const scene::Scene s = scene::parse_scene(
      scene_with("platform: {type: legged, bob: 0.02, motion_distortion: false}"), "p.yaml", ".");
  EXPECT_EQ(s.platform.type, scene::PlatformType::kLegged);
  EXPECT_DOUBLE_EQ(s.platform.bob, 0.02);
  EXPECT_DOUBLE_EQ(s.platform.step_hz, scene::platform_defaults(scene::PlatformType::kLegged).step_hz);
  EXPECT_FALSE(s.platform.motion_distortion);
  const scene::Scene again = scene::parse_scene(scene::scene_yaml(s, "again"), "again.yaml", ".");
  EXPECT_EQ(again.platform.type, s.platform.type);
  EXPECT_DOUBLE_EQ(again.platform.bob, 0.02);
  EXPECT_EQ(again.platform.motion_distortion, false);
  // A wheeled scene writes no platform section: old readers still load it.
  EXPECT_EQ(scene::scene_yaml(scene::parse_scene(scene_with(""), "w.yaml", "."), "w").find("platform:"),
            std::string::npos);

  const auto error = [](const std::string& platform) {
    return test::input_error_of([&] { scene::parse_scene(scene_with(platform), "p.yaml", "."); });
  };
  EXPECT_NE(error("platform: {type: hovering}").find("p.yaml:4: platform.type: unknown platform 'hovering'"),
            std::string::npos)
      << error("platform: {type: hovering}");
  EXPECT_NE(error("platform: {type: handheld, sway_deg: 45}").find("platform.sway_deg: must lie in [0, 30]"),
            std::string::npos);
  EXPECT_NE(error("platform: {bob: 0.05}").find("platform.step_hz: must be > 0 when bob is"),
            std::string::npos);
  EXPECT_NE(error("platform: {type: legged, wobble: 1}").find("unknown key 'platform.wobble'"),
            std::string::npos)
      << error("platform: {type: legged, wobble: 1}");
}

TEST(SimPlatforms, SweptSequenceCarriesItsTimes) {
  const std::filesystem::path dir = test::fresh_temp_dir();
  const sim::Simulator sim(scene::parse_scene(scene_with("platform: {type: handheld}"), "h.yaml", "."), 1);
  sim::write_sequence(sim, (dir / "seq").string());
  const io::SequenceReader reader((dir / "seq").string());
  const PointCloud scan = reader.scan(2);
  ASSERT_TRUE(scan.has_times());
  EXPECT_EQ(scan.times, sim.scan(2).times);
  std::filesystem::remove_all(dir);
}

TEST(SimPlatforms, ARecordingKeepsEveryNthSweep) {
  // A 10 Hz sensor stored at 2 Hz: scans 0.5 s apart, each swept over 0.1 s.
  std::string text = scene_with("platform: {type: handheld}");
  text.replace(text.find("rate_hz: 5"), 10, "rate_hz: 10, record_hz: 2");
  const sim::Simulator sim(scene::parse_scene(text, "r.yaml", "."), 1);
  ASSERT_GE(sim.num_scans(), 3u);
  EXPECT_NEAR(sim.times()[1] - sim.times()[0], 0.5, 1e-9);
  const PointCloud scan = sim.scan(1);
  EXPECT_LT(*std::max_element(scan.times.begin(), scan.times.end()), 0.1f);
  EXPECT_GT(*std::max_element(scan.times.begin(), scan.times.end()), 0.09f);
  std::string bad = scene_with("");
  bad.replace(bad.find("rate_hz: 5"), 10, "rate_hz: 5, record_hz: 8");
  EXPECT_NE(test::input_error_of([&] {
              scene::parse_scene(bad, "b.yaml", ".");
            }).find("sensor.record_hz: must lie in (0, rate_hz]"),
            std::string::npos);
}
