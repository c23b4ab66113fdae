// `tsgraphs generate`: a procedural building as a scene file.
#include <memory>

#include "cli_checks.hpp"
#include "command.hpp"
#include "scene_commands.hpp"

namespace tsgraphs::app::cli {

Command add_generate(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<GenerateOptions>();
  auto* cmd = app.add_subcommand(
      "generate", "a procedural building with ground-truth rooms and a survey path, as a scene file");
  cmd->add_option("--style", opt->style,
                  "office, atrium, library, open_plan, irregular, multi_storey or mixed")
      ->required();
  cmd->add_option("--seed", opt->seed, "the building's seed (the same seed, the same building)")
      ->check(seed_check())
      ->capture_default_str();
  cmd->add_option("--out", opt->out, "scene file to write")->required();
  cmd->add_option("--laps", opt->laps, "laps of the survey path")->check(laps_check())->capture_default_str();
  cmd->add_option("--size", opt->size,
                  "scales the building's extent, (0, 1] (small buildings for quick tests)")
      ->capture_default_str();
  cmd->add_option("--people", opt->people,
                  "people walking stretches of the survey path, there and back (0-50)")
      ->capture_default_str();
  cmd->add_flag("--realistic", opt->realistic,
                "as real floors are: furniture and clutter against the walls, open door leaves, windows, "
                "irregular rooms, rows of small offices");
  return {cmd, [opt, &global] {
            opt->quiet = global.quiet;
            generate(*opt);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
