#pragma once
// A constructed run shared by the report tests: two levels, rooms, walls, nodes, true rooms,
// trajectories, scan times and solves.
#include <string>

#include <Eigen/Core>

#include "tsgraphs/report/run_view.hpp"

namespace tsgraphs::test {

using report::RunView;

/// A 3 x 2 m room or corridor at `center` (yaw 0.1) with two free-space points on its level's floor.
inline RunView::Room room(int id, const std::string& kind, int level, const Vec2& center, int first_lap) {
  RunView::Room r;
  r.id = id;
  r.kind = kind;
  r.level = level;
  r.rect.center = center;
  r.rect.size = Vec2(3.0, 2.0);
  r.rect.yaw = 0.1;
  r.first_lap = first_lap;
  const double z = level == 0 ? 0.0 : 3.0;
  r.free_space = {Eigen::Vector3d(center.x(), center.y(), z),
                  Eigen::Vector3d(center.x() + 1.0, center.y(), z)};
  return r;
}

/// Level 0 (floor 0): 3 walls, 4 nodes, 2 rooms and a corridor, 2 true rooms. Level 1 (floor
/// 3): 1 wall, 2 nodes, 1 room, 1 true room. The trajectory walks level 0, then level 1.
inline RunView two_level_run() {
  RunView run;
  run.label = "TS-graphs & <co>";
  run.levels = {0.0, 3.0};
  run.walls = {{1, {0, 0}, {9, 0}, 0.0, 2.8},
               {2, {0, 0}, {0, 7}, 0.05, 2.9},
               {4, {9, 0}, {9, 7}, -0.1, 2.5},
               {7, {1, 1}, {1, 6}, 3.0, 5.5}};
  for (int i = 0; i < 4; ++i) run.nodes.push_back({Eigen::Vector3d(1.0 + i, 1.0, 0.02)});
  for (int i = 0; i < 2; ++i) run.nodes.push_back({Eigen::Vector3d(2.0 + i, 6.0, 3.01)});
  run.rooms = {room(0, "room", 0, {2, 2}, 1), room(1, "corridor", 0, {6, 2}, 2),
               room(2, "room", 0, {2, 6}, 0), room(7, "room", 1, {7, 6}, 1)};
  run.truth_rooms = {{"hall & <1>", "ground", {{0, 0}, {5, 0}, {5, 4}, {0, 4}}, 0.0},
                     {"office", "ground", {{5, 0}, {9, 0}, {9, 4}, {5, 4}}, 0.0},
                     {"loft", "upper", {{0, 4}, {9, 4}, {9, 8}, {0, 8}}, 3.0}};
  for (int i = 0; i <= 20; ++i) run.estimated.push_back({0.1 * i, Eigen::Vector3d(1.0 + 0.4 * i, 1.0, 0.55)});
  for (int i = 0; i <= 10; ++i)
    run.estimated.push_back({2.1 + 0.1 * i, Eigen::Vector3d(8.0 - 0.5 * i, 6.0, 3.55)});
  for (const RunView::Stamped& s : run.estimated)
    run.truth.push_back({s.t, s.p + Eigen::Vector3d(0.0, 0.05, 0.0)});
  for (int i = 0; i < 32; ++i) run.scans.push_back({0.1 * i, 10.0 + (i % 5)});
  run.solves = {{0.5, 0.002, false}, {1.5, 0.004, false}, {2.5, 0.020, true}};
  return run;
}

}  // namespace tsgraphs::test
