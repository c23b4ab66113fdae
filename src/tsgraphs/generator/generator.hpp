#pragma once
/// `tsgraphs generate`: procedural buildings with ground truth, for judging the method on
/// buildings it was not developed on. A style and a seed give one building: its storeys
/// (building_styles.hpp, floor_plan.hpp, furnishing.hpp), a random platform (sensor preset,
/// mount height, odometry drift, speed) and a closed survey path that enters every
/// ground-truth room through its door (survey_path.hpp). docs/generator.md gives the rules.
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::generator {

/// office, atrium, library, open_plan, irregular, multi_storey, mixed.
const std::vector<std::string>& building_style_names();

struct GeneratorConfig {
  double clearance = 0.3;         ///< m the survey path keeps from every obstacle (a door is >= 0.8 m)
  double grid_resolution = 0.05;  ///< m: the planning raster
  int laps = 2;                   ///< laps of the survey path
  double size = 1.0;              ///< (0, 1]: scales the building's extent (never below what its style needs)
  int max_attempts = 20;          ///< layouts drawn for one seed before giving up
  double mount_height_min = 0.3;  ///< m: sensor heights drawn from [min, max]
  double mount_height_max = 1.8;
  double speed_min = 0.5;  ///< m/s: path speeds drawn from [min, max]
  double speed_max = 1.5;
  double coverage_spacing = 8.0;  ///< m: a hall gets a stop in every tile of this size
  double coverage_area = 60.0;    ///< m^2: rooms larger than this get coverage stops too
  int people =
      0;  ///< people walking stretches of the survey path (scene people:), at most kMaxGeneratedPeople
  /// generate --realistic: clutter and furniture against the walls, open door leaves, windows,
  /// rooms that are not rectangles and rows of small offices (docs/generator.md, "Realistic
  /// buildings"). Without it a building is what it always was, byte for byte.
  bool realistic = false;
};

/// More people than this in one generated building is a typo.
constexpr int kMaxGeneratedPeople = 50;

struct GeneratedBuilding {
  scene::Scene scene;  ///< parsed from `yaml`, exactly what a scene file of it loads to
  std::string yaml;    ///< the scene file's text
  int attempts = 1;    ///< layouts drawn until one passed every check
};

/// The building of `style` for `seed`: the same style, seed and config give the same text.
/// Throws InputError for an unknown style, std::runtime_error when no attempt passes.
GeneratedBuilding generate_building(const std::string& style, std::uint64_t seed,
                                    const GeneratorConfig& config = {});

/// What the generator checks before it hands a building out; each problem one line, empty
/// when sound: the loader's and the path's warnings; the path's clearance along all laps
/// (exact geometry); a true pose inside every ground-truth room; rooms that overlap or leave
/// the walkable slab.
std::vector<std::string> check_building(const scene::Scene& scene, double clearance);

}  // namespace tsgraphs::generator
