// tsgraphs: the command line. A thin front end over the library; see docs/DESIGN.md for the
// contract (commands, options, exit status 0 / 2 bad input / 1 internal error).
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <malloc.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include "cli_checks.hpp"
#include "commands.hpp"
#include "demo.hpp"
#include "output_checks.hpp"
#include "scene_commands.hpp"
#include "segment_map.hpp"
#include "suite.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"

using namespace tsgraphs;
using namespace tsgraphs::app;

namespace {

// Bounds of --sensor-to-base: a mount this far from the base, or a quaternion this short, is a typo.
constexpr double kMaxMountOffset = 100.0;  // m
constexpr double kMinQuaternionNorm = 1e-3;
// More worker threads than any machine has cores is a typo.
constexpr long long kMaxThreads = 1024;
// Seeds of the demo: one seed is about four minutes on 2 cores.
constexpr long long kMaxDemoSeeds = 100;

struct Options {
  bool quiet = false;
  int threads = 0;
  std::string scene;
  std::string out;
  long long seed = -1;
  int laps = 0;
  std::string seq;
  std::string config;
  std::string free_space;              ///< overrides room_layer.free_space_method when set
  std::string room_trigger;            ///< overrides room_layer.room_trigger when set
  std::string against;                 ///< eval: the run to compare with
  io::ScanFolderOptions folder;        ///< run: a folder of scans instead of a sequence folder
  io::BagOptions bag;                  ///< run: a ROS1 bag instead of a sequence folder
  std::vector<double> sensor_to_base;  ///< run: x y z qx qy qz qw
  std::string odometry = "auto";       ///< run, convert: auto, input or lidar
  std::string bag_out;                 ///< simulate: write a bag
  std::string mcap_out;                ///< export: the Foxglove MCAP file
  std::string bag_format = "auto";  ///< simulate --bag: ros1, ros2-mcap, ros2-sqlite or auto (by extension)
  std::string compression;          ///< simulate --bag: "" for the format's default
  DemoOptions demo;
  GenerateOptions generate;
  ImportMapOptions import_map;
  SegmentMapOptions segment_map;
  SuiteOptions suite;
};

std::uint64_t seed_for(const scene::Scene& scene, long long cli_seed) {
  return cli_seed >= 0 ? static_cast<std::uint64_t>(cli_seed) : scene.seed;
}

}  // namespace

int main(int argc, char** argv) {
  // A run allocates and frees about a megabyte per scan (the raw scan as read). By default
  // glibc hands blocks this large back to the system when they are freed and faults them in
  // again for the next scan; kept in the process, they are reused (built-in atrium: system
  // time 2.2 -> 1.3 s, peak memory ~10 MB more).
  constexpr int kKeepFreed = 1 << 30;    // bytes: blocks below this come from the heap and stay
  constexpr int kHeapGrowth = 64 << 20;  // bytes: the heap grows by this much at a time
  mallopt(M_MMAP_THRESHOLD, kKeepFreed);
  mallopt(M_TRIM_THRESHOLD, kKeepFreed);
  mallopt(M_TOP_PAD, kHeapGrowth);
  CLI::App app{"tsgraphs: traversability-aware situational graphs from indoor 3-D LiDAR"};
  app.require_subcommand(1);
  app.fallthrough();  // --quiet and --threads also after the subcommand
  app.set_version_flag("--version", "tsgraphs " TSGRAPHS_VERSION);
  Options opt;
  app.add_flag("-q,--quiet", opt.quiet, "no progress output");
  app.add_option("--threads", opt.threads, "worker threads (default: all cores)")
      ->check(whole_number_in(0, kMaxThreads));

  auto* simulate_cmd = app.add_subcommand("simulate", "turn a scene into a LiDAR sequence folder");
  simulate_cmd->add_option("SCENE", opt.scene, "scene YAML file or built-in scene name")->required();
  simulate_cmd->add_option("--out", opt.out, "sequence folder to write (with --bag: kept beside the bag)");
  simulate_cmd->add_option(
      "--bag", opt.bag_out,
      "write the sequence as a bag (.bag ROS1, .mcap or .db3 rosbag2): /points, /odom, /tf_static, "
      "/groundtruth");
  simulate_cmd
      ->add_option("--bag-format", opt.bag_format,
                   "ros1, ros2-mcap, ros2-sqlite, or auto: by --bag's extension")
      ->check(CLI::IsMember({"auto", "ros1", "ros2-mcap", "ros2-sqlite"}))
      ->capture_default_str();
  simulate_cmd
      ->add_option(
          "--compression", opt.compression,
          "bag compression: ros1 none, bz2 or lz4 (default lz4); ros2-mcap chunks none, lz4 or zstd (default "
          "zstd); "
          "ros2 folders also zstd-file or zstd-message, rosbag2's own (default none for ros2-sqlite)")
      ->check(CLI::IsMember({"none", "bz2", "lz4", "zstd", "zstd-file", "zstd-message"}));
  simulate_cmd->add_option("--seed", opt.seed, "random seed (default: the scene's)")->check(seed_check());
  simulate_cmd->add_option("--laps", opt.laps, "laps of the path (default: the scene's)")
      ->check(laps_check());

  auto* generate_cmd = app.add_subcommand(
      "generate", "a procedural building with ground-truth rooms and a survey path, as a scene file");
  generate_cmd
      ->add_option("--style", opt.generate.style,
                   "office, atrium, library, open_plan, irregular, multi_storey or mixed")
      ->required();
  generate_cmd
      ->add_option("--seed", opt.generate.seed, "the building's seed (the same seed, the same building)")
      ->check(seed_check())
      ->capture_default_str();
  generate_cmd->add_option("--out", opt.generate.out, "scene file to write")->required();
  generate_cmd->add_option("--laps", opt.generate.laps, "laps of the survey path")
      ->check(laps_check())
      ->capture_default_str();
  generate_cmd
      ->add_option("--size", opt.generate.size,
                   "scales the building's extent, (0, 1] (small buildings for quick tests)")
      ->capture_default_str();
  generate_cmd
      ->add_option("--people", opt.generate.people,
                   "people walking stretches of the survey path, there and back (0-50)")
      ->capture_default_str();
  generate_cmd->add_flag(
      "--realistic", opt.generate.realistic,
      "as real floors are: furniture and clutter against the walls, open door leaves, windows, "
      "irregular rooms, rows of small offices");

  auto* import_cmd = app.add_subcommand("import-map",
                                        "a ROS map_server occupancy map (PGM or PNG and its YAML) as a scene "
                                        "file: walls, rooms, a survey path");
  import_cmd->add_option("MAP", opt.import_map.map, "the map's YAML file (map_server format)")->required();
  import_cmd
      ->add_option("--out", opt.import_map.out,
                   "scene file to write; its walls go beside it as <stem>_walls.pcd")
      ->required();
  import_cmd->add_option(
      "--rooms", opt.import_map.rooms,
      "ground-truth rooms: a PNG or PGM of the map's size, rooms white, doors closed by black lines "
      "(the IPA room-segmentation benchmark's convention)");
  import_cmd->add_option("--ceiling", opt.import_map.ceiling, "ceiling and wall height, m")
      ->capture_default_str();
  import_cmd
      ->add_option("--clearance", opt.import_map.clearance,
                   "m the survey path keeps from occupied and unknown cells")
      ->capture_default_str();
  import_cmd->add_option("--laps", opt.import_map.laps, "laps of the survey path")
      ->check(laps_check())
      ->capture_default_str();
  import_cmd
      ->add_option("--sensor", opt.import_map.sensor, "sensor preset: os1-64, os0-128, vlp-16 or hesai-xt32")
      ->capture_default_str();
  import_cmd->add_option("--mount-height", opt.import_map.mount_height, "sensor above the floor, m")
      ->capture_default_str();

  auto* segment_cmd = app.add_subcommand(
      "segment-map",
      "the room segmentation of a 2-D occupancy map: one colour per room out, scored against true rooms");
  segment_cmd->add_option("MAP", opt.segment_map.map, "the map's YAML file (map_server format)")->required();
  segment_cmd
      ->add_option("--out", opt.segment_map.out,
                   "label image to write (PNG: one colour per room, black none)")
      ->required();
  segment_cmd->add_option(
      "--rooms", opt.segment_map.rooms,
      "true rooms: a label image of the map's size (one colour per room, or IPA: white rooms, black door "
      "lines): prints the IPA figures and room F1");
  segment_cmd->add_option("--config", opt.segment_map.config,
                          "parameter file (room_segmentation, map_walls and free_space.lambda_th apply)");
  segment_cmd->add_option("--metrics", opt.segment_map.metrics, "JSON file to write the figures to");

  auto* draw_cmd = app.add_subcommand("draw-scene", "bird's-eye SVG of a scene and its path");
  draw_cmd->add_option("SCENE", opt.scene, "scene YAML file or built-in scene name")->required();
  draw_cmd->add_option("--out", opt.out, "SVG file to write")->required();

  // The scan sources `run` and `convert` read: a sequence folder, a folder of scans, or a bag.
  const auto add_source_options = [&opt](CLI::App* cmd) {
    cmd->add_option("SEQ_DIR", opt.seq,
                    "sequence folder (docs/scene-format.md), or a folder of .pcd / KITTI .bin scans (with a "
                    "pose file, or none)");
    cmd->add_option("--scans", opt.folder.scans,
                    "glob of scan files (.pcd or KITTI .bin) instead of SEQ_DIR");
    cmd->add_option("--poses", opt.folder.poses,
                    "pose file of the scans, one per scan (default: poses.txt or odom.txt beside them)");
    cmd->add_option("--pose-format", opt.folder.pose_format,
                    "tum, kitti (3x4 rows) or auto (by the field count)")
        ->check(CLI::IsMember({"tum", "kitti", "auto"}))
        ->capture_default_str();
    cmd->add_option("--times", opt.folder.times,
                    "times of the scans, one a line (default: times.txt beside them, or the TUM stamps)");
    // An hour between scans is no sweep rate: a typo (1e308 overflowed the scan stamps).
    cmd->add_option("--scan-period", opt.folder.scan_period, "s between scans when nothing gives their times")
        ->check(number_in(1e-6, 3600.0))
        ->capture_default_str();
    cmd->add_option("--bag", opt.bag.bag,
                    "a ROS1 bag or a rosbag2 recording (folder, .db3 or .mcap) instead of SEQ_DIR (see "
                    "bag-info for its topics)");
    cmd->add_option("--points-topic", opt.bag.points_topic, "bag: the sensor_msgs/PointCloud2 topic");
    cmd->add_option("--odom-topic", opt.bag.odom_topic,
                    "bag: the nav_msgs/Odometry or geometry_msgs/PoseStamped topic");
    cmd->add_option("--odom-tum", opt.bag.odom_tum, "bag: odometry of the base from a TUM file instead");
    cmd->add_option(
           "--sensor-to-base", opt.sensor_to_base,
           "x y z qx qy qz qw of the sensor in the base frame: a bag's (default: /tf_static, else identity), "
           "and the first pose of scans without poses (default: level with the floor under the first scan)")
        ->expected(7);
    cmd->add_option(
           "--odometry", opt.odometry,
           "auto: the input's poses, or LiDAR odometry from the scans when it has none; input; lidar")
        ->check(CLI::IsMember({"auto", "input", "lidar"}))
        ->capture_default_str();
    cmd->add_option("--config", opt.config, "parameter file (config/params.yaml lists every key)");
  };
  auto* run_cmd = app.add_subcommand(
      "run", "the SLAM pipeline: a sequence folder, a folder of scans or a bag in, a run folder out");
  add_source_options(run_cmd);
  run_cmd->add_option("--out", opt.out, "run folder to write")->required();
  run_cmd
      ->add_option(
          "--free-space", opt.free_space,
          "traversable (TS-graphs, default) or esdf (S-Graphs+); overrides room_layer.free_space_method")
      ->check(CLI::IsMember({"traversable", "esdf"}));
  run_cmd
      ->add_option("--room-trigger", opt.room_trigger,
                   "flush (TS-graphs, default) or timer (S-Graphs+); overrides room_layer.room_trigger")
      ->check(CLI::IsMember({"flush", "timer"}));

  auto* convert_cmd =
      app.add_subcommand("convert", "a folder of scans or a bag to a sequence folder (docs/scene-format.md)");
  add_source_options(convert_cmd);
  convert_cmd->add_option("--out", opt.out, "sequence folder to write")->required();

  auto* eval_cmd =
      app.add_subcommand("eval", "metrics of a run: metrics.json and a table; or two runs' rooms compared");
  eval_cmd->add_option("RUN_DIR", opt.out, "run folder written by `tsgraphs run`")->required();
  auto* seq_opt = eval_cmd->add_option("--seq", opt.seq, "the sequence folder it ran on (ground truth)");
  eval_cmd
      ->add_option("--against", opt.against,
                   "another run folder: pair its final rooms with RUN_DIR's (f_re, DCS, d_center) into "
                   "RUN_DIR/comparison.json")
      ->excludes(seq_opt);

  auto* bag_info_cmd = app.add_subcommand(
      "bag-info", "topics of a ROS1 bag or a rosbag2 recording: types, message counts, rates");
  bag_info_cmd->add_option("BAG", opt.bag.bag, "the .bag file, or the rosbag2 folder, .db3 or .mcap file")
      ->required();

  auto* export_cmd =
      app.add_subcommand("export",
                         "a run folder as an MCAP file Foxglove opens: trajectory, map, walls, "
                         "traversable nodes, rooms as they were extracted");
  export_cmd->add_option("RUN_DIR", opt.out, "run folder")->required();
  export_cmd->add_option("--mcap", opt.mcap_out, "MCAP file to write")->required();

  auto* demo_cmd = app.add_subcommand(
      "demo", "TS-graphs, S-Graphs+ and the ablations on simulated atrium and office: Table 1 and a report");
  demo_cmd->add_option("--out", opt.demo.out, "output folder")->capture_default_str();
  demo_cmd->add_option("--seeds", opt.demo.seeds, "seeds 1..N per scene")
      ->check(whole_number_in(1, kMaxDemoSeeds))
      ->capture_default_str();
  demo_cmd->add_option("--scenes", opt.demo.scenes, "built-in scene names or scene files")
      ->capture_default_str();
  demo_cmd
      ->add_option("--platform-height", opt.demo.platform_height,
                   "sensor height of the second platform compared on the first scene (m; 0: no comparison)")
      ->check(number_in(0.0, limits::kMaxPlatformHeight))
      ->capture_default_str();

  auto* suite_cmd = app.add_subcommand("suite",
                                       "many cases (generated buildings, imported maps, scenes, sequences) "
                                       "run by the same rules, and their tables");
  suite_cmd->add_option("SUITE", opt.suite.suite, "suite file (docs/suite.md)");
  suite_cmd->add_option("--out", opt.suite.out, "suite folder (resumed when it holds an earlier run)");
  suite_cmd
      ->add_option("--jobs", opt.suite.jobs, "cases at once, each a child process with cores / N threads")
      ->check(whole_number_in(1, kMaxSuiteJobs))
      ->capture_default_str();
  suite_cmd->add_flag("--keep-sequences", opt.suite.keep_sequences,
                      "keep each case's simulated sequence (2-9 GB)");
  suite_cmd->add_option(
      "--methods", opt.suite.methods,
      "instead of the suite's methods: ts-graphs, s-graphs-plus, traversable-timer, esdf-flush");
  suite_cmd->add_flag("--plan", opt.suite.plan,
                      "write OUT/plan.txt, one command per case (GNU parallel, Slurm), run nothing");
  auto* collect_opt =
      suite_cmd
          ->add_option("--collect", opt.suite.collect,
                       "build the tables from the cases that finished: of DIR, or of --out without a value")
          ->expected(0, 1);
  suite_cmd->add_option("--case", opt.suite.case_id, "run this case only (the commands of --plan)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "tsgraphs: error: %s\n", e.what());
    return 2;
  }
  spdlog::set_level(opt.quiet ? spdlog::level::warn : spdlog::level::info);
  const int threads =
      opt.threads > 0 ? opt.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  tbb::global_control threads_control(tbb::global_control::max_allowed_parallelism, threads);

  try {
    if (*simulate_cmd) {
      const scene::Scene scene = load_and_warn(opt.scene);
      if (opt.bag_out.empty()) {
        if (opt.out.empty()) throw input_error("simulate", 0, "give --out SEQ_DIR or --bag FILE.bag");
        simulate(scene, opt.out, seed_for(scene, opt.seed), opt.laps, opt.quiet);
      } else {
        simulate_bag(scene, opt.bag_out, opt.out, seed_for(scene, opt.seed), opt.laps, opt.bag_format,
                     opt.compression, opt.quiet);
      }
    } else if (*generate_cmd) {
      opt.generate.quiet = opt.quiet;
      generate(opt.generate);
    } else if (*import_cmd) {
      opt.import_map.quiet = opt.quiet;
      import_map(opt.import_map);
    } else if (*segment_cmd) {
      opt.segment_map.quiet = opt.quiet;
      segment_map(opt.segment_map);
    } else if (*bag_info_cmd) {
      print_bag_info(opt.bag.bag);
    } else if (*export_cmd) {
      export_mcap(opt.out, opt.mcap_out, opt.quiet);
    } else if (*draw_cmd) {
      draw_scene(load_and_warn(opt.scene), opt.out, opt.quiet);
    } else if (*run_cmd || *convert_cmd) {
      const int sources = int(!opt.seq.empty()) + int(!opt.folder.scans.empty()) + int(!opt.bag.bag.empty());
      if (sources != 1)
        throw input_error(*run_cmd ? "run" : "convert", 0, "give one of SEQ_DIR, --scans GLOB or --bag FILE");
      check_output_apart("--out", opt.out,
                         {opt.seq, opt.folder.scans, opt.folder.poses, opt.folder.times, opt.bag.bag,
                          opt.bag.odom_tum, opt.config});
      std::optional<Pose3> mount;
      if (!opt.sensor_to_base.empty()) {
        const auto& v = opt.sensor_to_base;
        // A mount farther than kMaxMountOffset from the base, or a rotation that is not one, is a typo.
        const bool finite = std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
        if (!finite || Eigen::Vector3d(v[0], v[1], v[2]).norm() > kMaxMountOffset)
          throw input_error("--sensor-to-base", 0, "x y z must be finite and within 100 m of the base");
        if (!(Eigen::Vector4d(v[3], v[4], v[5], v[6]).norm() > kMinQuaternionNorm))
          throw input_error("--sensor-to-base", 0,
                            "qx qy qz qw must be a rotation (a quaternion of norm about 1)");
        mount = Pose3::Identity();
        mount->translation() = Eigen::Vector3d(v[0], v[1], v[2]);
        mount->linear() = Eigen::Quaterniond(v[6], v[3], v[4], v[5]).normalized().toRotationMatrix();
      }
      std::unique_ptr<io::ScanSequence> sequence;
      if (!opt.bag.bag.empty()) {
        opt.bag.sensor_to_base = mount;
        OpenedBag bag = open_bag(opt.bag, opt.quiet);
        if (bag.mount) mount = bag.mount;
        sequence = std::move(bag.sequence);
      } else {
        opt.folder.folder = opt.seq;
        sequence = open_sequence(opt.folder);
        if (!opt.sensor_to_base.empty() && !sequence->info().odometry.empty())
          throw input_error(
              sequence->dir(), 0,
              "has poses of the sensor: --sensor-to-base is for bags and for scans without poses");
      }
      pipeline::PipelineConfig config =
          opt.config.empty() ? pipeline::PipelineConfig{} : pipeline::load_pipeline_config(opt.config);
      const pipeline::OdometryOptions odometry =
          choose_odometry(*sequence, opt.odometry, mount, config.floor_levelling, opt.quiet);
      if (*convert_cmd) {
        convert(*sequence, opt.out, odometry, config, opt.quiet);
      } else {
        if (!opt.free_space.empty()) config.rooms.layer.free_space_method = opt.free_space;
        if (!opt.room_trigger.empty()) config.rooms.layer.room_trigger = opt.room_trigger;
        run(*sequence, opt.out, config, opt.quiet, odometry);
      }
    } else if (*eval_cmd) {
      if (opt.against.empty()) {
        evaluate(opt.out, opt.seq, opt.quiet);
      } else {
        compare(opt.out, opt.against, opt.quiet);
      }
    } else if (*demo_cmd) {
      opt.demo.quiet = opt.quiet;
      demo(opt.demo);
    } else if (*suite_cmd) {
      opt.suite.quiet = opt.quiet;
      opt.suite.threads = opt.threads;
      opt.suite.collect_flag = collect_opt->count() > 0;
      return suite(opt.suite);
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
