// `tsgraphs export`: a run folder as an MCAP file for Foxglove.
#include <memory>
#include <string>

#include "command.hpp"
#include "commands.hpp"

namespace tsgraphs::app::cli {

Command add_export(CLI::App& app, const GlobalOptions& global) {
  struct Options {
    std::string run;
    std::string mcap;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("export",
                                 "a run folder as an MCAP file Foxglove opens: trajectory, map, walls, "
                                 "traversable nodes, rooms as they were extracted");
  cmd->add_option("RUN_DIR", opt->run, "run folder")->required();
  cmd->add_option("--mcap", opt->mcap, "MCAP file to write")->required();
  return {cmd, [opt, &global] {
            export_mcap(opt->run, opt->mcap, global.quiet);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
