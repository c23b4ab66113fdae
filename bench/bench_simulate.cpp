// Simulator speed: scans per second for os1-64 on the built-in atrium scene.
//   ./build/bench/bench_simulate --benchmark_counters_tabular=true
// The thread count is the benchmark's argument (TBB's parallelism).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <memory>

#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

namespace {

const sim::Simulator& atrium() {
  static const std::unique_ptr<sim::Simulator> simulator = [] {
    scene::Scene scene = scene::parse_scene(*scene::builtin_scene_text("atrium"), "builtin:atrium", ".");
    scene::SensorSpec sensor;
    scene::apply_preset("os1-64", &sensor);
    sensor.mount_height = scene.sensor.mount_height;
    scene.sensor = sensor;
    return std::make_unique<sim::Simulator>(scene, 1);
  }();
  return *simulator;
}

// Ray casting, noise and labels of one scan (no disk).
void BM_SimulateScan(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(0));
  const sim::Simulator& sim = atrium();
  std::size_t k = 0, points = 0;
  for (auto _ : state) {
    const PointCloud cloud = sim.scan(k);
    points += cloud.size();
    benchmark::DoNotOptimize(cloud.points.data());
    k = (k + 7) % sim.num_scans();
  }
  state.counters["scans/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["points/scan"] = static_cast<double>(points) / state.iterations();
}
BENCHMARK(BM_SimulateScan)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same plus writing .bin and .label files, as `tsgraphs simulate` does.
void BM_SimulateScanAndWrite(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(0));
  const sim::Simulator& sim = atrium();
  const std::string dir = (std::filesystem::temp_directory_path() / "tsgraphs_bench_seq").string();
  std::filesystem::remove_all(dir);
  {
    io::SequenceWriter writer(dir);  // never committed: removed at the end
    std::size_t k = 0;
    for (auto _ : state) {
      writer.write_scan(k % 64, sim.scan(k));
      k = (k + 7) % sim.num_scans();
    }
  }
  state.counters["scans/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateScanAndWrite)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
