// GraphOptimizer on synthetic ground truth (graph_test_support.hpp); a straight corridor for the
// local problem's size.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graph_test_support.hpp"
#include "tsgraphs/graph/graph_optimizer.hpp"

using namespace tsgraphs;
using namespace tsgraphs::graph;
using namespace tsgraphs::graph::test;

TEST(GraphOptimizer, ScenarioDriftsAsIntended) {
  const Scenario s = corridor_loop(true);
  const double drift = end_error(s.graph, s.truth);
  const double yaw_drift =
      std::abs(wrap_angle(yaw_of(s.graph.keyframes().back().pose) - yaw_of(s.truth.back())));
  std::printf("odometry end drift %.3f m, %.2f deg\n", drift, yaw_drift / kDeg);
  EXPECT_GT(drift, 0.3);
  EXPECT_LT(drift, 1.0);
  EXPECT_GT(yaw_drift, 1.0 * kDeg);
  EXPECT_LT(yaw_drift, 4.0 * kDeg);
  int mapped = 0;
  for (int id : s.plane_of) mapped += id >= 0;
  EXPECT_EQ(mapped, 9);
}

TEST(GraphOptimizer, FullSolveWithPlanesRecoversTheTrajectoryAndWalls) {
  Scenario s = corridor_loop(true);
  const double rmse_odom = position_rmse(s.graph, s.truth);
  const PlaneErrors before = plane_errors(s);
  const Pose3 anchor = s.graph.keyframes()[0].pose;
  std::map<int, Plane> initial;
  for (const auto& [id, node] : s.graph.planes()) initial[id] = node.plane;

  GraphOptimizer optimizer;
  const OptimizationStats stats = optimizer.optimize(s.graph, true);
  const double rmse = position_rmse(s.graph, s.truth);
  const PlaneErrors after = plane_errors(s);
  std::printf(
      "odometry RMSE %.3f m -> %.4f m; planes %.2f deg / %.3f m -> %.3f deg / %.4f m; "
      "%d vars %d factors %d its %.1f ms\n",
      rmse_odom, rmse, before.max_angle_deg, before.max_distance, after.max_angle_deg, after.max_distance,
      stats.n_variables, stats.n_factors, stats.iterations, stats.wall_time_s * 1e3);

  EXPECT_LE(rmse, 0.25 * rmse_odom);
  EXPECT_LE(rmse, 0.05);
  EXPECT_LT(after.max_angle_deg, 0.35);
  EXPECT_LT(after.max_distance, 0.035);
  EXPECT_TRUE(same_bits(s.graph.keyframes()[0].pose, anchor));
  for (const auto& [id, node] : s.graph.planes()) {
    EXPECT_NEAR(node.plane.n.norm(), 1.0, 1e-12);
    EXPECT_GT(node.plane.n.dot(initial[id].n), 0.9);  // no sign flip
  }
  const int num_keyframes = int(s.graph.keyframes().size());
  EXPECT_EQ(stats.n_variables, num_keyframes - 1 + int(s.graph.planes().size()));
  EXPECT_EQ(stats.n_factors, int(s.graph.odometry_edges().size() + s.graph.plane_edges().size()));
  EXPECT_TRUE(stats.full);
  EXPECT_GT(stats.wall_time_s, 0.0);
  EXPECT_LT(stats.final_cost, stats.initial_cost);
}

TEST(GraphOptimizer, LoopEdgeAloneRemovesTheEndDrift) {
  Scenario s = corridor_loop(false);
  const int last = int(s.truth.size()) - 1;
  s.graph.add_loop_edge({0, last, s.truth[0].inverse() * s.truth[last], 0.01});
  const double drift = end_error(s.graph, s.truth);
  const double rmse_odom = position_rmse(s.graph, s.truth);
  GraphOptimizer().optimize(s.graph, true);
  const double corrected = end_error(s.graph, s.truth);
  std::printf("end drift %.3f m -> %.4f m; RMSE %.3f -> %.3f m\n", drift, corrected, rmse_odom,
              position_rmse(s.graph, s.truth));
  EXPECT_LT(corrected, 0.1 * drift);
  EXPECT_LT(position_rmse(s.graph, s.truth), rmse_odom);
}

TEST(GraphOptimizer, WrongLoopIsDownWeightedByHuber) {
  // A false loop: keyframe 75 claimed 5 m further along the corridor than it is from keyframe 15.
  constexpr int kFrom = 15, kTo = 75;
  constexpr double kLoopError = 5.0;
  const auto solve = [&](bool add_wrong_loop, double huber_loop) {
    Scenario s = corridor_loop(true);
    Pose3 wrong = s.truth[kFrom].inverse() * s.truth[kTo];
    wrong.translation().x() += kLoopError;
    if (add_wrong_loop) s.graph.add_loop_edge({kFrom, kTo, wrong, 0.01});
    GraphOptimizerConfig config;
    config.huber_loop = huber_loop;
    GraphOptimizer(config).optimize(s.graph, true);
    return position_rmse(s.graph, s.truth);
  };
  const double huber = GraphOptimizerConfig{}.huber_loop;
  const double clean = solve(false, huber);
  const double robust = solve(true, huber);
  constexpr double kNoRobustKernel = 1e6;  // the largest delta declared, none reached: least squares
  const double plain = solve(true, kNoRobustKernel);
  std::printf("RMSE without the wrong loop %.4f m; with it: Huber %.4f m, least squares %.4f m\n", clean,
              robust, plain);
  EXPECT_LE(robust, 0.05);
  EXPECT_LT(robust - clean, 0.005);
  EXPECT_GT(plain, 3.0 * robust);  // the scenario is one where the kernel matters
}

TEST(GraphOptimizer, LocalSolveMovesOnlyTheWindow) {
  Scenario s = corridor_loop(true);
  GraphOptimizer optimizer;
  optimizer.optimize(s.graph, true);
  // New keyframes arrive displaced (drift since the last solve).
  const int n = int(s.graph.keyframes().size());
  const int window = optimizer.config().local_window;
  const Eigen::Vector3d kDisplacement(0.3, -0.2, 0.0);
  for (int k = n - window; k < n; ++k) s.graph.keyframes()[k].pose.translation() += kDisplacement;
  const SituationalGraph before = s.graph;

  const OptimizationStats stats = optimizer.optimize(s.graph, false);
  EXPECT_FALSE(stats.full);
  int window_planes = 0;
  std::set<int> seen;
  for (const PlaneEdge& e : before.plane_edges())
    if (e.keyframe >= n - window) seen.insert(e.plane);
  window_planes = int(seen.size());
  EXPECT_EQ(stats.n_variables, window + window_planes);

  for (int k = 0; k < n - window; ++k)
    EXPECT_TRUE(same_bits(s.graph.keyframes()[k].pose, before.keyframes()[k].pose)) << k;
  double worst = 0.0;
  for (int k = n - window; k < n; ++k) {
    EXPECT_FALSE(same_bits(s.graph.keyframes()[k].pose, before.keyframes()[k].pose)) << k;
    worst = std::max(worst, (s.graph.keyframes()[k].pose.translation() - s.truth[k].translation()).norm());
  }
  std::printf("window keyframes displaced %.2f m -> worst error %.4f m\n", kDisplacement.norm(), worst);
  EXPECT_LT(worst, 0.05);
  for (const auto& [id, node] : s.graph.planes()) {
    if (seen.count(id)) continue;
    EXPECT_TRUE(same_bits(node.plane, before.planes().at(id).plane)) << id;
  }
}

namespace {

// A straight corridor of `n` keyframes 1 m apart, its walls in 10 m segments (one plane each).
SituationalGraph straight_corridor(int n) {
  constexpr double kSegment = 10.0;
  SituationalGraph g;
  std::map<std::pair<int, int>, int> plane_of;  // (segment, side) -> plane id
  for (int k = 0; k < n; ++k) {
    KeyframeNode node;
    node.pose = make_pose({double(k), 0.0, 0.0}, 0.0);
    node.odom = node.pose;
    g.add_keyframe(node);
    if (k > 0) g.add_odometry_edge({k - 1, k, make_pose({1.0, 0.0, 0.0}, 0.0)});
    const int segment = int(std::floor(k / kSegment));
    for (int side : {-1, 1}) {
      const Plane wall = Plane::from_point_normal({0.0, side * kHalfWidth, 0.0}, {0.0, -double(side), 0.0});
      auto [it, inserted] = plane_of.try_emplace({segment, side}, -1);
      if (inserted) it->second = g.add_plane(wall, true);
      g.add_plane_edge({k, it->second, wall.transformed(node.pose.inverse()), 100});
    }
  }
  return g;
}

}  // namespace

TEST(GraphOptimizer, LocalProblemSizeDoesNotGrowWithTheRun) {
  GraphOptimizer optimizer;
  SituationalGraph small = straight_corridor(55), large = straight_corridor(505);
  const OptimizationStats a = optimizer.optimize(small, false);
  const OptimizationStats b = optimizer.optimize(large, false);
  // Window 45..54: 10 keyframes, the 4 wall segments they see; 10 odometry factors touch it, and
  // the segments are seen by 40..54 (15 keyframes x 2 sides).
  EXPECT_EQ(a.n_variables, 10 + 4);
  EXPECT_EQ(a.n_factors, 10 + 30);
  EXPECT_EQ(b.n_variables, a.n_variables);
  EXPECT_EQ(b.n_factors, a.n_factors);
  const OptimizationStats full = optimizer.optimize(large, true);
  EXPECT_GT(full.n_factors, 20 * a.n_factors);
}

TEST(GraphOptimizer, SameInputGivesBitIdenticalOutput) {
  Scenario a = corridor_loop(true), b = corridor_loop(true);
  a.graph.add_loop_edge({3, 63, a.truth[3].inverse() * a.truth[63], 0.01});
  b.graph.add_loop_edge({3, 63, b.truth[3].inverse() * b.truth[63], 0.01});
  GraphOptimizer optimizer;
  for (bool full : {true, false}) {
    const OptimizationStats sa = optimizer.optimize(a.graph, full);
    const OptimizationStats sb = optimizer.optimize(b.graph, full);
    EXPECT_EQ(sa.iterations, sb.iterations);
    EXPECT_EQ(sa.final_cost, sb.final_cost);
  }
  for (std::size_t k = 0; k < a.graph.keyframes().size(); ++k)
    EXPECT_TRUE(same_bits(a.graph.keyframes()[k].pose, b.graph.keyframes()[k].pose)) << k;
  for (const auto& [id, node] : a.graph.planes())
    EXPECT_TRUE(same_bits(node.plane, b.graph.planes().at(id).plane)) << id;
}

TEST(GraphOptimizer, EverySolverBackEndAgrees) {
  const std::vector<std::pair<std::string, std::string>> back_ends = {
      {"sparse_normal_cholesky", "suite_sparse"},
      {"sparse_normal_cholesky", "cx_sparse"},
      {"sparse_normal_cholesky", "eigen_sparse"},
      {"sparse_schur", "suite_sparse"},
      {"dense_schur", "suite_sparse"},
      {"iterative_schur", "suite_sparse"}};
  for (const auto& [solver, library] : back_ends) {
    Scenario s = corridor_loop(true);
    GraphOptimizerConfig config;
    config.linear_solver = *kLinearSolvers.parse(solver);
    config.sparse_library = *kSparseLibraries.parse(library);
    GraphOptimizer(config).optimize(s.graph, true);
    EXPECT_LT(position_rmse(s.graph, s.truth), 0.05) << solver << " " << library;
  }
}

TEST(GraphOptimizer, RejectsBadConfigAndGraphs) {
  GraphOptimizerConfig config;
  config.linear_solver = static_cast<LinearSolver>(99);  // no enumerator: Ceres knows no such solver
  EXPECT_THROW(GraphOptimizer{config}, std::invalid_argument);
  config = {};
  config.sparse_library = SparseLibrary::accelerate_sparse;  // Apple's: not in Debian's Ceres
  EXPECT_THROW(GraphOptimizer{config}, std::invalid_argument);
  config = {};
  config.local_window = 0;
  EXPECT_THROW(GraphOptimizer{config}, std::invalid_argument);

  GraphOptimizer optimizer;
  SituationalGraph empty;
  EXPECT_THROW(optimizer.optimize(empty, true), std::invalid_argument);
  SituationalGraph single;
  single.add_keyframe({});
  const OptimizationStats stats = optimizer.optimize(single, true);
  EXPECT_EQ(stats.n_variables, 0);
  EXPECT_EQ(stats.n_factors, 0);
  SituationalGraph dangling = straight_corridor(3);
  dangling.add_loop_edge({0, 7, Pose3::Identity(), 0.0});
  EXPECT_THROW(optimizer.optimize(dangling, true), std::invalid_argument);
}
