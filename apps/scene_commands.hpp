#pragma once
/// The commands that make scenes: `generate` (a procedural building) and `import-map` (a ROS
/// occupancy map), each writing a scene file that every other command reads.
#include <cstdint>
#include <string>

namespace tsgraphs::app {

struct GenerateOptions {
  std::string style;   ///< building style (scene::building_style_names())
  long long seed = 1;  ///< >= 0
  std::string out;     ///< scene file to write
  int laps = 2;        ///< laps of the survey path
  double size = 1.0;   ///< scales the building's extent, (0, 1]
  bool quiet = false;
};

/// `generate`: the building of the style and seed as a scene file (docs/generator.md),
/// written whole or not at all.
void generate(const GenerateOptions& options);

}  // namespace tsgraphs::app
