// The commands of the `tsgraphs` program (commands.hpp).
#include "commands.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <vector>
#include <unistd.h>

#include "output_checks.hpp"
#include "progress.hpp"
#include "segmentation_images.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/eval/run_evaluation.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/odometry_checks.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/odometry/floor_levelling.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"
#include "tsgraphs/pipeline/odometry_choice.hpp"
#include "tsgraphs/pipeline/run_outputs.hpp"
#include "tsgraphs/pipeline/sequence_runner.hpp"
#include "tsgraphs/report/foxglove_export.hpp"
#include "tsgraphs/report/report_html.hpp"
#include "tsgraphs/report/scene_svg.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

namespace tsgraphs::app {

namespace fs = std::filesystem;

scene::Scene resolve_scene(const std::string& arg) {
  if (!fs::exists(arg)) {
    if (const auto text = scene::builtin_scene_text(arg))
      return scene::parse_scene(*text, "builtin:" + arg, ".");
    std::string names;
    for (const std::string& n : scene::builtin_scene_names()) names += (names.empty() ? "" : ", ") + n;
    throw input_error(arg, 0, "no such scene file (built-in scenes: " + names + ")");
  }
  return scene::load_scene(arg);
}

void print_warnings(const std::string& where, const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    std::fprintf(stderr, "tsgraphs: warning: %s%s\n", where.c_str(), w.c_str());
}

scene::Scene load_and_warn(const std::string& arg) {
  scene::Scene scene = resolve_scene(arg);
  print_warnings("", scene.warnings);
  return scene;
}

void simulate(const scene::Scene& scene_in, const std::string& out, std::uint64_t seed, int laps,
              bool quiet) {
  check_output_apart("--out", out, scene_inputs(scene_in));
  scene::Scene scene = scene_in;
  if (laps > 0) {
    scene.trajectory.laps = laps;
    // The scene's own laps passed this check when it was loaded; these must too.
    const std::string over = scene::recording_over_limits(scene);
    if (!over.empty()) throw input_error("--laps", 0, over);
  }
  sim::Simulator simulator(scene, seed);
  print_warnings(scene.file + ": trajectory: ", simulator.trajectory().warnings());
  if (!quiet) {
    std::fprintf(
        stderr, "simulate: %s, %s %dx%d, %zu scans over %.1f m (%d lap%s), %zu triangles, seed %llu\n",
        scene.name.c_str(), scene.sensor.preset.empty() ? "custom sensor" : scene.sensor.preset.c_str(),
        scene.sensor.channels, scene.sensor.columns, simulator.num_scans(), simulator.trajectory().length(),
        scene.trajectory.laps, scene.trajectory.laps == 1 ? "" : "s", simulator.num_triangles(),
        static_cast<unsigned long long>(seed));
  }
  app::Progress progress("simulate", quiet);
  sim::write_sequence(simulator, out,
                      [&](std::size_t done, std::size_t total) { progress.update(done, total); });
  if (!quiet) std::fprintf(stderr, "simulate: wrote %s\n", out.c_str());
}

void simulate_bag(const scene::Scene& scene, const std::string& bag, const std::string& seq_dir,
                  std::uint64_t seed, int laps, const std::string& format_option,
                  const std::string& compression, bool quiet) {
  check_output_apart("--bag", bag, scene_inputs(scene));
  std::string format = format_option;
  const std::string ext = fs::path(bag).extension().string();
  if (format == "auto") {
    format = ext == ".mcap" ? "ros2-mcap" : ext == ".db3" ? "ros2-sqlite" : ext == ".bag" ? "ros1" : "";
    if (format.empty())
      throw input_error(bag, 0,
                        "give the bag a .bag, .mcap or .db3 name, or --bag-format (ros2 formats write a bag "
                        "folder under another name)");
  }
  // zstd-file and zstd-message: rosbag2's own compression (a bag folder only), MCAP chunks then uncompressed.
  const std::map<std::string, std::vector<std::string>> kCompressions = {
      {"ros1", {"lz4", "none", "bz2"}},
      {"ros2-mcap", {"zstd", "none", "lz4", "zstd-file", "zstd-message"}},
      {"ros2-sqlite", {"none", "zstd-file", "zstd-message"}}};
  const std::vector<std::string>& allowed = kCompressions.at(format);  // the first: the default
  const std::string c = compression.empty() ? allowed.front() : compression;
  if (std::find(allowed.begin(), allowed.end(), c) == allowed.end()) {
    std::string list;
    for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw input_error("--compression", 0, c + " is not a " + format + " compression (" + list + ")");
  }
  if ((c == "zstd-file" || c == "zstd-message") && (ext == ".db3" || ext == ".mcap")) {
    throw input_error(bag, 0,
                      "--compression " + c +
                          " is rosbag2's own, for a bag folder (its metadata.yaml records it): give "
                          "a name without " +
                          ext);
  }
  // The LiDAR 0.3 m above and 0.1 m ahead of base_link, so that /tf_static is not the identity.
  const Pose3 sensor_to_base = make_pose(Eigen::Vector3d(0.1, 0.0, 0.3), 0.0);
  const std::string folder = seq_dir.empty() ? bag + ".sequence-tmp-" + std::to_string(::getpid()) : seq_dir;
  simulate(scene, folder, seed, laps, quiet);
  try {
    const io::SequenceReader sequence(folder);
    if (format == "ros1") {
      ros1_bag::write_bag(sequence, bag,
                          c == "bz2"   ? ros1_bag::BagCompression::bz2
                          : c == "lz4" ? ros1_bag::BagCompression::lz4
                                       : ros1_bag::BagCompression::none,
                          sensor_to_base);
    } else {
      ros2_bag::write_rosbag2(
          sequence, bag,
          format == "ros2-mcap" ? ros2_bag::Rosbag2Storage::mcap : ros2_bag::Rosbag2Storage::sqlite,
          c == "zstd"  ? mcap::Compression::zstd
          : c == "lz4" ? mcap::Compression::lz4
                       : mcap::Compression::none,
          sensor_to_base,
          c == "zstd-file"      ? ros2_bag::Rosbag2Compression::file
          : c == "zstd-message" ? ros2_bag::Rosbag2Compression::message
                                : ros2_bag::Rosbag2Compression::none);
    }
  } catch (...) {
    if (seq_dir.empty()) fs::remove_all(folder);
    throw;
  }
  if (seq_dir.empty()) fs::remove_all(folder);
  if (!quiet) std::fprintf(stderr, "simulate: wrote %s\n", bag.c_str());
}

void convert(const io::ScanSequence& sequence, const std::string& out,
             const pipeline::OdometryOptions& odometry, const pipeline::PipelineConfig& config, bool quiet) {
  io::SequenceWriter writer(out);
  io::SequenceInfo info = sequence.info();
  std::optional<odometry::LidarOdometry> lidar_odometry;
  if (odometry.estimate) {
    lidar_odometry.emplace(pipeline::make_lidar_odometry(config, odometry.initial_pose));
    info.odometry.clear();
  }
  app::Progress progress("convert", quiet);
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const PointCloud scan = sequence.scan(i);
    writer.write_scan(i, scan);
    if (lidar_odometry) info.odometry.push_back(lidar_odometry->register_scan(scan, info.times[i]));
    progress.update(i + 1, sequence.size());
  }
  writer.commit(info);
  if (!quiet)
    std::fprintf(stderr, "convert: wrote %s (%zu scans%s)\n", out.c_str(), sequence.size(),
                 lidar_odometry ? ", odom.txt from LiDAR odometry" : "");
}

void export_mcap(const std::string& run_dir, const std::string& out, bool quiet) {
  check_output_apart("--mcap", out, {run_dir});
  report::export_foxglove_mcap(run_dir, out);
  if (!quiet) std::fprintf(stderr, "export: wrote %s\n", out.c_str());
}

void print_bag_info(const std::string& bag) {
  std::printf("%s",
              (ros2_bag::is_rosbag2(bag) ? ros2_bag::rosbag2_info(bag) : ros1_bag::bag_info(bag)).c_str());
}

void draw_scene(const scene::Scene& scene, const std::string& out, bool quiet) {
  check_output_apart("--out", out, scene_inputs(scene));
  const scene::Trajectory trajectory(scene);
  print_warnings(scene.file + ": trajectory: ", trajectory.warnings());
  io::write_file_atomic(out, report::scene_svg(scene, trajectory));
  if (!quiet) std::fprintf(stderr, "draw-scene: wrote %s\n", out.c_str());
}

std::unique_ptr<io::ScanSequence> open_sequence(const io::ScanFolderOptions& options) {
  if (options.scans.empty() && io::is_sequence_folder(options.folder)) {
    if (!options.poses.empty() || !options.times.empty() || options.pose_format != "auto")
      throw input_error(options.folder, 0,
                        "a sequence folder has its own poses and times: --poses, --times and "
                        "--pose-format are for folders of scans");
    auto sequence = std::make_unique<io::SequenceReader>(options.folder);
    io::check_odometry_motion(sequence->info(), sequence->dir());
    return sequence;
  }
  auto sequence = std::make_unique<io::ScanFolderReader>(options);
  io::check_odometry_motion(sequence->info(), sequence->dir());
  return sequence;
}

namespace {

OpenedBag opened(std::unique_ptr<io::RecordedSequence> bag, const io::BagOptions& options, bool quiet) {
  io::check_odometry_motion(bag->info(), options.bag);
  if (!quiet && bag->dropped_scans() > 0)
    std::fprintf(stderr, "run: %zu scans of %s lie outside the odometry's time span and are left out\n",
                 bag->dropped_scans(), options.bag.c_str());
  OpenedBag out;
  if (bag->sensor_to_base_known()) out.mount = bag->sensor_to_base();
  out.sequence = std::move(bag);
  return out;
}

}  // namespace

OpenedBag open_bag(const io::BagOptions& options, bool quiet) {
  if (ros2_bag::is_rosbag2(options.bag)) {
    auto bag = std::make_unique<ros2_bag::Rosbag2Sequence>(options);
    print_warnings("", bag->warnings());  // each names its file
    return opened(std::move(bag), options, quiet);
  }
  auto bag = std::make_unique<ros1_bag::BagSequence>(options);
  print_warnings(options.bag + ": ", bag->warnings());
  return opened(std::move(bag), options, quiet);
}

pipeline::OdometryOptions choose_odometry(const io::ScanSequence& sequence, const std::string& mode,
                                          const std::optional<Pose3>& sensor_to_base,
                                          const odometry::FloorLevellingConfig& levelling, bool quiet) {
  const pipeline::OdometryChoice choice =
      pipeline::choose_odometry(sequence, mode, sensor_to_base, levelling);
  if (choice.level && !quiet)
    std::fprintf(stderr,
                 "odometry: the map is level with the floor under the first scan (sensor %.2f m above it, "
                 "tilted %.1f deg)\n",
                 choice.level->height, choice.level->tilt_deg);
  if (!choice.warning.empty()) print_warnings(sequence.dir() + ": ", {choice.warning});
  return choice.options;
}

void run(const std::string& seq_dir, const std::string& out, const pipeline::PipelineConfig& config,
         bool quiet) {
  io::ScanFolderOptions folder;
  folder.folder = seq_dir;
  const std::unique_ptr<io::ScanSequence> sequence = open_sequence(folder);
  run(*sequence, out, config, quiet,
      choose_odometry(*sequence, "auto", std::nullopt, config.floor_levelling, quiet));
}

void run(const io::ScanSequence& sequence, const std::string& out, const pipeline::PipelineConfig& config,
         bool quiet, const pipeline::OdometryOptions& odometry, bool segmentations) {
  const auto start = std::chrono::steady_clock::now();
  const std::string& seq_dir = sequence.dir();
  io::AtomicDirectory dir(out, pipeline::run_files::kSceneGraph);
  if (!quiet)
    std::fprintf(stderr, "run: %s, %zu scans, %s\n", seq_dir.c_str(), sequence.size(),
                 odometry.estimate ? "LiDAR odometry from the scans" : "the input's odometry");
  pipeline::Pipeline slam(config);
  app::Progress progress("run", quiet);
  pipeline::RunCallbacks callbacks;
  std::optional<SegmentationImages> images;
  if (segmentations) images.emplace((fs::path(dir.path()) / pipeline::run_files::kSegmentations).string());
  callbacks.progress = [&](std::size_t done, std::size_t total) {
    progress.update(done, total);
    if (images) images->write_new(slam);
  };
  callbacks.warning = [](const std::string& w) {
    std::fprintf(stderr, "tsgraphs: warning: %s\n", w.c_str());
  };
  if (!quiet)
    callbacks.note = [](const std::string& n) { std::fprintf(stderr, "run: platform: %s\n", n.c_str()); };
  pipeline::RunInfo info = pipeline::run_sequence(sequence, slam, callbacks, odometry);
  info.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (slam.graph().keyframes().empty())
    throw input_error(seq_dir, 0,
                      sequence.size() == 0
                          ? "holds no scan; nothing written"
                          : "no scan could be used: all " + std::to_string(sequence.size()) +
                                " were skipped (the warnings above say why); nothing written");
  try {
    pipeline::write_run_outputs(slam, info, dir.path());
    if (images) {
      images->write_new(slam);  // the run's last extraction
      images->close();
    }
    // Ground truth for the report comes with a sequence folder only.
    const bool has_truth = dynamic_cast<const io::SequenceReader*>(&sequence) != nullptr;
    report::write_run_report(dir.path(), has_truth ? seq_dir : "", fs::path(out).filename().string());
  } catch (const InputError& e) {
    throw dir.named_as_final(e);
  }
  dir.commit();
  if (!quiet) {
    std::fprintf(
        stderr,
        "run: %zu keyframes, %zu planes, %zu loop closures, %zu optimisations; %.1f s (%.1fx real time)\n",
        slam.graph().keyframes().size(), slam.graph().planes().size(), slam.graph().loop_edges().size(),
        slam.optimizations().size(), info.wall_time_s,
        info.wall_time_s > 0 ? info.sequence_duration_s / info.wall_time_s : 0.0);
    std::fprintf(stderr, "run: wrote %s\n", out.c_str());
  }
}

eval::Metrics evaluate(const std::string& run_dir, const std::string& seq_dir, bool quiet, bool print) {
  eval::EvalOptions options;
  options.run_dir = run_dir;
  options.seq_dir = seq_dir;
  const eval::Metrics metrics = eval::evaluate_run(options);
  const std::string metrics_text = eval::metrics_json(metrics);
  // The report gets the metrics table (and the ground truth when the sequence is given).
  const report::RunReportFiles report = report::run_report_files(
      run_dir, seq_dir, fs::weakly_canonical(run_dir).filename().string(), metrics_text);
  // Everything is made before anything is written, and metrics.json is written last: a failed
  // eval leaves the run folder as it was, an earlier metrics.json and report included.
  const fs::path dir(run_dir);
  const fs::path birdseye = dir / report::kBirdseyeFile, html = dir / report::kReportFile;
  const fs::path metrics_file = dir / pipeline::run_files::kMetrics;
  for (const fs::path& p : {birdseye, html, metrics_file}) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) throw input_error(p.string(), 0, "is a folder; eval writes a file there");
  }
  io::write_file_atomic(birdseye.string(), report.birdseye_svg);
  io::write_file_atomic(html.string(), report.report_html);
  io::write_file_atomic(metrics_file.string(), metrics_text);
  if (print) std::printf("%s", eval::metrics_table(metrics).c_str());
  if (!quiet)
    std::fprintf(stderr, "eval: wrote %s\n", (fs::path(run_dir) / pipeline::run_files::kMetrics).c_str());
  return metrics;
}

eval::Consistency compare(const std::string& run_a, const std::string& run_b, bool quiet, bool print) {
  const eval::Consistency c = eval::compare_runs(run_a, run_b);
  const std::string out = (fs::path(run_a) / "comparison.json").string();
  io::write_file_atomic(out, eval::comparison_json(c, run_a, run_b));
  const auto figure = [](const std::optional<double>& v) {
    if (!v) return std::string("-");
    char text[32];
    std::snprintf(text, sizeof(text), "%.2f", *v);
    return std::string(text);
  };
  if (print)
    std::printf("rooms of %s against %s: %d / %d rooms, %d paired, f_re %.2f, DCS %s, d_center %s m\n",
                run_a.c_str(), run_b.c_str(), c.N1st, c.N2nd, c.N_re, c.f_re, figure(c.dcs).c_str(),
                figure(c.d_center).c_str());
  if (!quiet) std::fprintf(stderr, "eval: wrote %s\n", out.c_str());
  return c;
}

}  // namespace tsgraphs::app
