// Ground segmentation speed: milliseconds per raw scan (not voxelised) of segment_ground on one
// core, for os1-64 scans of the built-in atrium and vlp-16 scans of the built-in office, each
// spread over the whole path; the counters give the mean and the 95th percentile per scan.
//   ./build/bench/bench_ground --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <string>
#include <unordered_map>
#include <vector>

#include "tsgraphs/ground/ground_segmentation.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

namespace {

constexpr std::size_t kNumScans = 40;  // per scene and sensor, spread over the whole path
constexpr double kP95 = 0.95;

struct Scan {
  PointCloud cloud;
  Eigen::Matrix3d R_map_sensor;
};

// Scans of a built-in scene seen by `preset` (the scene's mount height is kept).
const std::vector<Scan>& scans(const std::string& scene_name, const std::string& preset) {
  static std::unordered_map<std::string, std::vector<Scan>> cache;
  const std::string key = scene_name + "/" + preset;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  scene::Scene scene = scene::parse_scene(*scene::builtin_scene_text(scene_name), "builtin:" + scene_name, ".");
  scene::SensorSpec sensor;
  scene::apply_preset(preset, &sensor);
  sensor.preset = preset;
  sensor.mount_height = scene.sensor.mount_height;
  scene.sensor = sensor;
  const sim::Simulator simulator(scene, 1);
  std::vector<Scan> out;
  for (std::size_t i = 0; i < kNumScans; ++i) {
    const std::size_t k = i * simulator.num_scans() / kNumScans;
    out.push_back({simulator.scan(k), simulator.true_poses()[k].linear()});
  }
  return cache.emplace(key, std::move(out)).first->second;
}

void BM_SegmentGround(benchmark::State& state, const std::string& scene, const std::string& preset) {
  const std::vector<Scan>& input = scans(scene, preset);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  const ground::GroundConfig config = ground::per_sensor_preset(preset);
  std::vector<double> ms;
  std::size_t k = 0, points = 0, ground_points = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const ground::GroundScan result = ground::segment_ground(input[k].cloud, input[k].R_map_sensor, config);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(result.labels.data());
    points += input[k].cloud.size();
    ground_points += static_cast<std::size_t>(std::count(result.labels.begin(), result.labels.end(), ground::GroundLabel::kGround));
    k = (k + 1) % input.size();
  }
  const double n = static_cast<double>(ms.size());
  double sum = 0.0;
  for (double t : ms) sum += t;
  std::sort(ms.begin(), ms.end());
  state.counters["mean_ms"] = sum / n;
  state.counters["p95_ms"] = ms[std::min(ms.size() - 1, static_cast<std::size_t>(kP95 * n))];
  state.counters["points/scan"] = static_cast<double>(points) / n;
  state.counters["ground/scan"] = static_cast<double>(ground_points) / n;
}
BENCHMARK_CAPTURE(BM_SegmentGround, atrium_os1_64, std::string("atrium"), std::string("os1-64"))
    ->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SegmentGround, office_vlp_16, std::string("office"), std::string("vlp-16"))
    ->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
