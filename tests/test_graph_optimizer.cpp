// GraphOptimizer on synthetic ground truth: a square corridor loop driven twice with drifting
// odometry, its walls and floor seen with small noise; a straight corridor for the local
// problem's size.
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

#include "tsgraphs/graph/graph_optimizer.hpp"

using namespace tsgraphs;
using namespace tsgraphs::graph;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kLoopWidth = 20.0, kLoopHeight = 10.0;  // centre line of the corridor loop (m)
constexpr double kLap = 2.0 * (kLoopWidth + kLoopHeight);
constexpr int kLaps = 2;
constexpr double kHalfWidth = 1.5;  // corridor half width (m)
// A keyframe sees the wall faces in front of it nearer than this (m): far enough to see the end
// of its corridor, short of the 11.5 m across the inner block (that would see through it).
constexpr double kWallRange = 10.0;
constexpr double kOdomSigmaTrans = 0.02, kOdomSigmaYawDeg = 0.2;  // per 1 m step
constexpr double kPlaneNoiseDeg = 0.2, kPlaneNoiseDist = 0.01;
constexpr unsigned kSeed = 2;  // its odometry ends 0.50 m and 3.1 deg off

constexpr double kSensorHeight = 0.5;  // above the floor (m)

struct Surface {
  Plane plane;           ///< map frame, normal towards the corridor
  bool vertical = true;  ///< a wall; false: the floor, seen from everywhere
  Eigen::Vector2d from = Eigen::Vector2d::Zero(),
                  to = Eigen::Vector2d::Zero();  ///< a wall's extent
};

struct Scenario {
  std::vector<Pose3> truth;
  std::vector<Surface> surfaces;
  std::vector<int> plane_of;  ///< graph plane id of each surface, -1 if never seen
  SituationalGraph graph;
};

// Pose at arc length s on the rectangle (anticlockwise from the origin, heading along it).
Pose3 loop_pose(double s) {
  s = std::fmod(s, kLap);
  if (s < kLoopWidth) return make_pose({s, 0, 0}, 0.0);
  s -= kLoopWidth;
  if (s < kLoopHeight) return make_pose({kLoopWidth, s, 0}, M_PI / 2);
  s -= kLoopHeight;
  if (s < kLoopWidth) return make_pose({kLoopWidth - s, kLoopHeight, 0}, M_PI);
  s -= kLoopWidth;
  return make_pose({0, kLoopHeight - s, 0}, -M_PI / 2);
}

Surface wall(Eigen::Vector2d from, Eigen::Vector2d to, Eigen::Vector2d normal) {
  const Eigen::Vector3d n(normal.x(), normal.y(), 0.0);
  return {Plane::from_point_normal(Eigen::Vector3d(from.x(), from.y(), 0.0), n), true, from, to};
}

// The floor, then the outer and inner wall faces of the corridor round the rectangle.
std::vector<Surface> loop_surfaces() {
  const double h = kHalfWidth, W = kLoopWidth, H = kLoopHeight;
  Surface floor;
  floor.plane = Plane::from_point_normal({0, 0, -kSensorHeight}, {0, 0, 1});
  floor.vertical = false;
  return {floor,
          wall({-h, -h}, {W + h, -h}, {0, 1}),
          wall({-h, H + h}, {W + h, H + h}, {0, -1}),
          wall({-h, -h}, {-h, H + h}, {1, 0}),
          wall({W + h, -h}, {W + h, H + h}, {-1, 0}),
          wall({h, h}, {W - h, h}, {0, -1}),
          wall({h, H - h}, {W - h, H - h}, {0, 1}),
          wall({h, h}, {h, H - h}, {-1, 0}),
          wall({W - h, h}, {W - h, H - h}, {1, 0})};
}

bool sees(const Surface& w, const Eigen::Vector3d& p) {
  if (!w.vertical) return true;
  const Eigen::Vector2d dir = (w.to - w.from).normalized();
  const double along = dir.dot(p.head<2>() - w.from);
  const double distance = w.plane.signed_distance(p);
  return distance > 0.0 && distance < kWallRange && along >= 0.0 && along <= (w.to - w.from).norm();
}

// Builds the graph a front end would: keyframes at the odometry, each surface mapped from its first
// observation, then every observation as a plane edge.
void fill_graph(Scenario& s, const std::vector<Pose3>& odom, bool with_planes, std::mt19937& rng) {
  std::normal_distribution<double> angle(0.0, kPlaneNoiseDeg * kDeg), dist(0.0, kPlaneNoiseDist);
  for (std::size_t k = 0; k < s.truth.size(); ++k) {
    KeyframeNode node;
    node.scan_index = k;
    node.pose = odom[k];
    node.odom = odom[k];
    s.graph.add_keyframe(node);
    if (k > 0) s.graph.add_odometry_edge({int(k) - 1, int(k), odom[k - 1].inverse() * odom[k]});
  }
  s.plane_of.assign(s.surfaces.size(), -1);
  if (!with_planes) return;
  for (std::size_t k = 0; k < s.truth.size(); ++k) {
    for (std::size_t w = 0; w < s.surfaces.size(); ++w) {
      if (!sees(s.surfaces[w], s.truth[k].translation())) continue;
      Plane measured = s.surfaces[w].plane.transformed(s.truth[k].inverse());
      const Eigen::Vector3d tilt(angle(rng), angle(rng), angle(rng));
      measured.n = Eigen::AngleAxisd(tilt.norm(), tilt.normalized()) * measured.n;
      measured.d += dist(rng);
      if (s.plane_of[w] < 0)
        s.plane_of[w] = s.graph.add_plane(measured.transformed(odom[k]), s.surfaces[w].vertical);
      s.graph.add_plane_edge({int(k), s.plane_of[w], measured, 100});
    }
  }
}

// Two laps of the corridor loop, a keyframe every metre, ending where it started.
Scenario corridor_loop(bool with_planes) {
  Scenario s;
  s.surfaces = loop_surfaces();
  const int n = int(kLaps * kLap) + 1;
  for (int k = 0; k < n; ++k) s.truth.push_back(loop_pose(k));
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> trans(0.0, kOdomSigmaTrans), yaw(0.0, kOdomSigmaYawDeg * kDeg);
  std::vector<Pose3> odom{s.truth[0]};
  for (int k = 1; k < n; ++k) {
    Pose3 step = s.truth[k - 1].inverse() * s.truth[k];
    step.translation() += Eigen::Vector3d(trans(rng), trans(rng), 0);
    step.linear() = Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitZ()) * step.linear();
    odom.push_back(odom.back() * step);
  }
  fill_graph(s, odom, with_planes, rng);
  return s;
}

double position_rmse(const SituationalGraph& g, const std::vector<Pose3>& truth) {
  double sum = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k)
    sum += (g.keyframes()[k].pose.translation() - truth[k].translation()).squaredNorm();
  return std::sqrt(sum / double(truth.size()));
}

double end_error(const SituationalGraph& g, const std::vector<Pose3>& truth) {
  return (g.keyframes().back().pose.translation() - truth.back().translation()).norm();
}

struct PlaneErrors {
  double max_angle_deg = 0.0, max_distance = 0.0;
};

PlaneErrors plane_errors(const Scenario& s) {
  PlaneErrors e;
  for (std::size_t w = 0; w < s.surfaces.size(); ++w) {
    if (s.plane_of[w] < 0) continue;
    const Plane& est = s.graph.planes().at(s.plane_of[w]).plane;
    const Plane& gt = s.surfaces[w].plane;
    e.max_angle_deg = std::max(e.max_angle_deg, std::acos(std::min(1.0, est.n.dot(gt.n))) / kDeg);
    e.max_distance = std::max(e.max_distance, std::abs(est.d - gt.d));
  }
  return e;
}

bool same_bits(const Pose3& a, const Pose3& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), sizeof(double) * 16) == 0;
}

bool same_bits(const Plane& a, const Plane& b) {
  return std::memcmp(a.n.data(), b.n.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(&a.d, &b.d, sizeof(double)) == 0;
}

}  // namespace

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
      rmse_odom, rmse, before.max_angle_deg, before.max_distance, after.max_angle_deg,
      after.max_distance, stats.n_variables, stats.n_factors, stats.iterations,
      stats.wall_time_s * 1e3);

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
  constexpr double kNoRobustKernel = 1e9;  // Huber delta no residual reaches: plain least squares
  const double plain = solve(true, kNoRobustKernel);
  std::printf("RMSE without the wrong loop %.4f m; with it: Huber %.4f m, least squares %.4f m\n",
              clean, robust, plain);
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
    worst = std::max(worst,
                     (s.graph.keyframes()[k].pose.translation() - s.truth[k].translation()).norm());
  }
  std::printf("window keyframes displaced %.2f m -> worst error %.4f m\n", kDisplacement.norm(),
              worst);
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
      const Plane wall =
          Plane::from_point_normal({0.0, side * kHalfWidth, 0.0}, {0.0, -double(side), 0.0});
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
    config.linear_solver = solver;
    config.sparse_library = library;
    GraphOptimizer(config).optimize(s.graph, true);
    EXPECT_LT(position_rmse(s.graph, s.truth), 0.05) << solver << " " << library;
  }
}

TEST(GraphOptimizer, RejectsBadConfigAndGraphs) {
  GraphOptimizerConfig config;
  config.linear_solver = "sparse_magic";
  EXPECT_THROW(GraphOptimizer{config}, std::invalid_argument);
  config = {};
  config.sparse_library = "dense_magic";
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
