// `tsgraphs run`: the SLAM pipeline, scans in, a run folder out.
#include <memory>
#include <string>

#include "command.hpp"
#include "commands.hpp"
#include "scan_source.hpp"

namespace tsgraphs::app::cli {

Command add_run(CLI::App& app, const GlobalOptions& global) {
  struct Options {
    ScanSourceOptions source;
    std::string free_space;    ///< overrides room_layer.free_space_method when set
    std::string room_trigger;  ///< overrides room_layer.room_trigger when set
    bool segmentations = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "run", "the SLAM pipeline: a sequence folder, a folder of scans or a bag in, a run folder out");
  add_scan_source_options(*cmd, opt->source, "run folder to write");
  cmd->add_option(
         "--free-space", opt->free_space,
         "traversable (TS-graphs, default) or esdf (S-Graphs+); overrides room_layer.free_space_method")
      ->check(CLI::IsMember(room_layer::kFreeSpaceMethods.words()));
  cmd->add_option("--room-trigger", opt->room_trigger,
                  "flush (TS-graphs, default) or timer (S-Graphs+); overrides room_layer.room_trigger")
      ->check(CLI::IsMember(room_layer::kRoomTriggers.words()));
  cmd->add_flag("--segmentations", opt->segmentations,
                "also write each segmentation of the room layer (TS-graphs) as a label image, with "
                "index.csv, in OUT/segmentations/");
  return {cmd, [opt, &global] {
            ScanSource source = open_scan_source(opt->source, "run", global.quiet);
            room_layer::RoomLayerConfig& layer = source.config.rooms.layer;
            if (!opt->free_space.empty())
              layer.free_space_method = *room_layer::kFreeSpaceMethods.parse(opt->free_space);
            if (!opt->room_trigger.empty())
              layer.room_trigger = *room_layer::kRoomTriggers.parse(opt->room_trigger);
            run(*source.sequence, opt->source.out, source.config, global.quiet, source.odometry,
                opt->segmentations);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
