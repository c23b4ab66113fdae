// The commands that make scenes (scene_commands.hpp).
#include "scene_commands.hpp"

#include <cstdio>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/scene/generator.hpp"

namespace tsgraphs::app {

void generate(const GenerateOptions& options) {
  if (options.out.empty()) throw input_error("generate", 0, "give --out SCENE.yaml");
  if (options.laps < 1) throw input_error("--laps", 0, "must be >= 1");
  if (!(options.size > 0.0 && options.size <= 1.0)) throw input_error("--size", 0, "must lie in (0, 1]");
  scene::GeneratorConfig config;
  config.laps = options.laps;
  config.size = options.size;
  if (options.seed < 0) throw input_error("--seed", 0, "must be >= 0");
  const scene::GeneratedBuilding b =
      scene::generate_building(options.style, static_cast<std::uint64_t>(options.seed), config);
  io::write_file_atomic(options.out, b.yaml);
  if (!options.quiet) {
    const scene::Scene& s = b.scene;
    std::fprintf(stderr, "generate: %s, seed %llu: %zu level%s, %zu rooms, %zu walls, %zu boxes, %s at %.2f m; wrote %s\n",
                 options.style.c_str(), static_cast<unsigned long long>(options.seed), s.levels.size(),
                 s.levels.size() == 1 ? "" : "s", s.rooms.size(), s.walls.size(), s.boxes.size(),
                 s.sensor.preset.c_str(), s.sensor.mount_height, options.out.c_str());
  }
}

}  // namespace tsgraphs::app
