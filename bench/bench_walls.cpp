// Plane extraction speed: milliseconds per os1-64 keyframe of the built-in office and atrium
// scenes, prefiltered with a 0.1 m voxel grid as the pipeline does, on one thread.
//   ./build/bench/bench_walls --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "tsgraphs/pipeline/prefilter.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"
#include "tsgraphs/walls/plane_extraction.hpp"

using namespace tsgraphs;

namespace {

constexpr double kVoxel = 0.1;         // the pipeline's default prefilter voxel (m)
constexpr std::size_t kNumScans = 24;  // keyframes per scene, spread over the whole path

// The pipeline's own prefilter (NaN drop, range crop, one centroid per voxel).
PointCloud voxel_filter(const PointCloud& in, double voxel) {
  pipeline::PrefilterConfig config;
  config.voxel_size = voxel;
  return pipeline::prefilter(in, config);
}

struct Keyframe {
  PointCloud cloud;
  Eigen::Matrix3d R_map_keyframe;
};

const std::vector<Keyframe>& keyframes(const std::string& name) {
  static std::unordered_map<std::string, std::vector<Keyframe>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  scene::Scene scene = scene::parse_scene(*scene::builtin_scene_text(name), "builtin:" + name, ".");
  scene::SensorSpec sensor;
  scene::apply_preset("os1-64", &sensor);
  sensor.mount_height = scene.sensor.mount_height;
  scene.sensor = sensor;
  const sim::Simulator simulator(scene, 1);
  std::vector<Keyframe> out;
  for (std::size_t i = 0; i < kNumScans; ++i) {
    const std::size_t k = i * simulator.num_scans() / kNumScans;
    out.push_back({voxel_filter(simulator.scan(k), kVoxel), simulator.true_poses()[k].linear()});
  }
  return cache.emplace(name, std::move(out)).first->second;
}

void BM_ExtractPlanes(benchmark::State& state, const std::string& scene) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  const std::vector<Keyframe>& kfs = keyframes(scene);
  const walls::PlaneExtractionConfig config;
  std::size_t k = 0, points = 0, planes = 0;
  for (auto _ : state) {
    const std::vector<walls::PlaneObservation> obs =
        walls::extract_planes(kfs[k].cloud, kfs[k].R_map_keyframe, config);
    points += kfs[k].cloud.size();
    planes += obs.size();
    benchmark::DoNotOptimize(obs.data());
    k = (k + 1) % kfs.size();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["points/kf"] = static_cast<double>(points) / n;
  state.counters["planes/kf"] = static_cast<double>(planes) / n;
}
BENCHMARK_CAPTURE(BM_ExtractPlanes, office, std::string("office"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ExtractPlanes, atrium, std::string("atrium"))->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
