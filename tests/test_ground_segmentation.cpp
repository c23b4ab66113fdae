// The traversable ground of one scan against simulated ground truth and on real returns:
// point precision and recall on the office and the atrium; nothing traversable in the atrium's
// void or on the storey below; the bench top below the void is not ground; the two_storeys ramp
// is; a far wall's foot is no ground; on two real HDL-32e scans the ground is one connected
// region lying on its local plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/core/pose.hpp"
#include <Eigen/Cholesky>
#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;
using ground::GroundConfig;
using ground::GroundLabel;
using ground::GroundScan;

namespace {

constexpr std::size_t kScanStep = 25;  // every 25th scan of the 2-lap path
constexpr double kEvalRange = 15.0;    // points within this (horizontal) range are scored (m)
constexpr double kOtherStorey =
    1.0;  // a floor more than this below or above the sensor's is another storey's (m)
constexpr double kVoidEdgeNoise =
    0.05;  // range noise carries floor points at the void's edge a few cm over it (m)
constexpr double kMinPrecision = 0.97;
constexpr double kMinRecall = 0.95;
constexpr std::uint32_t kFloor = static_cast<std::uint32_t>(PointLabel::kFloor);
constexpr std::uint32_t kRamp = static_cast<std::uint32_t>(PointLabel::kRamp);
constexpr std::uint32_t kBox = static_cast<std::uint32_t>(PointLabel::kBox);

scene::Scene builtin(const std::string& name) {
  return scene::parse_scene(*scene::builtin_scene_text(name), "builtin:" + name, ".");
}

int level_index(const scene::Scene& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.levels.size(); ++i)
    if (scene.levels[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no level " << name;
  return 0;
}

// A segmented scan with what is needed to score it in the world.
struct Segmented {
  PointCloud cloud;
  Pose3 pose;  // world <- sensor
  GroundScan result;
  double floor_z = 0;  // world height of the floor under the sensor

  Eigen::Vector3d node_world(const ground::GroundNode& node) const {
    return pose * (result.R_level_sensor.transpose() * node.centre.cast<double>());
  }
};

Segmented segment(const sim::Simulator& sim, std::size_t k, const GroundConfig& config) {
  Segmented s;
  s.cloud = sim.scan(k);
  s.pose = sim.true_poses()[k];
  s.floor_z = s.pose.translation().z() - sim.scene().sensor.mount_height;
  s.result = ground::segment_ground(s.cloud, s.pose.linear(), config);
  return s;
}

std::vector<Segmented> segment_path(const sim::Simulator& sim, const GroundConfig& config, std::size_t step) {
  std::vector<Segmented> out;
  for (std::size_t k = 0; k < sim.num_scans(); k += step) out.push_back(segment(sim, k, config));
  return out;
}

struct Score {
  std::size_t true_positive = 0, false_positive = 0, false_negative = 0;
  double precision() const {
    return static_cast<double>(true_positive) / std::max<std::size_t>(1, true_positive + false_positive);
  }
  double recall() const {
    return static_cast<double>(true_positive) / std::max<std::size_t>(1, true_positive + false_negative);
  }
};

// Ground truth: floor and ramp points of the sensor's own storey, within kEvalRange.
Score score(const std::vector<Segmented>& scans) {
  Score sc;
  for (const Segmented& s : scans) {
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
      const Eigen::Vector3f& p = s.cloud.points[i];
      if (!p.allFinite() || p.head<2>().norm() > kEvalRange) continue;
      const double world_z = (s.pose * p.cast<double>()).z();
      const std::uint32_t label = s.cloud.labels[i];
      const bool truth = (label == kFloor || label == kRamp) && std::abs(world_z - s.floor_z) <= kOtherStorey;
      const bool predicted = s.result.labels[i] == GroundLabel::kGround;
      if (truth && predicted) ++sc.true_positive;
      if (!truth && predicted) ++sc.false_positive;
      if (truth && !predicted) ++sc.false_negative;
    }
  }
  return sc;
}

// (scene, sensor preset): the scene's own os1-64, and the office seen by a 16-beam sensor.
class SimulatedGround : public ::testing::TestWithParam<std::pair<std::string, std::string>> {};

TEST_P(SimulatedGround, PrecisionAndRecallOfGroundPoints) {
  const auto& [name, preset] = GetParam();
  scene::Scene scene = builtin(name);
  if (scene.sensor.preset != preset) {
    scene::SensorSpec sensor;
    ASSERT_TRUE(scene::apply_preset(preset, &sensor));
    sensor.mount_height = scene.sensor.mount_height;
    scene.sensor = sensor;
  }
  const sim::Simulator sim(scene, 1);
  const GroundConfig config = ground::per_sensor_preset(preset);
  const std::vector<Segmented> scans = segment_path(sim, config, kScanStep);
  const Score sc = score(scans);
  std::printf("%s (%s): %zu scans, ground precision %.4f recall %.4f (tp %zu fp %zu fn %zu)\n", name.c_str(),
              preset.c_str(), scans.size(), sc.precision(), sc.recall(), sc.true_positive, sc.false_positive,
              sc.false_negative);
  EXPECT_GE(sc.precision(), kMinPrecision);
  EXPECT_GE(sc.recall(), kMinRecall);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SimulatedGround,
                         ::testing::Values(std::make_pair(std::string("office"), std::string("os1-64")),
                                           std::make_pair(std::string("atrium"), std::string("os1-64")),
                                           std::make_pair(std::string("office"), std::string("vlp-16"))));

// The atrium from its L1 ring: nothing traversable over the void (the railings bound the
// ground), and no ground point on the storey below seen through it.
TEST(AtriumGround, VoidAndStoreyBelowAreNeverGround) {
  const sim::Simulator sim(builtin("atrium"), 2);
  const scene::Scene& scene = sim.scene();
  const scene::Level& l1 = scene.levels[level_index(scene, "L1")];
  ASSERT_FALSE(l1.voids.empty());
  const GroundConfig config = ground::per_sensor_preset(scene.sensor.preset);
  std::size_t scans = 0, nodes_in_void = 0, traversable = 0, below = 0;
  for (std::size_t k = 0; k < sim.num_scans(); k += kScanStep, ++scans) {
    const Segmented s = segment(sim, k, config);
    for (const ground::GroundNode& node : s.result.nodes) {
      if (!node.traversable) continue;
      ++traversable;
      const Eigen::Vector3d w = s.node_world(node);
      for (const Polygon2& v : l1.voids) {
        if (!contains(v, w.head<2>())) continue;
        double depth = std::numeric_limits<double>::infinity();
        for (std::size_t e = 0; e < v.size(); ++e)
          depth = std::min(depth, distance_to_segment(w.head<2>(), v[e], v[(e + 1) % v.size()]));
        if (depth > kVoidEdgeNoise) ++nodes_in_void;
      }
    }
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
      if (s.result.labels[i] != GroundLabel::kGround) continue;
      if ((s.pose * s.cloud.points[i].cast<double>()).z() < s.floor_z - kOtherStorey) ++below;
    }
  }
  std::printf(
      "atrium: %zu scans, %zu traversable nodes, %zu in the void, %zu ground points on the storey below\n",
      scans, traversable, nodes_in_void, below);
  EXPECT_GT(traversable, scans * 100);
  EXPECT_EQ(nodes_in_void, 0u);
  EXPECT_EQ(below, 0u);
}

// The atrium's 0.45 m bench seen from L0 around it (its top is just below the sensor, so the
// scans see it well): no ground point on it, no traversable node over it at its height.
TEST(AtriumGround, BenchTopIsNotGround) {
  const sim::Simulator sim(builtin("atrium"), 3);
  const scene::Scene& scene = sim.scene();
  const int l0 = level_index(scene, "L0");
  const scene::Box* bench = nullptr;
  for (const scene::Box& b : scene.boxes)
    if (b.label == "bench") bench = &b;
  ASSERT_NE(bench, nullptr);
  const double base = scene.levels[l0].elevation;
  const double top = base + bench->max.z();
  constexpr double kMargin = 0.05;  // around the bench's box (m)
  auto on_bench = [&](const Eigen::Vector3d& w, double z_lo, double z_hi) {
    return w.x() >= bench->min.x() - kMargin && w.x() <= bench->max.x() + kMargin &&
           w.y() >= bench->min.y() - kMargin && w.y() <= bench->max.y() + kMargin && w.z() >= z_lo &&
           w.z() <= z_hi;
  };
  const GroundConfig config = ground::per_sensor_preset(scene.sensor.preset);
  const std::vector<Eigen::Vector2d> stands = {
      {11.0, 12.0}, {14.0, 10.6}, {17.0, 12.0}, {14.0, 13.4}, {12.0, 10.5}};
  std::size_t bench_points = 0, bench_ground = 0, bench_nodes = 0, floor_ground = 0;
  for (std::size_t k = 0; k < stands.size(); ++k) {
    const Pose3 pose = make_pose({stands[k].x(), stands[k].y(), base + scene.sensor.mount_height}, 0.7 * k);
    const PointCloud cloud = sim.scan_at(pose, k);
    const GroundScan result = ground::segment_ground(cloud, pose.linear(), config);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const Eigen::Vector3d w = pose * cloud.points[i].cast<double>();
      const bool ground = result.labels[i] == GroundLabel::kGround;
      if (cloud.labels[i] == kBox && on_bench(w, base, top + kMargin)) {
        ++bench_points;
        bench_ground += ground ? 1 : 0;
      }
      if (cloud.labels[i] == kFloor && ground) ++floor_ground;
    }
    for (const ground::GroundNode& node : result.nodes) {
      if (!node.traversable) continue;
      const Eigen::Vector3d w = pose * (result.R_level_sensor.transpose() * node.centre.cast<double>());
      if (on_bench(w, top - 0.2, top + 0.2)) ++bench_nodes;
    }
  }
  std::printf(
      "bench: %zu points on it, %zu of them ground; %zu traversable nodes on top; %zu floor points ground\n",
      bench_points, bench_ground, bench_nodes, floor_ground);
  EXPECT_GT(bench_points, 1000u);
  EXPECT_GT(floor_ground, 10000u);
  EXPECT_EQ(bench_ground, 0u);
  EXPECT_EQ(bench_nodes, 0u);
}

// two_storeys: from scans on the ramp and near it, the ramp (1:8, 7 degrees) is ground.
TEST(TwoStoreysGround, RampIsTraversable) {
  const sim::Simulator sim(builtin("two_storeys"), 4);
  const scene::Scene& scene = sim.scene();
  ASSERT_EQ(scene.ramps.size(), 1u);
  const Polygon2& ramp = scene.ramps[0].polygon;
  constexpr double kNear = 2.0;  // scans within this of the ramp's footprint (m)
  auto near_ramp = [&](const Eigen::Vector2d& xy) {
    if (contains(ramp, xy)) return true;
    for (std::size_t i = 0; i < ramp.size(); ++i)
      if (distance_to_segment(xy, ramp[i], ramp[(i + 1) % ramp.size()]) <= kNear) return true;
    return false;
  };
  const GroundConfig config = ground::per_sensor_preset(scene.sensor.preset);
  constexpr std::size_t kRampStep = 10;
  std::size_t scans = 0, ramp_points = 0, ramp_ground = 0;
  std::size_t last = 0;
  for (std::size_t k = 0; k < sim.num_scans(); ++k) {
    if (!near_ramp(sim.true_poses()[k].translation().head<2>())) continue;
    if (scans > 0 && k < last + kRampStep) continue;
    last = k;
    ++scans;
    const Segmented s = segment(sim, k, config);
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
      if (s.cloud.labels[i] != kRamp || s.cloud.points[i].head<2>().norm() > kEvalRange) continue;
      ++ramp_points;
      ramp_ground += s.result.labels[i] == GroundLabel::kGround ? 1 : 0;
    }
  }
  const double fraction = static_cast<double>(ramp_ground) / std::max<std::size_t>(1, ramp_points);
  std::printf("ramp: %zu scans, %zu ramp points, %.4f of them ground\n", scans, ramp_points, fraction);
  EXPECT_GT(scans, 10u);
  EXPECT_GE(fraction, 0.9);
}

}  // namespace

// Real HDL-32e returns of a campus walkway (tests/data/hdl32_pair). The sensor stands about
// 1.7 m above the ground: the densest height band of the returns between 3 m and 10 m is
// 1.65 to 1.75 m below it. In each scan the traversable nodes form one connected region
// (nodes within max_gap of each other are linked, as the search links them) and no ground
// point is more than 0.3 m above the plane fitted to the ground points around it.
// A vlp-16's rings meet a wall 10 m away 0.35 m apart (10 m x tan 2 degrees): the ring above a
// wall's foot is higher than foot_height, so the foot is found only by reaching foot_rings up.
TEST(WallFoot, AFarWallsFootIsAnObstacleThoughTheNextRingIsAboveFootHeight) {
  constexpr double kHeight = 0.55, kWallX = 10.2, kRingGap = 0.35, kFootAbove = 0.03;
  PointCloud cloud;
  for (double x = 1.3; x < kWallX - 0.03; x += 0.04)
    for (double y = -2.0; y <= 2.0; y += 0.04) cloud.points.emplace_back(x, y, -kHeight);
  std::size_t first_foot = cloud.size();
  for (double y = -2.0; y <= 2.0; y += 0.04) cloud.points.emplace_back(kWallX, y, -kHeight + kFootAbove);
  const std::size_t end_foot = cloud.size();
  for (double z = -kHeight + kFootAbove + kRingGap; z < 2.0; z += kRingGap)
    for (double y = -2.0; y <= 2.0; y += 0.04) cloud.points.emplace_back(kWallX, y, z);
  GroundConfig config = ground::per_sensor_preset("vlp-16");
  config.sensor_height = kHeight;
  const auto foot_ground = [&](const GroundConfig& c) {
    const GroundScan scan = ground::segment_ground(cloud, Eigen::Matrix3d::Identity(), c);
    int n = 0;
    for (std::size_t i = first_foot; i < end_foot; ++i) n += scan.labels[i] == GroundLabel::kGround;
    int floor = 0;
    for (std::size_t i = 0; i < first_foot; ++i) floor += scan.labels[i] == GroundLabel::kGround;
    EXPECT_GT(floor, 0.95 * first_foot);  // the floor up to the wall stays ground
    return n;
  };
  EXPECT_EQ(foot_ground(config), 0);
  GroundConfig one_window = config;
  one_window.foot_rings = 0.0;  // foot_height alone
  EXPECT_GT(foot_ground(one_window), static_cast<int>(0.9 * (end_foot - first_foot)));
}

TEST(RealGround, Hdl32ScansGiveOneRegionOnItsLocalPlane) {
  constexpr double kSensorHeight = 1.7;   // m, from the data (see above)
  constexpr double kMaxAbovePlane = 0.3;  // m
  constexpr double kLocalCell = 1.0;  // local planes: ground points of the 3 x 3 cells of this size around
  constexpr std::size_t kMinGroundPoints =
      10000;  // of about 14,000 returns within 0.3 m of the walkway's best-fit plane inside 15 m
  GroundConfig config = ground::per_sensor_preset("");
  config.sensor_height = kSensorHeight;
  config.seed_radius = 5.0;  // the lowest beam (-30.7 degrees) meets the ground 2.9 m away
  for (const char* name : {"251370668.pcd", "251371071.pcd"}) {
    const PointCloud cloud = io::read_pcd(std::string(TSGRAPHS_TEST_DATA_DIR) + "/hdl32_pair/" + name);
    const GroundScan result = ground::segment_ground(cloud, Eigen::Matrix3d::Identity(), config);

    // Connectivity of the traversable nodes.
    std::vector<Eigen::Vector2f> nodes;
    for (const ground::GroundNode& n : result.nodes)
      if (n.traversable) nodes.push_back(n.centre.head<2>());
    std::vector<int> component(nodes.size(), -1);
    int components = 0;
    for (std::size_t s = 0; s < nodes.size(); ++s) {
      if (component[s] >= 0) continue;
      std::vector<std::size_t> stack{s};
      component[s] = components;
      while (!stack.empty()) {
        const std::size_t a = stack.back();
        stack.pop_back();
        for (std::size_t b = 0; b < nodes.size(); ++b) {
          if (component[b] >= 0 || (nodes[a] - nodes[b]).norm() > config.max_gap) continue;
          component[b] = components;
          stack.push_back(b);
        }
      }
      ++components;
    }

    // Local planes z = a x + b y + c of the ground points, per cell, from the 3 x 3 cells around.
    std::map<std::pair<int, int>, std::vector<Eigen::Vector3d>> cells;
    std::size_t ground_points = 0;
    auto cell_of = [&](const Eigen::Vector3f& p) {
      return std::make_pair(static_cast<int>(std::floor(p.x() / kLocalCell)),
                            static_cast<int>(std::floor(p.y() / kLocalCell)));
    };
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (result.labels[i] != GroundLabel::kGround) continue;
      ++ground_points;
      const Eigen::Vector3f p = (result.R_level_sensor.cast<float>() * cloud.points[i]);
      cells[cell_of(p)].push_back(p.cast<double>());
    }
    double worst = 0.0;
    for (const auto& [key, pts] : cells) {
      Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
      Eigen::Vector3d b = Eigen::Vector3d::Zero();
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          auto it = cells.find({key.first + dx, key.second + dy});
          if (it == cells.end()) continue;
          for (const Eigen::Vector3d& q : it->second) {
            const Eigen::Vector3d row(q.x(), q.y(), 1.0);
            A += row * row.transpose();
            b += row * q.z();
          }
        }
      }
      const Eigen::Vector3d abc = A.ldlt().solve(b);
      for (const Eigen::Vector3d& q : pts)
        worst = std::max(worst, q.z() - (abc.x() * q.x() + abc.y() * q.y() + abc.z()));
    }
    std::printf(
        "%s: %zu points, %zu ground, %zu traversable nodes in %d region(s), highest ground point %.3f m "
        "above its local plane\n",
        name, cloud.size(), ground_points, nodes.size(), components, worst);
    EXPECT_GT(ground_points, kMinGroundPoints);
    EXPECT_EQ(components, 1);
    EXPECT_LE(worst, kMaxAbovePlane);
  }
}
