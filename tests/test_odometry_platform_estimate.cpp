// The platform measured from scans: the sensor's height above the floor and its tilt from
// simulated scans at the heights of a legged robot, a wheeled one and a person's hand, bobbing
// and swaying; the beam layout of simulated sensors and of a real Velodyne HDL-32e scan.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/odometry/platform_estimate.hpp"
#include "tsgraphs/generator/generator.hpp"
#include "tsgraphs/scene/platform_presets.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;
using odometry::estimate_platform;
using odometry::measure_beam_layout;

namespace {

constexpr double kDegToRad = M_PI / 180.0;

// A room with a desk; the sensor preset is filled in per test.
std::string room_scene(const std::string& preset) {
  return R"(name: platform_room
seed: 3
sensor: {preset: )" +
         preset + R"(, columns: 512}
levels:
  - {name: G, elevation: 0.0, ceiling: 2.8, slab: [[0,0],[12,0],[12,9],[0,9]]}
walls:
  - {level: G, from: [0, 0], to: [12, 0]}
  - {level: G, from: [12, 0], to: [12, 9]}
  - {level: G, from: [12, 9], to: [0, 9]}
  - {level: G, from: [0, 9], to: [0, 0]}
boxes:
  - {level: G, min: [7, 6, 0], max: [8.5, 7, 0.75], label: desk}
trajectory:
  level: G
  waypoints: [[2, 2], [9, 2]]
)";
}

// Scan k of a walk at `height`: the sensor bobs by `bob` (m) and sways in pitch and roll by
// `sway_deg`, as a hand-held sensor does, moving 0.3 m per scan.
Pose3 walking_pose(int k, double height, double bob, double sway_deg) {
  const double phase = 1.3 * k;
  Pose3 T = Pose3::Identity();
  T.linear() = (Eigen::AngleAxisd(0.2 * k, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(sway_deg * std::sin(phase) * kDegToRad, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(sway_deg * std::cos(phase) * kDegToRad, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(3.0 + 0.3 * k, 3.5, height + bob * std::sin(2.0 * phase));
  return T;
}

std::vector<PointCloud> walk(const sim::Simulator& sim, double height, double bob, double sway_deg,
                             int n = 10) {
  std::vector<PointCloud> scans;
  for (int k = 0; k < n; ++k) scans.push_back(sim.scan_at(walking_pose(k, height, bob, sway_deg), k));
  return scans;
}

}  // namespace

TEST(PlatformEstimate, HeightWithinFiveCentimetresFromLeggedToHandHeld) {
  const sim::Simulator sim(scene::parse_scene(room_scene("os1-64"), "platform_room.yaml", "."), 1);
  struct Case {
    double height, bob, sway_deg;
  };
  // A legged robot trots (small bob), a wheeled one rolls level, a person's hand bobs and sways.
  for (const Case c :
       {Case{0.3, 0.02, 2.0}, Case{0.55, 0.0, 0.0}, Case{1.2, 0.04, 5.0}, Case{1.8, 0.04, 5.0}}) {
    SCOPED_TRACE("height " + std::to_string(c.height));
    const odometry::PlatformEstimate e = estimate_platform(walk(sim, c.height, c.bob, c.sway_deg));
    EXPECT_EQ(e.scans_measured, 10u);
    EXPECT_EQ(e.floors_found, 10u);
    ASSERT_TRUE(e.height_found);
    EXPECT_NEAR(e.height, c.height, 0.05);
    EXPECT_LE(e.height_spread, 2.0 * c.bob + 0.03);
    EXPECT_LE(e.tilt_deg, c.sway_deg + 0.5);
    // With the poses' gravity, as a run with poses measures it: the same within 2 cm.
    std::vector<Eigen::Vector3d> ups;
    for (int k = 0; k < 10; ++k)
      ups.push_back(walking_pose(k, c.height, c.bob, c.sway_deg).linear().transpose() *
                    Eigen::Vector3d::UnitZ());
    const odometry::PlatformEstimate with_poses =
        estimate_platform(walk(sim, c.height, c.bob, c.sway_deg), {}, {}, ups);
    ASSERT_TRUE(with_poses.height_found);
    EXPECT_NEAR(with_poses.height, c.height, 0.02);
    EXPECT_NEAR(with_poses.tilt_deg, e.tilt_deg, 1.0);
    // From 0.3 m the lowest beams meet the floor nearer than ring_min_range (1 m): not counted.
    EXPECT_GE(e.beams.rings, c.height < 0.5 ? 60 : 64);
    EXPECT_NEAR(e.beams.spacing_deg, 45.0 / 63.0, 0.02);
  }
}

TEST(PlatformEstimate, ATiltedSensorsHeightIsAlongTheFloorsNormal) {
  const sim::Simulator sim(scene::parse_scene(room_scene("os1-64"), "platform_room.yaml", "."), 1);
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(12.0 * kDegToRad, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(5.0, 4.0, 1.5);
  const odometry::PlatformEstimate e = estimate_platform({sim.scan_at(T, 0)});
  ASSERT_TRUE(e.height_found);
  EXPECT_NEAR(e.height, 1.5, 0.02);
  EXPECT_NEAR(e.tilt_deg, 12.0, 0.3);
}

TEST(PlatformEstimate, NoFloorIsSaidNotGuessed) {
  const sim::Simulator sim(scene::parse_scene(room_scene("os1-64"), "platform_room.yaml", "."), 1);
  // Only the returns above the sensor's horizon: no floor (and the walls' feet, which would
  // give it, are gone too).
  std::vector<PointCloud> scans = walk(sim, 0.55, 0.0, 0.0, 3);
  for (PointCloud& scan : scans) {
    PointCloud kept;
    for (const Eigen::Vector3f& p : scan.points)
      if (p.z() > 0.0f) kept.points.push_back(p);
    scan = kept;
  }
  const odometry::PlatformEstimate e = estimate_platform(scans);
  EXPECT_EQ(e.scans_measured, 3u);
  EXPECT_EQ(e.floors_found, 0u);
  EXPECT_FALSE(e.height_found);
  EXPECT_FALSE(estimate_platform({}).height_found);
  odometry::PlatformEstimateConfig bad;
  bad.scans = 0;
  EXPECT_THROW(estimate_platform(scans, {}, bad), std::invalid_argument);
}

TEST(BeamLayout, SimulatedSensorsRingsAndTheirGroundPreset) {
  struct Case {
    const char* preset;
    int rings;
    double lowest_deg, spacing_deg;
    const char* ground_preset;
  };
  for (const Case c :
       {Case{"os1-64", 64, -22.5, 45.0 / 63.0, "os1-64"}, Case{"vlp-16", 16, -15.0, 2.0, "vlp-16"},
        Case{"hesai-xt32", 32, -16.0, 1.0, "hesai-xt32"},
        Case{"os0-128", 128, -45.0, 90.0 / 127.0, "os1-64"}}) {
    SCOPED_TRACE(c.preset);
    const sim::Simulator sim(scene::parse_scene(room_scene(c.preset), "platform_room.yaml", "."), 1);
    // High enough that the os0-128's lowest beam (45 deg down) meets the floor beyond
    // ring_min_range (1 m).
    Pose3 T = Pose3::Identity();
    T.translation() = Eigen::Vector3d(6.0, 4.5, 1.2);
    const odometry::BeamLayout layout = measure_beam_layout(sim.scan_at(T, 0));
    EXPECT_EQ(layout.rings, c.rings);
    EXPECT_NEAR(layout.lowest_deg, c.lowest_deg, 0.05);
    EXPECT_NEAR(layout.spacing_deg, c.spacing_deg, 0.02);
    EXPECT_EQ(ground::preset_for_ring_spacing(layout.spacing_deg), c.ground_preset);
  }
  EXPECT_EQ(measure_beam_layout(PointCloud{}).rings, 0);
  EXPECT_EQ(ground::preset_for_ring_spacing(0.0), "");
}

TEST(BeamLayout, RealVelodyneHdl32eScan) {
  // 32 lasers 1.33 deg apart from -30.67 to +10.67 deg; outdoors the highest ones may see only sky.
  const PointCloud scan = io::read_pcd(std::string(TSGRAPHS_TEST_DATA_DIR) + "/hdl32_pair/251370668.pcd");
  const odometry::BeamLayout layout = measure_beam_layout(scan);
  EXPECT_GE(layout.rings, 24);
  EXPECT_LE(layout.rings, 32);
  EXPECT_NEAR(layout.lowest_deg, -30.67, 0.3);
  EXPECT_NEAR(layout.spacing_deg, 1.33, 0.05);
  EXPECT_EQ(ground::preset_for_ring_spacing(layout.spacing_deg), "hesai-xt32");
}

TEST(PlatformEstimate, SweptHandHeldScansOfAGeneratedBuilding) {
  // A person walking a generated mixed building (small rooms off corridors) with a 32-beam
  // sensor at 1.5 m: its floor rings start 5.2 m out, where the tilting within a sweep moves
  // the floor by tens of centimetres in single scans; the median of the default 30 holds.
  scene::Scene scene = generator::generate_building("mixed", 1).scene;
  scene::apply_preset("hesai-xt32", &scene.sensor);
  scene.sensor.preset = "hesai-xt32";
  scene.sensor.mount_height = 1.5;
  scene.platform = scene::platform_defaults(scene::PlatformType::kHandheld);
  const sim::Simulator sim(scene, 1);
  const odometry::PlatformEstimateConfig config;
  std::vector<PointCloud> scans;
  std::vector<Eigen::Vector3d> ups;
  for (int j = 0; j < config.scans; ++j) {
    const std::size_t k = static_cast<std::size_t>(j) * (sim.num_scans() - 1) / (config.scans - 1);
    scans.push_back(sim.scan(k));
    ASSERT_TRUE(scans.back().has_times());
    ups.push_back(sim.odometry_poses()[k].linear().transpose() * Eigen::Vector3d::UnitZ());
  }
  const odometry::PlatformEstimate e = estimate_platform(scans, {}, config, ups);
  ASSERT_TRUE(e.height_found);
  EXPECT_NEAR(e.height, 1.5, 0.05) << e.floors_found << " floors, spread " << e.height_spread;
  EXPECT_GT(e.height_spread, 0.1) << "single swept scans do miss";
}
