// `tsgraphs simulate`: a scene into a LiDAR sequence folder or a bag.
#include <memory>
#include <string>

#include "cli_checks.hpp"
#include "command.hpp"
#include "commands.hpp"
#include "tsgraphs/core/error.hpp"

namespace tsgraphs::app::cli {

namespace {

struct SimulateOptions {
  std::string scene;
  std::string out;
  long long seed = -1;  ///< -1: the scene's
  int laps = 0;         ///< 0: the scene's
  std::string bag;
  std::string bag_format = "auto";  ///< ros1, ros2-mcap, ros2-sqlite or auto (by extension)
  std::string compression;          ///< "" for the format's default
};

}  // namespace

Command add_simulate(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<SimulateOptions>();
  auto* cmd = app.add_subcommand("simulate", "turn a scene into a LiDAR sequence folder");
  cmd->add_option("SCENE", opt->scene, "scene YAML file or built-in scene name")->required();
  cmd->add_option("--out", opt->out, "sequence folder to write (with --bag: kept beside the bag)");
  cmd->add_option(
      "--bag", opt->bag,
      "write the sequence as a bag (.bag ROS1, .mcap or .db3 rosbag2): /points, /odom, /tf_static, "
      "/groundtruth");
  cmd->add_option("--bag-format", opt->bag_format,
                  "ros1, ros2-mcap, ros2-sqlite, or auto: by --bag's extension")
      ->check(CLI::IsMember({"auto", "ros1", "ros2-mcap", "ros2-sqlite"}))
      ->capture_default_str();
  cmd->add_option(
         "--compression", opt->compression,
         "bag compression: ros1 none, bz2 or lz4 (default lz4); ros2-mcap chunks none, lz4 or zstd (default "
         "zstd); "
         "ros2 folders also zstd-file or zstd-message, rosbag2's own (default none for ros2-sqlite)")
      ->check(CLI::IsMember({"none", "bz2", "lz4", "zstd", "zstd-file", "zstd-message"}));
  cmd->add_option("--seed", opt->seed, "random seed (default: the scene's)")->check(seed_check());
  cmd->add_option("--laps", opt->laps, "laps of the path (default: the scene's)")->check(laps_check());
  return {cmd, [opt, &global] {
            const scene::Scene scene = load_and_warn(opt->scene);
            const std::uint64_t seed = opt->seed >= 0 ? static_cast<std::uint64_t>(opt->seed) : scene.seed;
            if (opt->bag.empty()) {
              if (opt->out.empty()) throw input_error("simulate", 0, "give --out SEQ_DIR or --bag FILE.bag");
              simulate(scene, opt->out, seed, opt->laps, global.quiet);
            } else {
              simulate_bag(scene, opt->bag, opt->out, seed, opt->laps, opt->bag_format, opt->compression,
                           global.quiet);
            }
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
