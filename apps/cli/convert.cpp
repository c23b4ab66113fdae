// `tsgraphs convert`: a folder of scans or a bag to a sequence folder.
#include <memory>

#include "command.hpp"
#include "commands.hpp"
#include "scan_source.hpp"

namespace tsgraphs::app::cli {

Command add_convert(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<ScanSourceOptions>();
  auto* cmd =
      app.add_subcommand("convert", "a folder of scans or a bag to a sequence folder (docs/scene-format.md)");
  add_scan_source_options(*cmd, *opt, "sequence folder to write");
  return {cmd, [opt, &global] {
            const ScanSource source = open_scan_source(*opt, "convert", global.quiet);
            convert(*source.sequence, opt->out, source.odometry, source.config, global.quiet);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
