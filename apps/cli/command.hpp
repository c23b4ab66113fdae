#pragma once
/// The `tsgraphs` program's commands as the command line declares them: each file of apps/cli/
/// adds one command's options to the parser and returns what runs it once the line is parsed.
#include <CLI/CLI.hpp>
#include <functional>

namespace tsgraphs::app::cli {

/// Options before or after any command.
struct GlobalOptions {
  bool quiet = false;
  int threads = 0;  ///< worker threads; 0: all cores
};

/// A command added to the parser: `chosen` is its subcommand, `run` runs it with the parsed
/// options and returns the exit status (InputError for bad input, as every command).
struct Command {
  CLI::App* chosen = nullptr;
  std::function<int()> run;
};

Command add_simulate(CLI::App& app, const GlobalOptions& global);
Command add_generate(CLI::App& app, const GlobalOptions& global);
Command add_import_map(CLI::App& app, const GlobalOptions& global);
Command add_segment_map(CLI::App& app, const GlobalOptions& global);
Command add_draw_scene(CLI::App& app, const GlobalOptions& global);
Command add_run(CLI::App& app, const GlobalOptions& global);
Command add_convert(CLI::App& app, const GlobalOptions& global);
Command add_eval(CLI::App& app, const GlobalOptions& global);
Command add_bag_info(CLI::App& app, const GlobalOptions& global);
Command add_export(CLI::App& app, const GlobalOptions& global);
Command add_demo(CLI::App& app, const GlobalOptions& global);
Command add_suite(CLI::App& app, const GlobalOptions& global);
Command add_params(CLI::App& app, const GlobalOptions& global);

}  // namespace tsgraphs::app::cli
