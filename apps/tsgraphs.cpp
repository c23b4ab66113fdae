// tsgraphs: the command line. A thin front end over the library; see docs/DESIGN.md for the
// contract (commands, options, exit status 0 / 2 bad input / 1 internal error). Each command's
// options and call are in apps/cli/, one file per command.
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <malloc.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <thread>
#include <vector>

#include "cli/command.hpp"
#include "cli_checks.hpp"
#include "tsgraphs/core/error.hpp"

using namespace tsgraphs;
using namespace tsgraphs::app;

namespace {

// More worker threads than any machine has cores is a typo.
constexpr long long kMaxThreads = 1024;

// A run allocates and frees about a megabyte per scan (the raw scan as read). By default glibc
// hands blocks this large back to the system when they are freed and faults them in again for
// the next scan; kept in the process, they are reused (built-in atrium: system time 2.2 -> 1.3 s,
// peak memory ~10 MB more).
void keep_freed_memory() {
  constexpr int kKeepFreed = 1 << 30;    // bytes: blocks below this come from the heap and stay
  constexpr int kHeapGrowth = 64 << 20;  // bytes: the heap grows by this much at a time
  mallopt(M_MMAP_THRESHOLD, kKeepFreed);
  mallopt(M_TRIM_THRESHOLD, kKeepFreed);
  mallopt(M_TOP_PAD, kHeapGrowth);
}

std::vector<cli::Command> add_commands(CLI::App& app, const cli::GlobalOptions& global) {
  return {
      cli::add_simulate(app, global),    cli::add_generate(app, global),   cli::add_import_map(app, global),
      cli::add_segment_map(app, global), cli::add_draw_scene(app, global), cli::add_run(app, global),
      cli::add_convert(app, global),     cli::add_eval(app, global),       cli::add_bag_info(app, global),
      cli::add_export(app, global),      cli::add_demo(app, global),       cli::add_suite(app, global),
      cli::add_params(app, global)};
}

/// The chosen command run; errors printed in one line with the exit status of DESIGN.md.
int run_chosen(const std::vector<cli::Command>& commands) {
  try {
    for (const cli::Command& command : commands)
      if (*command.chosen) return command.run();
  } catch (const InputError& e) {
    std::fprintf(stderr, "tsgraphs: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tsgraphs: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  CLI::App app{"tsgraphs: traversability-aware situational graphs from indoor 3-D LiDAR"};
  app.require_subcommand(1);
  app.fallthrough();  // --quiet and --threads also after the subcommand
  app.set_version_flag("--version", "tsgraphs " TSGRAPHS_VERSION);
  cli::GlobalOptions global;
  app.add_flag("-q,--quiet", global.quiet, "no progress output");
  app.add_option("--threads", global.threads, "worker threads (default: all cores)")
      ->check(whole_number_in(0, kMaxThreads));
  const std::vector<cli::Command> commands = add_commands(app, global);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "tsgraphs: error: %s\n", e.what());
    return 2;
  }
  spdlog::set_level(global.quiet ? spdlog::level::warn : spdlog::level::info);
  const int threads = global.threads > 0
                          ? global.threads
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  tbb::global_control threads_control(tbb::global_control::max_allowed_parallelism, threads);
  return run_chosen(commands);
}
