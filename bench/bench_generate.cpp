// Building generator speed: one building per style (seeds 1-4 in turn), layout, furniture,
// survey path and the generator's own checks included.
//   ./build/bench/bench_generate --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <string>

#include "tsgraphs/generator/generator.hpp"
#include "tsgraphs/scene/trajectory.hpp"

using namespace tsgraphs;

namespace {

void BM_Generate(benchmark::State& state, const std::string& style) {
  std::uint64_t seed = 1;
  double rooms = 0.0, lap_m = 0.0, attempts = 0.0;
  for (auto _ : state) {
    const generator::GeneratedBuilding b = generator::generate_building(style, seed);
    rooms += static_cast<double>(b.scene.rooms.size());
    lap_m += scene::Trajectory(b.scene).length() / b.scene.trajectory.laps;
    attempts += b.attempts;
    seed = seed % 4 + 1;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["rooms"] = rooms / n;
  state.counters["lap_m"] = lap_m / n;
  state.counters["attempts"] = attempts / n;
}

}  // namespace

BENCHMARK_CAPTURE(BM_Generate, office, std::string("office"))->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK_CAPTURE(BM_Generate, atrium, std::string("atrium"))->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK_CAPTURE(BM_Generate, library, std::string("library"))->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK_CAPTURE(BM_Generate, open_plan, std::string("open_plan"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4);
BENCHMARK_CAPTURE(BM_Generate, irregular, std::string("irregular"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4);
BENCHMARK_CAPTURE(BM_Generate, multi_storey, std::string("multi_storey"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4);
BENCHMARK_CAPTURE(BM_Generate, mixed, std::string("mixed"))->Unit(benchmark::kMillisecond)->Iterations(4);

BENCHMARK_MAIN();
