// `tsgraphs draw-scene`: a bird's-eye SVG of a scene and its path.
#include <memory>
#include <string>

#include "command.hpp"
#include "commands.hpp"

namespace tsgraphs::app::cli {

Command add_draw_scene(CLI::App& app, const GlobalOptions& global) {
  struct Options {
    std::string scene;
    std::string out;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("draw-scene", "bird's-eye SVG of a scene and its path");
  cmd->add_option("SCENE", opt->scene, "scene YAML file or built-in scene name")->required();
  cmd->add_option("--out", opt->out, "SVG file to write")->required();
  return {cmd, [opt, &global] {
            draw_scene(load_and_warn(opt->scene), opt->out, global.quiet);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
