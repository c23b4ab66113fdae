// `tsgraphs demo`: the paper's comparison on the built-in scenes.
#include "demo.hpp"

#include <memory>

#include "cli_checks.hpp"
#include "command.hpp"
#include "tsgraphs/core/limits.hpp"

namespace tsgraphs::app::cli {

namespace {
// Seeds of the demo: one seed is about four minutes on 2 cores.
constexpr long long kMaxDemoSeeds = 100;
}  // namespace

Command add_demo(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<DemoOptions>();
  auto* cmd = app.add_subcommand(
      "demo", "TS-graphs, S-Graphs+ and the ablations on simulated atrium and office: Table 1 and a report");
  cmd->add_option("--out", opt->out, "output folder")->capture_default_str();
  cmd->add_option("--seeds", opt->seeds, "seeds 1..N per scene")
      ->check(whole_number_in(1, kMaxDemoSeeds))
      ->capture_default_str();
  cmd->add_option("--scenes", opt->scenes, "built-in scene names or scene files")->capture_default_str();
  cmd->add_option("--platform-height", opt->platform_height,
                  "sensor height of the second platform compared on the first scene (m; 0: no comparison)")
      ->check(number_in(0.0, limits::kMaxPlatformHeight))
      ->capture_default_str();
  return {cmd, [opt, &global] {
            opt->quiet = global.quiet;
            demo(*opt);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
