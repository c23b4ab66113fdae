// `tsgraphs suite`: many cases run by the same rules, and their tables.
#include "suite.hpp"

#include <memory>

#include "cli_checks.hpp"
#include "command.hpp"

namespace tsgraphs::app::cli {

Command add_suite(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<SuiteOptions>();
  auto* cmd = app.add_subcommand("suite",
                                 "many cases (generated buildings, imported maps, scenes, sequences) "
                                 "run by the same rules, and their tables");
  cmd->add_option("SUITE", opt->suite, "suite file (docs/suite.md)");
  cmd->add_option("--out", opt->out, "suite folder (resumed when it holds an earlier run)");
  cmd->add_option("--jobs", opt->jobs, "cases at once, each a child process with cores / N threads")
      ->check(whole_number_in(1, kMaxSuiteJobs))
      ->capture_default_str();
  cmd->add_flag("--keep-sequences", opt->keep_sequences, "keep each case's simulated sequence (2-9 GB)");
  cmd->add_option("--methods", opt->methods,
                  "instead of the suite's methods: ts-graphs, s-graphs-plus, traversable-timer, esdf-flush");
  cmd->add_flag("--plan", opt->plan,
                "write OUT/plan.txt, one command per case (GNU parallel, Slurm), run nothing");
  auto* collect =
      cmd->add_option("--collect", opt->collect,
                      "build the tables from the cases that finished: of DIR, or of --out without a value")
          ->expected(0, 1);
  cmd->add_option("--case", opt->case_id, "run this case only (the commands of --plan)");
  return {cmd, [opt, collect, &global] {
            opt->quiet = global.quiet;
            opt->threads = global.threads;
            opt->collect_flag = collect->count() > 0;
            return suite(*opt);
          }};
}

}  // namespace tsgraphs::app::cli
