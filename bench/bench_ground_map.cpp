// Global traversable node map speed on a 66 x 51 m floor (about 53k nodes) built from 300
// keyframes on a 3 m grid, each seeing ~2000 nodes (a 0.2 m lattice within +-4.4 m):
// fuse() of one revisiting keyframe, update() after optimisation (a rigid shift of every
// keyframe: no merges; per-keyframe corrections of 1 mm and 5 cm: merges), and nodes_near().
//   ./build/bench/bench_ground_map --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "tsgraphs/ground/traversable_node_map.hpp"

using namespace tsgraphs;
using namespace tsgraphs::ground;

namespace {

constexpr int kColumns = 20, kRows = 15;              // keyframe grid: 300 keyframes
constexpr double kKeyframeStep = 3.0;                 // between keyframes (m)
constexpr double kHalf = 4.4, kSpacing = 0.2;         // each keyframe sees a 45 x 45 lattice: 2025 nodes
constexpr double kSensorHeight = 0.55;                // above the floor (m)
constexpr double kYawPerMetre = 10.0 * M_PI / 180.0;  // perturbed update: yaw correction per metre of shift
constexpr double kQueryRadius = 3.0;                  // nodes_near radius, the free-space graph's scale (m)
constexpr unsigned kSeed = 1;

struct Keyframe {
  Pose3 pose;
  std::vector<NodeObservation> nodes;  // in the keyframe frame
};

/// Floor z = 0 seen from `pose`: the lattice in the keyframe frame, projected on the floor.
std::vector<NodeObservation> observe(const Pose3& pose) {
  std::vector<NodeObservation> out;
  const int n = static_cast<int>(std::lround(2.0 * kHalf / kSpacing));
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const Eigen::Vector3d offset(-kHalf + i * kSpacing, -kHalf + j * kSpacing, 0.0);
      Eigen::Vector3d p = pose.translation() + pose.linear() * offset;
      p.z() = 0.0;
      NodeObservation obs;
      obs.position = pose.inverse() * p;
      obs.normal = pose.linear().transpose() * Eigen::Vector3d::UnitZ();
      obs.probability = 0.9;
      out.push_back(obs);
    }
  }
  return out;
}

const std::vector<Keyframe>& keyframes() {
  static const std::vector<Keyframe> kfs = [] {
    std::mt19937 rng(kSeed);
    std::uniform_real_distribution<double> yaw(-M_PI, M_PI);
    std::vector<Keyframe> out;
    for (int r = 0; r < kRows; ++r) {
      for (int c = 0; c < kColumns; ++c) {
        const Pose3 pose =
            make_pose(Eigen::Vector3d(c * kKeyframeStep, r * kKeyframeStep, kSensorHeight), yaw(rng));
        out.push_back({pose, observe(pose)});
      }
    }
    return out;
  }();
  return kfs;
}

const TraversableNodeMap& full_map() {
  static const TraversableNodeMap map = [] {
    TraversableNodeMap m;
    const std::vector<Keyframe>& kfs = keyframes();
    for (std::size_t k = 0; k < kfs.size(); ++k) m.fuse(static_cast<int>(k), kfs[k].pose, kfs[k].nodes);
    return m;
  }();
  return map;
}

// One new keyframe revisiting mapped floor: its nodes fuse into existing ones.
void BM_Fuse(benchmark::State& state) {
  TraversableNodeMap map = full_map();
  const std::vector<Keyframe>& kfs = keyframes();
  int next_id = static_cast<int>(kfs.size());
  std::size_t k = 0, observations = 0;
  for (auto _ : state) {
    map.fuse(next_id++, kfs[k].pose, kfs[k].nodes);
    observations += kfs[k].nodes.size();
    k = (k + 1) % kfs.size();
  }
  state.counters["obs/kf"] = static_cast<double>(observations) / static_cast<double>(state.iterations());
  state.counters["nodes"] = static_cast<double>(map.size());
}
BENCHMARK(BM_Fuse)->Unit(benchmark::kMillisecond);

// Every keyframe shifted by the same offset (back and forth): every node moves, none merges.
void BM_UpdateRigid(benchmark::State& state) {
  TraversableNodeMap map = full_map();
  const std::vector<Keyframe>& kfs = keyframes();
  const Eigen::Vector3d shift(1.0, 0.5, 0.0);
  bool shifted = false;
  for (auto _ : state) {
    shifted = !shifted;
    map.update([&](int id) {
      Pose3 T = kfs[static_cast<std::size_t>(id)].pose;
      if (shifted) T.translation() += shift;
      return T;
    });
  }
  state.counters["nodes"] = static_cast<double>(map.size());
  state.counters["keyframes"] = static_cast<double>(kfs.size());
}
BENCHMARK(BM_UpdateRigid)->Unit(benchmark::kMillisecond);

// Each keyframe corrected by its own shift (sigma = the argument, in mm) and yaw: nodes of
// neighbouring keyframes come to share cells and merge. Each iteration starts from the unmerged map.
void BM_UpdatePerturbed(benchmark::State& state) {
  const std::vector<Keyframe>& kfs = keyframes();
  const double sigma = static_cast<double>(state.range(0)) * 1e-3;
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<Pose3> corrected;
  for (const Keyframe& kf : kfs) {
    Pose3 T = kf.pose;
    T.translation() += Eigen::Vector3d(sigma * unit(rng), sigma * unit(rng), 0.0);
    T.linear() = Eigen::AngleAxisd(sigma * kYawPerMetre * unit(rng), Eigen::Vector3d::UnitZ()) * T.linear();
    corrected.push_back(T);
  }
  std::size_t merged = 0;
  for (auto _ : state) {
    state.PauseTiming();
    TraversableNodeMap map = full_map();
    state.ResumeTiming();
    map.update([&](int id) { return corrected[static_cast<std::size_t>(id)]; });
    merged = full_map().size() - map.size();
  }
  state.counters["nodes"] = static_cast<double>(full_map().size());
  state.counters["merged"] = static_cast<double>(merged);
}
BENCHMARK(BM_UpdatePerturbed)->Arg(1)->Arg(50)->Unit(benchmark::kMillisecond);

// The nodes within kQueryRadius of each keyframe.
void BM_NodesNear(benchmark::State& state) {
  const TraversableNodeMap& map = full_map();
  const std::vector<Keyframe>& kfs = keyframes();
  std::size_t k = 0, found = 0;
  for (auto _ : state) {
    Eigen::Vector3d p = kfs[k].pose.translation();
    p.z() = 0.0;
    const auto near = map.nodes_near(p, kQueryRadius);
    found += near.size();
    benchmark::DoNotOptimize(near.data());
    k = (k + 1) % kfs.size();
  }
  state.counters["found"] = static_cast<double>(found) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_NodesNear)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
