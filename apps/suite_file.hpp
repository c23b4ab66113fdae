#pragma once
/// The suite file of `tsgraphs suite` (docs/suite.md): a name, the methods, the laps, and the
/// cases: generated buildings (styles x seeds x platforms), imported occupancy maps, scene
/// files or built-in scenes, and existing sequence folders, each with a stable id.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::app {

/// How a generated building's platform differs from the generator's own random draw.
struct SuitePlatform {
  std::string name;                    ///< "" for the generator's draw ("default")
  std::optional<double> mount_height;  ///< m: the sensor above the floor
  std::string preset;                  ///< a sensor preset ("" keeps the drawn one)
  std::string type;  ///< what carries the sensor: wheeled, handheld, legged ("" keeps the drawn one)
  std::optional<double> rate_hz;    ///< sweeps per second (none keeps the preset's)
  std::optional<double> record_hz;  ///< scans kept per second (none: every sweep)
};

struct SuiteCase {
  std::string id;     ///< unique: office-s3, office-s3-handheld, import-<name>, scene-office, seq-<dir>
  std::string kind;   ///< generate, import, scene or sequence
  std::string where;  ///< "file:line" of the entry, for messages
  std::string group;  ///< the entry of `cases:` it comes from: "cases[1]: generate, realistic"
  // generate
  std::string style;
  std::uint64_t seed = 1;
  double size = 1.0;
  int people = 0;          ///< generate --people
  bool realistic = false;  ///< generate --realistic (the id ends in -realistic)
  SuitePlatform platform;
  // import: the map's YAML (absolute); scene: a scene file (absolute path) or a built-in
  // scene's name; sequence: the folder (absolute)
  std::string source;
  // import
  std::string rooms;     ///< the room labels image (absolute), "" for none
  double ceiling = 2.6;  ///< m: import-map's default
};

struct Suite {
  std::string file;  ///< the suite file, absolute
  std::string name;
  std::vector<std::string> methods;  ///< method slugs (methods.hpp), in order
  int laps = 0;  ///< laps of every path but a sequence's; 0: 2 (generate, import), the scene's own
  std::vector<SuiteCase> cases;  ///< in plan order
};

/// Reads and checks a suite file: unknown keys, styles, presets, methods, missing scene files
/// or sequence folders and duplicate case ids are InputErrors naming file:line and the key.
/// Scene files are loaded to check them. Relative paths are taken from the suite file's folder.
Suite load_suite(const std::string& file);

/// `slugs` checked as a method list (known, no repeats, not empty); `where` names them in messages.
std::vector<std::string> check_methods(const std::vector<std::string>& slugs, const std::string& where);

/// The scene of a `scene` case: its file (an absolute path), else the built-in scene of that
/// name (never a file of that name in the working folder). Warnings are not printed.
scene::Scene scene_of(const SuiteCase& c);

/// The case with `id`; an InputError naming the suite file when there is none.
const SuiteCase& find_case(const Suite& suite, const std::string& id);

}  // namespace tsgraphs::app
