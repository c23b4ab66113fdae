// Back-end speed: full and local solves of a 2000-keyframe situational graph (8 laps of a
// 100 x 25 m corridor loop, 50 wall planes, a loop closure every 25 m from the second lap).
//   ./build/bench/bench_graph --benchmark_counters_tabular=true
// The benchmark's argument picks the linear solver and sparse back-end (kBackEnds). Time is
// T_PGO (Ceres Solve only); call_ms adds building the problem and writing the estimates back.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/graph/graph_optimizer.hpp"

using namespace tsgraphs;
using namespace tsgraphs::graph;

namespace {

constexpr int kKeyframes = 2000;
constexpr double kWidth = 100.0, kHeight = 25.0;  // loop centre line (m), a keyframe per metre
constexpr double kLap = 2.0 * (kWidth + kHeight);
constexpr double kHalfWidth = 1.5;  // corridor half width (m)
constexpr double kSegment = 10.0;   // one wall plane per side per 10 m of corridor
constexpr int kLoopEvery = 25;      // keyframes between loop closures to the previous lap
constexpr double kOdomSigmaTrans = 0.02, kOdomSigmaYawDeg = 0.2;  // per step
constexpr double kMeasSigmaTrans = 0.01, kMeasSigmaDeg = 0.2;     // loops and planes
constexpr unsigned kSeed = 1;
constexpr double kDeg = M_PI / 180.0;

const std::vector<std::pair<std::string, std::string>> kBackEnds = {
    {"sparse_normal_cholesky", "suite_sparse"},
    {"sparse_normal_cholesky", "cx_sparse"},
    {"sparse_normal_cholesky", "eigen_sparse"},
    {"sparse_schur", "suite_sparse"},
    {"sparse_schur", "cx_sparse"},
    {"sparse_schur", "eigen_sparse"}};

Pose3 loop_pose(double s) {
  s = std::fmod(s, kLap);
  if (s < kWidth) return make_pose({s, 0, 0}, 0.0);
  s -= kWidth;
  if (s < kHeight) return make_pose({kWidth, s, 0}, M_PI / 2);
  s -= kHeight;
  if (s < kWidth) return make_pose({kWidth - s, kHeight, 0}, M_PI);
  s -= kWidth;
  return make_pose({0, kHeight - s, 0}, -M_PI / 2);
}

Pose3 perturbed(Pose3 T, double sigma_trans, double sigma_rad, std::mt19937& rng) {
  std::normal_distribution<double> t(0.0, sigma_trans), r(0.0, sigma_rad);
  T.translation() += Eigen::Vector3d(t(rng), t(rng), 0.0);
  T.linear() = Eigen::AngleAxisd(r(rng), Eigen::Vector3d::UnitZ()) * T.linear();
  return T;
}

// The graph a front end would build: drifting odometry, walls mapped from their first sighting.
SituationalGraph make_graph() {
  std::mt19937 rng(kSeed);
  std::vector<Pose3> truth, odom;
  for (int k = 0; k < kKeyframes; ++k) truth.push_back(loop_pose(k));
  odom.push_back(truth[0]);
  for (int k = 1; k < kKeyframes; ++k)
    odom.push_back(odom.back() * perturbed(truth[k - 1].inverse() * truth[k], kOdomSigmaTrans,
                                           kOdomSigmaYawDeg * kDeg, rng));
  SituationalGraph g;
  std::map<std::pair<int, int>, int> plane_of;  // (segment of the lap, side) -> plane id
  std::normal_distribution<double> dist(0.0, kMeasSigmaTrans), angle(0.0, kMeasSigmaDeg * kDeg);
  for (int k = 0; k < kKeyframes; ++k) {
    KeyframeNode node;
    node.scan_index = std::size_t(k);
    node.pose = node.odom = odom[k];
    g.add_keyframe(node);
    if (k > 0) g.add_odometry_edge({k - 1, k, odom[k - 1].inverse() * odom[k]});
    if (k >= int(kLap) && k % kLoopEvery == 0) {
      const int old = k - int(kLap);
      g.add_loop_edge({old, k,
                       perturbed(truth[old].inverse() * truth[k], kMeasSigmaTrans, kMeasSigmaDeg * kDeg, rng),
                       0.01});
    }
    const int segment = int(std::fmod(k, kLap) / kSegment);
    for (int side : {-1, 1}) {
      // Side walls in the keyframe's frame (heading along the corridor), normals towards it.
      Plane measured = Plane::from_point_normal({0.0, side * kHalfWidth, 0.0}, {0.0, -double(side), 0.0});
      measured.n = Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ()) * measured.n;
      measured.d += dist(rng);
      auto [it, inserted] = plane_of.try_emplace({segment, side}, -1);
      if (inserted) it->second = g.add_plane(measured.transformed(odom[k]), true);
      g.add_plane_edge({k, it->second, measured, 100});
    }
  }
  return g;
}

const SituationalGraph& drifted_graph() {
  static const SituationalGraph graph = make_graph();
  return graph;
}

GraphOptimizerConfig config_for(int back_end) {
  GraphOptimizerConfig config;
  config.linear_solver = *kLinearSolvers.parse(kBackEnds[std::size_t(back_end)].first);
  config.sparse_library = *kSparseLibraries.parse(kBackEnds[std::size_t(back_end)].second);
  return config;
}

// Times optimize(graph_copy) per iteration: T_PGO as the benchmark's time, the whole call as a
// counter.
void run(benchmark::State& state, const SituationalGraph& input, bool full) {
  const auto& [solver, library] = kBackEnds[std::size_t(state.range(0))];
  state.SetLabel(solver + "/" + library);
  GraphOptimizer optimizer(config_for(int(state.range(0))));
  OptimizationStats stats;
  double call_s = 0.0;
  for (auto _ : state) {
    SituationalGraph graph = input;
    const auto start = std::chrono::steady_clock::now();
    stats = optimizer.optimize(graph, full);
    call_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(stats.wall_time_s);
  }
  state.counters["vars"] = stats.n_variables;
  state.counters["factors"] = stats.n_factors;
  state.counters["its"] = stats.iterations;
  state.counters["call_ms"] = benchmark::Counter(call_s * 1e3, benchmark::Counter::kAvgIterations);
}

// Full solve from the drifted odometry (after a loop closure).
void BM_FullSolve(benchmark::State& state) { run(state, drifted_graph(), true); }

// Local solve at the end of the run: the map is optimised, the last window of keyframes has
// drifted since.
void BM_LocalSolve(benchmark::State& state) {
  static const SituationalGraph optimised = [] {
    SituationalGraph g = drifted_graph();
    GraphOptimizer().optimize(g, true);
    std::mt19937 rng(kSeed);
    const int window = GraphOptimizerConfig{}.local_window;
    for (int k = kKeyframes - window; k < kKeyframes; ++k)
      g.keyframes()[std::size_t(k)].pose =
          perturbed(g.keyframes()[std::size_t(k)].pose, kOdomSigmaTrans * window, 0.0, rng);
    return g;
  }();
  run(state, optimised, false);
}

}  // namespace

BENCHMARK(BM_FullSolve)
    ->DenseRange(0, int(kBackEnds.size()) - 1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LocalSolve)
    ->DenseRange(0, int(kBackEnds.size()) - 1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
