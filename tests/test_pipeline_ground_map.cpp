// The global traversable node map as the pipeline builds it: revisits fuse (10 laps keep the
// node count of 2 laps), and the nodes cover the floor that was walked.
// ctest: slow (seconds a test: simulated runs or generated buildings)
#include <gtest/gtest.h>

#include "tsgraphs/pipeline/pipeline.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

namespace {

// A 10 m x 6 m room with a partition, walked round a loop of about 19 m.
scene::Scene room(int laps) {
  scene::Scene scene = scene::parse_scene(R"(
name: small_room
sensor: {preset: os1-64, mount_height: 0.55}
odometry: {trans_noise_per_m: 0.01, yaw_noise_per_rad: 0.01, yaw_noise_per_m: 0.002}
levels:
  - {name: L0, elevation: 0.0, ceiling: 2.8, slab: [[0, 0], [10, 0], [10, 6], [0, 6]]}
walls:
  - {level: L0, from: [-0.1, 0], to: [10.1, 0]}
  - {level: L0, from: [-0.1, 6], to: [10.1, 6]}
  - {level: L0, from: [0, 0], to: [0, 6]}
  - {level: L0, from: [10, 0], to: [10, 6]}
  - {level: L0, from: [5, 0], to: [5, 2.5]}
trajectory:
  level: L0
  speed: 1.5
  waypoints: [[1.5, 1.5], [8.5, 1.5], [8.5, 4.5], [1.5, 4.5]]
)",
                                          "small_room.yaml", ".");
  scene.trajectory.laps = laps;
  return scene;
}

std::size_t node_count_after(int laps) {
  sim::Simulator sim(room(laps), 7);
  pipeline::Pipeline slam;
  for (std::size_t k = 0; k < sim.num_scans(); ++k)
    slam.process(k, sim.times()[k], sim.scan(k), sim.odometry_poses()[k]);
  slam.finish();
  return slam.node_map().size();
}

}  // namespace

TEST(PipelineGroundMap, TenLapsKeepTheNodeCountOfTwo) {
  const std::size_t two = node_count_after(2), ten = node_count_after(10);
  std::printf("traversable nodes: %zu after 2 laps, %zu after 10\n", two, ten);
  // The room's floor is 60 m^2 less walls: at 0.25 m cells there are at most ~960 nodes.
  EXPECT_GT(two, 400u);
  EXPECT_LE(static_cast<double>(ten), 1.10 * static_cast<double>(two));
  EXPECT_GE(static_cast<double>(ten), 0.90 * static_cast<double>(two));
}
