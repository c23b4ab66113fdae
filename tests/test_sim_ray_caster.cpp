// Ray casting against scene geometry, checked against hand-computed ground truth.
#include <gtest/gtest.h>

#include <cmath>

#include "tsgraphs/sim/ray_caster.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/sim/scene_mesh.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;
using namespace tsgraphs::sim;
using namespace tsgraphs::scene;

namespace {

constexpr auto kWall = static_cast<std::uint32_t>(PointLabel::kWall);
constexpr auto kFloor = static_cast<std::uint32_t>(PointLabel::kFloor);
constexpr auto kCeiling = static_cast<std::uint32_t>(PointLabel::kCeiling);
constexpr auto kRailing = static_cast<std::uint32_t>(PointLabel::kRailing);

// Two storeys: a 20 x 12 m lower hall (elevation 0) and an upper floor (elevation 4) with a
// 6 x 4 m void, railings round it (bars on the south side, solid on the north), and a wall
// with a door (x in [9.5, 10.5], up to 2.1 m) and a window.
const char* kScene = R"(name: rays
sensor: {channels: 16, columns: 360, vertical_fov_deg: [-15, 15], range_noise_std: 0.01}
levels:
  - {name: L0, elevation: 0.0, ceiling: 3.8, slab: [[0,0],[20,0],[20,12],[0,12]]}
  - name: L1
    elevation: 4.0
    ceiling: 3.0
    slab: [[0,0],[20,0],[20,12],[0,12]]
    voids: [[[7,4],[13,4],[13,8],[7,8]]]
walls:
  - level: L1
    from: [0, 10]
    to: [20, 10]
    thickness: 0.2
    openings:
      - {at: 10.0, width: 1.0, height: 2.1}
      - {at: 15.0, width: 2.0, height: 1.0, sill: 1.0}
  - {level: L1, from: [20, 0], to: [20, 12]}
railings:
  - {level: L1, from: [7, 4], to: [13, 4], height: 1.0, style: bars}
  - {level: L1, from: [7, 8], to: [13, 8], height: 1.0, style: solid}
trajectory:
  level: L1
  waypoints: [[2, 2], [18, 2]]
)";

class RayCasterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = parse_scene(kScene, "rays.yaml", ".");
    caster_ = std::make_unique<RayCaster>(build_scene_mesh(scene_));
  }
  Scene scene_;
  std::unique_ptr<RayCaster> caster_;
};

}  // namespace

TEST_F(RayCasterTest, WallAtKnownDistance) {
  // From (16, 6, 5) looking +x: the wall along x = 20 has its face at 19.9.
  const RayHit h = caster_->cast({16.0f, 6.0f, 5.0f}, {1, 0, 0}, 60.0f);
  EXPECT_NEAR(h.range, 3.9f, 1e-4);
  EXPECT_EQ(h.label, kWall);
  EXPECT_NEAR(h.cos_incidence, 1.0f, 1e-5);
}

TEST_F(RayCasterTest, DoorLetsRaysThroughAndWindowOnlyAboveItsSill) {
  // Looking +y at the wall along y = 10 (faces at 9.9 and 10.1), the slab ends at y = 12.
  const RayHit in_door = caster_->cast({10.0f, 8.5f, 5.0f}, {0, 1, 0}, 60.0f);  // 1.0 m above L1
  EXPECT_LT(in_door.range, 0.0f) << "the ray should pass the door and leave the building";
  const RayHit above_door = caster_->cast({10.0f, 8.5f, 6.5f}, {0, 1, 0}, 60.0f);  // 2.5 m: above the door
  EXPECT_NEAR(above_door.range, 1.4f, 1e-4);
  EXPECT_EQ(above_door.label, kWall);
  const RayHit beside = caster_->cast({11.0f, 8.5f, 5.0f}, {0, 1, 0}, 60.0f);  // 0.5 m off the door's centre
  EXPECT_NEAR(beside.range, 1.4f, 1e-4);
  const RayHit under_window = caster_->cast({15.0f, 8.5f, 4.5f}, {0, 1, 0}, 60.0f);
  EXPECT_EQ(under_window.label, kWall);
  const RayHit through_window = caster_->cast({15.0f, 8.5f, 5.5f}, {0, 1, 0}, 60.0f);
  EXPECT_LT(through_window.range, 0.0f);
}

TEST_F(RayCasterTest, VoidShowsTheStoreyBelow) {
  // Straight down through the void: the lower hall's floor at z = 0, label floor.
  const RayHit down_void = caster_->cast({10.0f, 6.0f, 4.55f}, {0, 0, -1}, 60.0f);
  EXPECT_NEAR(down_void.range, 4.55f, 1e-4);
  EXPECT_EQ(down_void.label, kFloor);
  // Beside the void: the upper floor.
  const RayHit down_floor = caster_->cast({3.0f, 6.0f, 4.55f}, {0, 0, -1}, 60.0f);
  EXPECT_NEAR(down_floor.range, 0.55f, 1e-4);
  EXPECT_EQ(down_floor.label, kFloor);
  // From the lower hall, up: its ceiling (the upper slab seen from below) except under the
  // void, where the ray passes both storeys (the top storey's ceiling has the void too).
  const RayHit up = caster_->cast({3.0f, 6.0f, 0.55f}, {0, 0, 1}, 60.0f);
  EXPECT_NEAR(up.range, 3.25f, 1e-4);
  EXPECT_EQ(up.label, kCeiling);
  const RayHit up_void = caster_->cast({10.0f, 6.0f, 0.55f}, {0, 0, 1}, 60.0f);
  EXPECT_LT(up_void.range, 0.0f);
}

TEST_F(RayCasterTest, BarsLetSomeRaysThroughSolidRailingsNone) {
  // A fan of rays at 0.5 m above L1 from the void's centre toward each railing.
  int bars_hit = 0, solid_hit = 0;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    const float x = 7.3f + 5.4f * i / (n - 1);
    const RayHit south = caster_->cast({10.0f, 6.0f, 4.5f}, Eigen::Vector3f(x - 10.0f, -2.0f, 0.0f), 60.0f);
    const RayHit north = caster_->cast({10.0f, 6.0f, 4.5f}, Eigen::Vector3f(x - 10.0f, 2.0f, 0.0f), 60.0f);
    bars_hit += south.label == kRailing;
    solid_hit += north.label == kRailing;
  }
  EXPECT_EQ(solid_hit, n);
  // 3 cm posts every 12 cm: about a quarter of the rays (more at oblique incidence).
  EXPECT_GT(bars_hit, n / 8);
  EXPECT_LT(bars_hit, n / 2);
  // Above the railing's top everything passes.
  const RayHit above = caster_->cast({10.0f, 6.0f, 5.2f}, {0, -1, 0}, 60.0f);
  EXPECT_LT(above.range, 0.0f);
}

// A glass railing in front of a wall, at three transmissions: the share of rays that pass
// it and return from the wall behind is the transmission, and the result is the same on
// a second cast (the draw depends on the ray, not on a random state).
TEST(GlassRailing, LetsItsTransmissionThrough) {
  for (const double transmission : {0.0, 0.3, 0.8, 1.0}) {
    const std::string text = std::string(R"(name: glass
levels: [{name: L0, slab: [[0,0],[10,0],[10,10],[0,10]]}]
walls: [{level: L0, from: [0, 8], to: [10, 8]}]
railings: [{level: L0, from: [0, 5], to: [10, 5], height: 1.0, style: glass, transmission: )") +
                             std::to_string(transmission) + R"(}]
trajectory: {waypoints: [[2, 2], [8, 2]]}
)";
    const Scene scene = parse_scene(text, "glass.yaml", ".");
    const RayCaster caster(build_scene_mesh(scene));
    int glass = 0, wall = 0, same = 0;
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3f dir(-0.6f + 1.2f * i / (n - 1), 1.0f, -0.02f);
      const RayHit h = caster.cast({5.0f, 2.0f, 0.6f}, dir, 60.0f);
      glass += h.label == kRailing;
      wall += h.label == kWall;
      same += caster.cast({5.0f, 2.0f, 0.6f}, dir, 60.0f).range == h.range;
    }
    EXPECT_EQ(glass + wall, n) << transmission;
    EXPECT_NEAR(static_cast<double>(wall) / n, transmission, 0.05) << transmission;
    EXPECT_EQ(same, n);
  }
}

// A wall with a glazed window (0.9 to 2.1 m) and an open one: below the sills every ray
// returns from the wall; through the pane the share that passes (to nothing behind it) is the
// pane's transmission, the rest returns from the glass as wall; through the open window all pass.
TEST(GlassWindow, LetsItsTransmissionThroughAboveTheSill) {
  const Scene scene = parse_scene(R"(name: window
levels: [{name: L0, ceiling: 3.0, slab: [[0,0],[10,0],[10,10],[0,10]]}]
walls: [{level: L0, from: [0, 8], to: [10, 8], openings: [{at: 3, width: 2.0, height: 1.2, sill: 0.9, transmission: 0.6},
                                                           {at: 7, width: 2.0, height: 1.2, sill: 0.9}]}]
trajectory: {waypoints: [[2, 2], [8, 2]]}
)",
                                  "window.yaml", ".");
  const RayCaster caster(build_scene_mesh(scene));
  int glazed_passed = 0, open_passed = 0, sill_hit = 0;
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    const float dx = -0.15f + 0.3f * i / (n - 1);  // a fan onto the middle of each window
    glazed_passed += caster.cast({3.0f, 2.0f, 1.5f}, Eigen::Vector3f(dx, 1.0f, 0.0f), 60.0f).range < 0.0f;
    open_passed += caster.cast({7.0f, 2.0f, 1.5f}, Eigen::Vector3f(dx, 1.0f, 0.0f), 60.0f).range < 0.0f;
    const RayHit low = caster.cast({3.0f, 2.0f, 0.5f}, Eigen::Vector3f(dx, 1.0f, 0.0f), 60.0f);
    sill_hit += low.label == kWall && low.range > 0.0f;
  }
  EXPECT_NEAR(static_cast<double>(glazed_passed) / n, 0.6, 0.05);
  EXPECT_EQ(open_passed, n);
  EXPECT_EQ(sill_hit, n);
  // What the pane returns lies on the wall's centre line and is labelled wall.
  int on_pane = 0;
  for (int i = 0; i < n; ++i) {
    const float dx = -0.15f + 0.3f * i / (n - 1);
    const RayHit h = caster.cast({3.0f, 2.0f, 1.5f}, Eigen::Vector3f(dx, 1.0f, 0.0f), 60.0f);
    if (h.range < 0.0f) continue;
    EXPECT_EQ(h.label, kWall);
    on_pane += std::abs(h.range * 1.0f / std::sqrt(dx * dx + 1.0f) - 6.0f) < 1e-3f;
  }
  EXPECT_EQ(on_pane, n - glazed_passed);
}

TEST(SimulatedScan, RangesToAWallMatchTruthWithinNoise) {
  // One horizontal beam ring in a 20 m wide hall: the wall face at x = 9.9 is 4.9 m ahead.
  const Scene scene = parse_scene(R"(
sensor: {vertical_angles_deg: [0.0], columns: 3600, range_noise_std: 0.02, max_range: 60}
levels: [{name: L0, slab: [[-10,-10],[10,-10],[10,10],[-10,10]]}]
walls:
  - {level: L0, from: [10, -10], to: [10, 10]}
trajectory: {waypoints: [[5, 0], [6, 0]]}
)",
                                  "wall.yaml", ".");
  const Simulator sim(scene, 3);
  const Pose3 pose = make_pose({5.0, 0.0, 0.55}, 0.0);
  const PointCloud cloud = sim.scan_at(pose, 0);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f p = cloud.points[i];
    const double az = std::atan2(p.y(), p.x());
    if (std::abs(az) > 0.6) continue;  // only the wall ahead
    EXPECT_EQ(cloud.labels[i], kWall);
    const double truth = 4.9 / std::cos(az);
    const double err = p.norm() - truth;
    sum += err;
    sum2 += err * err;
    ++n;
  }
  ASSERT_GT(n, 500);
  const double mean = sum / n;
  const double stdev = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4 * 0.02 / std::sqrt(n));
  EXPECT_NEAR(stdev, 0.02, 0.002);
}

TEST(SimulatedScan, DropoutLosesTheConfiguredShare) {
  const std::string base = R"(
sensor: {vertical_angles_deg: [0.0], columns: 4000, dropout: DROP}
levels: [{name: L0, slab: [[-10,-10],[10,-10],[10,10],[-10,10]]}]
walls:
  - {level: L0, from: [10, -10], to: [10, 10]}
  - {level: L0, from: [10, 10], to: [-10, 10]}
  - {level: L0, from: [-10, 10], to: [-10, -10]}
  - {level: L0, from: [-10, -10], to: [10, -10]}
trajectory: {waypoints: [[0, 0], [1, 0]]}
)";
  auto with = [&](const std::string& d) {
    std::string t = base;
    t.replace(t.find("DROP"), 4, d);
    return parse_scene(t, "drop.yaml", ".");
  };
  const Pose3 pose = make_pose({0.0, 0.0, 0.55}, 0.0);
  const std::size_t all = Simulator(with("0.0"), 1).scan_at(pose, 0).size();
  EXPECT_EQ(all, 4000u);
  const std::size_t kept = Simulator(with("0.25"), 1).scan_at(pose, 0).size();
  EXPECT_NEAR(static_cast<double>(kept) / all, 0.75, 0.03);
}

TEST(SceneGeometry, JoinedWallsCloseTheirCorner) {
  const Scene scene = parse_scene(R"(levels: [{name: L0, slab: [[0,0],[10,0],[10,8],[0,8]]}]
walls:
  - {level: L0, from: [0, 0], to: [10, 0]}
  - {level: L0, from: [10, 0], to: [10, 8]}
trajectory: {waypoints: [[2, 2], [8, 2]]}
)",
                                  "corner.yaml", ".");
  const RayCaster caster(build_scene_mesh(scene));
  // Aim from outside at the outer corner square (10..10.1, -0.1..0): without the join the ray
  // would pass through the gap between the two walls' ends.
  const RayHit h = caster.cast({12.0f, -2.0f, 1.0f}, Eigen::Vector3f(-1.95f, 1.95f, 0.0f), 60.0f);
  EXPECT_EQ(h.label, kWall);
  // The pieces of a joined wall reach half its thickness past the joined end only.
  const std::vector<WallPiece> pieces = wall_pieces(scene.walls[0]);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_DOUBLE_EQ(pieces[0].s0, 0.0);
  EXPECT_DOUBLE_EQ(pieces[0].s1, 10.1);
}
