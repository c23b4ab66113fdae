// tsgraphs: the command line. A thin front end over the library; see docs/DESIGN.md for the
// contract (commands, options, exit status 0 / 2 bad input / 1 internal error).
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "progress.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/eval/run_evaluation.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/pipeline/run_outputs.hpp"
#include "tsgraphs/pipeline/sequence_runner.hpp"
#include "tsgraphs/report/scene_svg.hpp"
#include "tsgraphs/sim/builtin_scenes.hpp"
#include "tsgraphs/sim/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;

namespace {

struct Options {
  bool quiet = false;
  int threads = 0;
  std::string scene;
  std::string out;
  long long seed = -1;
  int laps = 0;
  int seeds = 1;
  std::string seq;
  std::string config;
  std::string free_space;    ///< overrides room_layer.free_space_method when set
  std::string room_trigger;  ///< overrides room_layer.room_trigger when set
};

// A scene file, or the name of a built-in scene (office, atrium, long_corridor, two_storeys).
sim::Scene resolve_scene(const std::string& arg) {
  if (!fs::exists(arg)) {
    if (const auto text = sim::builtin_scene_text(arg)) return sim::parse_scene(*text, "builtin:" + arg, ".");
    std::string names;
    for (const std::string& n : sim::builtin_scene_names()) names += (names.empty() ? "" : ", ") + n;
    throw input_error(arg, 0, "no such scene file (built-in scenes: " + names + ")");
  }
  return sim::load_scene(arg);
}

// Warnings are shown even with --quiet: they say the output may not be what was meant.
void print_warnings(const std::string& where, const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::fprintf(stderr, "tsgraphs: warning: %s%s\n", where.c_str(), w.c_str());
}

sim::Scene load_and_warn(const std::string& arg) {
  sim::Scene scene = resolve_scene(arg);
  print_warnings("", scene.warnings);
  return scene;
}

void simulate(const sim::Scene& scene_in, const std::string& out, std::uint64_t seed, int laps, bool quiet) {
  sim::Scene scene = scene_in;
  if (laps > 0) scene.trajectory.laps = laps;
  sim::Simulator simulator(scene, seed);
  print_warnings(scene.file + ": trajectory: ", simulator.trajectory().warnings());
  if (!quiet) {
    std::fprintf(stderr, "simulate: %s, %s %dx%d, %zu scans over %.1f m (%d lap%s), %zu triangles, seed %llu\n",
                 scene.name.c_str(), scene.sensor.preset.empty() ? "custom sensor" : scene.sensor.preset.c_str(),
                 scene.sensor.channels, scene.sensor.columns, simulator.num_scans(), simulator.trajectory().length(),
                 scene.trajectory.laps, scene.trajectory.laps == 1 ? "" : "s", simulator.num_triangles(),
                 static_cast<unsigned long long>(seed));
  }
  app::Progress progress("simulate", quiet);
  sim::write_sequence(simulator, out, [&](std::size_t done, std::size_t total) { progress.update(done, total); });
  if (!quiet) std::fprintf(stderr, "simulate: wrote %s\n", out.c_str());
}

void draw_scene(const sim::Scene& scene, const std::string& out, bool quiet) {
  const sim::Trajectory trajectory(scene);
  print_warnings(scene.file + ": trajectory: ", trajectory.warnings());
  io::write_file_atomic(out, report::scene_svg(scene, trajectory));
  if (!quiet) std::fprintf(stderr, "draw-scene: wrote %s\n", out.c_str());
}

// `run`: a sequence folder through the pipeline into a run folder, written whole or not at all.
void run(const std::string& seq_dir, const std::string& out, const Options& opt) {
  const auto start = std::chrono::steady_clock::now();
  const bool quiet = opt.quiet;
  pipeline::PipelineConfig config =
      opt.config.empty() ? pipeline::PipelineConfig{} : pipeline::load_pipeline_config(opt.config);
  if (!opt.free_space.empty()) config.rooms.layer.free_space_method = opt.free_space;
  if (!opt.room_trigger.empty()) config.rooms.layer.room_trigger = opt.room_trigger;
  const io::SequenceReader sequence(seq_dir);
  io::AtomicDirectory dir(out, pipeline::run_files::kSceneGraph);
  if (!quiet) std::fprintf(stderr, "run: %s, %zu scans\n", seq_dir.c_str(), sequence.size());
  pipeline::Pipeline slam(config);
  app::Progress progress("run", quiet);
  pipeline::RunCallbacks callbacks;
  callbacks.progress = [&](std::size_t done, std::size_t total) { progress.update(done, total); };
  callbacks.warning = [](const std::string& w) { std::fprintf(stderr, "tsgraphs: warning: %s\n", w.c_str()); };
  pipeline::RunInfo info = pipeline::run_sequence(sequence, slam, callbacks);
  info.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  pipeline::write_run_outputs(slam, info, dir.path());
  dir.commit();
  if (!quiet) {
    std::fprintf(stderr, "run: %zu keyframes, %zu planes, %zu loop closures, %zu optimisations; %.1f s (%.1fx real time)\n",
                 slam.graph().keyframes().size(), slam.graph().planes().size(), slam.graph().loop_edges().size(),
                 slam.optimizations().size(), info.wall_time_s,
                 info.wall_time_s > 0 ? info.sequence_duration_s / info.wall_time_s : 0.0);
    std::fprintf(stderr, "run: wrote %s\n", out.c_str());
  }
}

// `eval`: metrics.json in the run folder and the table on stdout.
void evaluate(const std::string& run_dir, const std::string& seq_dir, bool quiet) {
  eval::EvalOptions options;
  options.run_dir = run_dir;
  options.seq_dir = seq_dir;
  const eval::Metrics metrics = eval::evaluate_run(options);
  io::write_file_atomic((fs::path(run_dir) / pipeline::run_files::kMetrics).string(), eval::metrics_json(metrics));
  std::printf("%s", eval::metrics_table(metrics).c_str());
  if (!quiet) std::fprintf(stderr, "eval: wrote %s\n", (fs::path(run_dir) / pipeline::run_files::kMetrics).c_str());
}

std::uint64_t seed_for(const sim::Scene& scene, long long cli_seed) {
  return cli_seed >= 0 ? static_cast<std::uint64_t>(cli_seed) : scene.seed;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tsgraphs: traversability-aware situational graphs from indoor 3-D LiDAR"};
  app.require_subcommand(1);
  app.fallthrough();  // --quiet and --threads also after the subcommand
  app.set_version_flag("--version", "tsgraphs " TSGRAPHS_VERSION);
  Options opt;
  app.add_flag("-q,--quiet", opt.quiet, "no progress output");
  app.add_option("--threads", opt.threads, "worker threads (default: all cores)")->check(CLI::NonNegativeNumber);

  auto* simulate_cmd = app.add_subcommand("simulate", "turn a scene into a LiDAR sequence folder");
  simulate_cmd->add_option("SCENE", opt.scene, "scene YAML file or built-in scene name")->required();
  simulate_cmd->add_option("--out", opt.out, "sequence folder to write")->required();
  simulate_cmd->add_option("--seed", opt.seed, "random seed (default: the scene's)")->check(CLI::NonNegativeNumber);
  simulate_cmd->add_option("--laps", opt.laps, "laps of the path (default: the scene's)")->check(CLI::PositiveNumber);

  auto* draw_cmd = app.add_subcommand("draw-scene", "bird's-eye SVG of a scene and its path");
  draw_cmd->add_option("SCENE", opt.scene, "scene YAML file or built-in scene name")->required();
  draw_cmd->add_option("--out", opt.out, "SVG file to write")->required();

  auto* run_cmd = app.add_subcommand("run", "the SLAM pipeline: a sequence folder in, a run folder out");
  run_cmd->add_option("SEQ_DIR", opt.seq, "sequence folder (docs/scene-format.md)")->required();
  run_cmd->add_option("--out", opt.out, "run folder to write")->required();
  run_cmd->add_option("--config", opt.config, "parameter file (config/params.yaml lists every key)");
  run_cmd->add_option("--free-space", opt.free_space,
                      "traversable (TS-graphs, default) or esdf (S-Graphs+); overrides room_layer.free_space_method")
      ->check(CLI::IsMember({"traversable", "esdf"}));
  run_cmd->add_option("--room-trigger", opt.room_trigger,
                      "flush (TS-graphs, default) or timer (S-Graphs+); overrides room_layer.room_trigger")
      ->check(CLI::IsMember({"flush", "timer"}));

  auto* eval_cmd = app.add_subcommand("eval", "metrics of a run: metrics.json and a table");
  eval_cmd->add_option("RUN_DIR", opt.out, "run folder written by `tsgraphs run`")->required();
  eval_cmd->add_option("--seq", opt.seq, "the sequence folder it ran on (ground truth)");

  auto* demo_cmd = app.add_subcommand("demo", "simulate the built-in atrium scene, draw it, run the pipeline on it and evaluate");
  opt.out = "";
  demo_cmd->add_option("--out", opt.out, "output folder (default: tsgraphs-demo)");
  demo_cmd->add_option("--seeds", opt.seeds, "number of seeds to simulate (1..N)")->check(CLI::PositiveNumber);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  spdlog::set_level(opt.quiet ? spdlog::level::warn : spdlog::level::info);
  const int threads = opt.threads > 0 ? opt.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  tbb::global_control threads_control(tbb::global_control::max_allowed_parallelism, threads);

  try {
    if (*simulate_cmd) {
      const sim::Scene scene = load_and_warn(opt.scene);
      simulate(scene, opt.out, seed_for(scene, opt.seed), opt.laps, opt.quiet);
    } else if (*draw_cmd) {
      draw_scene(load_and_warn(opt.scene), opt.out, opt.quiet);
    } else if (*run_cmd) {
      run(opt.seq, opt.out, opt);
    } else if (*eval_cmd) {
      evaluate(opt.out, opt.seq, opt.quiet);
    } else if (*demo_cmd) {
      const std::string out = opt.out.empty() ? "tsgraphs-demo" : opt.out;
      fs::create_directories(out);
      const sim::Scene scene = resolve_scene("atrium");
      draw_scene(scene, (fs::path(out) / "atrium.svg").string(), opt.quiet);
      for (int s = 1; s <= opt.seeds; ++s) {
        const std::string seq = (fs::path(out) / ("atrium_seed" + std::to_string(s))).string();
        simulate(scene, seq, static_cast<std::uint64_t>(s), 0, opt.quiet);
        Options defaults;
        defaults.quiet = opt.quiet;
        run(seq, seq + "_run", defaults);
        evaluate(seq + "_run", seq, opt.quiet);
      }
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "tsgraphs: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tsgraphs: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
