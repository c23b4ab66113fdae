// `tsgraphs import-map`: a map_server occupancy map as a scene file.
#include <memory>

#include "cli_checks.hpp"
#include "command.hpp"
#include "scene_commands.hpp"

namespace tsgraphs::app::cli {

Command add_import_map(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<ImportMapOptions>();
  auto* cmd = app.add_subcommand("import-map",
                                 "a ROS map_server occupancy map (PGM or PNG and its YAML) as a scene "
                                 "file: walls, rooms, a survey path");
  cmd->add_option("MAP", opt->map, "the map's YAML file (map_server format)")->required();
  cmd->add_option("--out", opt->out, "scene file to write; its walls go beside it as <stem>_walls.pcd")
      ->required();
  cmd->add_option(
      "--rooms", opt->rooms,
      "ground-truth rooms: a PNG or PGM of the map's size, rooms white, doors closed by black lines "
      "(the IPA room-segmentation benchmark's convention)");
  cmd->add_option("--ceiling", opt->ceiling, "ceiling and wall height, m")->capture_default_str();
  cmd->add_option("--clearance", opt->clearance, "m the survey path keeps from occupied and unknown cells")
      ->capture_default_str();
  cmd->add_option("--laps", opt->laps, "laps of the survey path")->check(laps_check())->capture_default_str();
  cmd->add_option("--sensor", opt->sensor, "sensor preset: os1-64, os0-128, vlp-16 or hesai-xt32")
      ->capture_default_str();
  cmd->add_option("--mount-height", opt->mount_height, "sensor above the floor, m")->capture_default_str();
  return {cmd, [opt, &global] {
            opt->quiet = global.quiet;
            import_map(*opt);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
