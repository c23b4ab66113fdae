#pragma once
/// The commands that make scenes: `generate` (a procedural building) and `import-map` (a ROS
/// occupancy map), each writing a scene file that every other command reads.
#include <cstdint>
#include <string>

namespace tsgraphs::app {

struct GenerateOptions {
  std::string style;       ///< building style (generator::building_style_names())
  long long seed = 1;      ///< >= 0
  std::string out;         ///< scene file to write
  int laps = 2;            ///< laps of the survey path
  double size = 1.0;       ///< scales the building's extent, (0, 1]
  int people = 0;          ///< people walking through (scene people:)
  bool realistic = false;  ///< clutter, open door leaves, windows, irregular rooms, small offices
  bool quiet = false;
};

/// `generate`: the building of the style and seed as a scene file (docs/generator.md),
/// written whole or not at all.
void generate(const GenerateOptions& options);

struct ImportMapOptions {
  std::string map;                ///< the map_server YAML
  std::string out;                ///< scene file to write; its walls go beside it as <stem>_walls.pcd
  std::string rooms;              ///< room labels image (IPA convention), or "" for none
  double ceiling = 2.6;           ///< m: ceiling and wall height
  double clearance = 0.35;        ///< m the survey path keeps from occupied and unknown cells
  int laps = 2;                   ///< laps of the survey path
  std::string sensor = "os1-64";  ///< sensor preset
  double mount_height = 0.55;     ///< m: sensor above the floor
  bool quiet = false;
};

/// `import-map`: a ROS occupancy map (and its room labels) as a scene file and its voxel
/// PCD (docs/import-map.md), both written whole or not at all.
void import_map(const ImportMapOptions& options);

}  // namespace tsgraphs::app
