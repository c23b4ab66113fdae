// `tsgraphs params`: every parameter with its default (or a file's value) and what it does.
#include <cstdio>
#include <memory>
#include <string>

#include "command.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"

namespace tsgraphs::app::cli {

Command add_params(CLI::App& app, const GlobalOptions&) {
  auto config = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand(
      "params", "print every parameter with its default and what it does (config/params.yaml is this)");
  cmd->add_option("--config", *config, "show this parameter file's values in place of the defaults");
  return {cmd, [config] {
            const pipeline::PipelineConfig values =
                config->empty() ? pipeline::PipelineConfig{} : pipeline::load_pipeline_config(*config);
            std::fputs(pipeline::documented_pipeline_config(values).c_str(), stdout);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
