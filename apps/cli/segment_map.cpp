// `tsgraphs segment-map`: the room segmentation of a 2-D occupancy map.
#include "segment_map.hpp"

#include <memory>

#include "command.hpp"

namespace tsgraphs::app::cli {

Command add_segment_map(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<SegmentMapOptions>();
  auto* cmd = app.add_subcommand(
      "segment-map",
      "the room segmentation of a 2-D occupancy map: one colour per room out, scored against true rooms");
  cmd->add_option("MAP", opt->map, "the map's YAML file (map_server format)")->required();
  cmd->add_option("--out", opt->out, "label image to write (PNG: one colour per room, black none)")
      ->required();
  cmd->add_option(
      "--rooms", opt->rooms,
      "true rooms: a label image of the map's size (one colour per room, or IPA: white rooms, black "
      "door lines): prints the IPA figures and room F1");
  cmd->add_option("--config", opt->config,
                  "parameter file (room_segmentation, map_walls and free_space.lambda_th apply)");
  cmd->add_option("--metrics", opt->metrics, "JSON file to write the figures to");
  return {cmd, [opt, &global] {
            opt->quiet = global.quiet;
            segment_map(*opt);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
