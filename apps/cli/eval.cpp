// `tsgraphs eval`: a run's metrics against its ground truth, or two runs' rooms compared.
#include <memory>
#include <string>

#include "command.hpp"
#include "commands.hpp"

namespace tsgraphs::app::cli {

Command add_eval(CLI::App& app, const GlobalOptions& global) {
  struct Options {
    std::string run;
    std::string seq;
    std::string against;  ///< the run to compare with
  };
  auto opt = std::make_shared<Options>();
  auto* cmd =
      app.add_subcommand("eval", "metrics of a run: metrics.json and a table; or two runs' rooms compared");
  cmd->add_option("RUN_DIR", opt->run, "run folder written by `tsgraphs run`")->required();
  auto* seq = cmd->add_option("--seq", opt->seq, "the sequence folder it ran on (ground truth)");
  cmd->add_option("--against", opt->against,
                  "another run folder: pair its final rooms with RUN_DIR's (f_re, DCS, d_center) into "
                  "RUN_DIR/comparison.json")
      ->excludes(seq);
  return {cmd, [opt, &global] {
            if (opt->against.empty()) {
              evaluate(opt->run, opt->seq, global.quiet);
            } else {
              compare(opt->run, opt->against, global.quiet);
            }
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
