// Ground segmentation speed and recall: milliseconds per raw scan (not voxelised) of
// segment_ground on one core, for os1-64 scans of the built-in atrium (at its 0.55 m mount and
// carried at 1.5 m) and vlp-16 scans of the built-in office, each spread over the whole path;
// the counters give the mean and the 95th percentile per scan, the precision over 0.5-15 m and
// the recall of the floor's points by range band (0.5-6, 6-12, 12-15 m; floor more than 1 m
// below the robot's, another storey seen through a void, is not counted, as in `run`) and how
// many floor points per scan each band holds.
//   ./build/bench/bench_ground --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
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

constexpr double kOtherStorey = 1.0;                 // m below the robot's floor: not its ground
constexpr double kBands[] = {0.5, 6.0, 12.0, 15.0};  // m, range bands of the recall

// Scans of a built-in scene seen by `preset` at `height` (0: the scene's mount height).
const std::vector<Scan>& scans(const std::string& scene_name, const std::string& preset, double height) {
  static std::unordered_map<std::string, std::vector<Scan>> cache;
  const std::string key = scene_name + "/" + preset + "/" + std::to_string(height);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  scene::Scene scene =
      scene::parse_scene(*scene::builtin_scene_text(scene_name), "builtin:" + scene_name, ".");
  scene::SensorSpec sensor;
  scene::apply_preset(preset, &sensor);
  sensor.preset = preset;
  sensor.mount_height = height > 0.0 ? height : scene.sensor.mount_height;
  scene.sensor = sensor;
  const sim::Simulator simulator(scene, 1);
  std::vector<Scan> out;
  for (std::size_t i = 0; i < kNumScans; ++i) {
    const std::size_t k = i * simulator.num_scans() / kNumScans;
    out.push_back({simulator.scan(k), simulator.true_poses()[k].linear()});
  }
  return cache.emplace(key, std::move(out)).first->second;
}

void BM_SegmentGround(benchmark::State& state, const std::string& scene, const std::string& preset,
                      double height, double seed_radius) {
  const std::vector<Scan>& input = scans(scene, preset, height);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  ground::GroundConfig config = ground::per_sensor_preset(preset);
  if (height > 0.0) config.sensor_height = height;
  if (seed_radius > 0.0) config.seed_radius = seed_radius;
  std::vector<double> tp(3, 0.0), fn(3, 0.0);
  double all_tp = 0.0, all_fp = 0.0;
  std::vector<double> ms;
  std::size_t k = 0, points = 0, ground_points = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const ground::GroundScan result = ground::segment_ground(input[k].cloud, input[k].R_map_sensor, config);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(result.labels.data());
    points += input[k].cloud.size();
    ground_points += static_cast<std::size_t>(
        std::count(result.labels.begin(), result.labels.end(), ground::GroundLabel::kGround));
    const PointCloud& cloud = input[k].cloud;
    const Eigen::Vector3d up = result.R_level_sensor.transpose().col(2);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const double r = cloud.points[i].norm();
      if (!(r >= kBands[0] && r <= kBands[3])) continue;
      const bool floor = cloud.labels[i] == static_cast<std::uint32_t>(PointLabel::kFloor) ||
                         cloud.labels[i] == static_cast<std::uint32_t>(PointLabel::kRamp);
      if (floor && up.dot(cloud.points[i].cast<double>()) < -config.sensor_height - kOtherStorey) continue;
      const bool ground = result.labels[i] == ground::GroundLabel::kGround;
      const int band = r < kBands[1] ? 0 : r < kBands[2] ? 1 : 2;
      all_tp += floor && ground;
      all_fp += !floor && ground;
      if (floor) (ground ? tp : fn)[band] += 1.0;
    }
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
  state.counters["P"] = all_tp / std::max(1.0, all_tp + all_fp);
  // A band without floor (a VLP-16 at 0.55 m has no ring between 9.7 and 21 m) has no recall: NaN.
  const char* names[] = {"0.5-6", "6-12", "12-15"};
  for (int b = 0; b < 3; ++b) {
    state.counters[std::string("R_") + names[b]] =
        tp[b] + fn[b] > 0.0 ? tp[b] / (tp[b] + fn[b]) : std::nan("");
    state.counters[std::string("floor_") + names[b]] = (tp[b] + fn[b]) / n;
  }
}
BENCHMARK_CAPTURE(BM_SegmentGround, atrium_os1_64, std::string("atrium"), std::string("os1-64"), 0.0, 0.0)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
// Carried at 1.5 m: the first floor ring 3.6 m out, the seed radius by the platform's rule
// (pipeline/platform.hpp: 3.6 + 1.5 m).
BENCHMARK_CAPTURE(BM_SegmentGround, atrium_os1_64_h150, std::string("atrium"), std::string("os1-64"), 1.5,
                  5.12)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SegmentGround, office_vlp_16, std::string("office"), std::string("vlp-16"), 0.0, 0.0)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
