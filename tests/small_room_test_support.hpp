#pragma once
/// The command-line tests' small room: one room walked once round, a few hundred VLP-16
/// scans, quick to simulate and run. Each test file simulates it once and copies what a test
/// damages.
#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"

namespace tsgraphs::test {

inline const char* kSmallRoomScene = R"(
name: small_room
seed: 5
sensor: {preset: vlp-16, mount_height: 0.55}
odometry: {trans_noise_per_m: 0.01, yaw_noise_per_rad: 0.01, yaw_noise_per_m: 0.002}
levels:
  - {name: L0, elevation: 0.0, ceiling: 2.8, slab: [[0, 0], [8, 0], [8, 6], [0, 6]]}
walls:
  - {level: L0, from: [-0.1, 0], to: [8.1, 0]}
  - {level: L0, from: [-0.1, 6], to: [8.1, 6]}
  - {level: L0, from: [0, 0], to: [0, 6]}
  - {level: L0, from: [8, 0], to: [8, 6]}
  - {level: L0, from: [4, 0], to: [4, 2.5]}
trajectory:
  level: L0
  speed: 1.0
  laps: 1
  waypoints: [[1.5, 1.5], [6.5, 1.5], [6.5, 4.5], [1.5, 4.5]]
)";

/// Writes the small room to `dir`/room.yaml and simulates it into `dir`/seq; false (and the
/// command's stderr in `err`) when that failed.
inline bool simulate_small_room(const std::filesystem::path& dir, std::string* err) {
  std::ofstream(dir / "room.yaml") << kSmallRoomScene;
  return cli("-q simulate " + (dir / "room.yaml").string() + " --out " + (dir / "seq").string(), err) == 0;
}

}  // namespace tsgraphs::test
