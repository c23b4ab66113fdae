// The commands that make scenes (scene_commands.hpp).
#include "scene_commands.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "output_checks.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/occupancy_map.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/io/room_labels.hpp"
#include "tsgraphs/generator/generator.hpp"
#include "tsgraphs/map_import/map_import.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"

namespace tsgraphs::app {

void generate(const GenerateOptions& options) {
  if (options.out.empty()) throw input_error("generate", 0, "give --out SCENE.yaml");
  if (options.laps < 1) throw input_error("--laps", 0, "must be >= 1");
  if (!(options.size > 0.0 && options.size <= 1.0)) throw input_error("--size", 0, "must lie in (0, 1]");
  generator::GeneratorConfig config;
  config.laps = options.laps;
  config.size = options.size;
  config.people = options.people;
  config.realistic = options.realistic;
  if (options.seed < 0) throw input_error("--seed", 0, "must be >= 0");
  const generator::GeneratedBuilding b =
      generator::generate_building(options.style, static_cast<std::uint64_t>(options.seed), config);
  io::write_file_atomic(options.out, b.yaml);
  if (!options.quiet) {
    const scene::Scene& s = b.scene;
    std::fprintf(
        stderr,
        "generate: %s%s, seed %llu: %zu level%s, %zu rooms, %zu walls, %zu boxes, %s at %.2f m; wrote %s\n",
        options.style.c_str(), options.realistic ? " (realistic)" : "",
        static_cast<unsigned long long>(options.seed), s.levels.size(), s.levels.size() == 1 ? "" : "s",
        s.rooms.size(), s.walls.size(), s.boxes.size(), s.sensor.preset.c_str(), s.sensor.mount_height,
        options.out.c_str());
  }
}

namespace {

constexpr double kMaxCeiling = 20.0;   // m: an atrium's height, well beyond any storey
constexpr double kMaxClearance = 5.0;  // m: more than half of any corridor's width

/// The map's cells for the scene builder (the same raster, the classes renamed).
map_import::MapRaster raster_of(const io::OccupancyMap& m) {
  map_import::MapRaster r;
  r.cols = m.width;
  r.rows = m.height;
  r.resolution = m.meta.resolution;
  r.origin = Vec2(m.meta.origin_x, m.meta.origin_y);
  r.yaw = m.meta.origin_yaw;
  r.cells.resize(m.cells.size());
  for (std::size_t i = 0; i < m.cells.size(); ++i) {
    r.cells[i] = m.cells[i] == io::CellState::kFree       ? map_import::MapCell::kFree
                 : m.cells[i] == io::CellState::kOccupied ? map_import::MapCell::kOccupied
                                                          : map_import::MapCell::kUnknown;
  }
  return r;
}

/// The one-line summary of an import (docs/import-map.md, the worked example).
void print_summary(const ImportMapOptions& options, const io::OccupancyMap& map, const io::RoomLabels& labels,
                   const map_import::ImportedMap& imported, const std::string& pcd, double seconds) {
  const map_import::MapImportStats& st = imported.stats;
  const scene::Scene& s = imported.scene;
  std::string rooms;
  if (!options.rooms.empty()) {
    rooms = " (" + std::string(io::convention_name(labels.convention));
    if (st.room_cells_left_out > 0)
      rooms += "; " + std::to_string(st.room_cells_left_out) + " labelled cells left out";
    if (st.room_slits > 0) rooms += "; " + std::to_string(st.room_slits) + " hole(s) holding rooms opened";
    rooms += ")";
  }
  std::fprintf(
      stderr,
      "import-map: %s: %d x %d cells at %.3f m; slab %zu vertices, %zu fringe cells, %zu void%s; %zu "
      "room%s%s; "
      "walls: %zu occupied cells (%zu off the slab) and %zu cells of their gaps, %zu on the surface, "
      "%zu voxels; path %.1f m a lap (%zu waypoints), clearance >= %.2f m; %.1f s; wrote %s%s%s\n",
      options.map.c_str(), map.width, map.height, map.meta.resolution, st.slab_vertices, st.bridged_cells,
      s.levels[0].voids.size(), s.levels[0].voids.size() == 1 ? "" : "s", s.rooms.size(),
      s.rooms.size() == 1 ? "" : "s", rooms.c_str(), st.occupied_cells, st.occupied_off_slab,
      st.wall_gap_cells, st.skin_cells, st.voxels, st.path_length, s.trajectory.waypoints.size(),
      st.min_path_clearance, seconds, options.out.c_str(), pcd.empty() ? "" : " and ", pcd.c_str());
}

void check_import_options(const ImportMapOptions& options) {
  if (options.map.empty()) throw input_error("import-map", 0, "give the map's YAML file");
  if (options.out.empty()) throw input_error("import-map", 0, "give --out SCENE.yaml");
  if (!(options.ceiling > 0.0 && options.ceiling <= kMaxCeiling))
    throw input_error("--ceiling", 0, "must lie in (0, 20] m");
  if (!(options.clearance >= 0.0 && options.clearance < kMaxClearance))
    throw input_error("--clearance", 0, "must lie in [0, 5) m");
  if (options.laps < 1) throw input_error("--laps", 0, "must be >= 1");
  const auto& presets = scene::preset_names();
  if (std::find(presets.begin(), presets.end(), options.sensor) == presets.end()) {
    std::string list;
    for (const std::string& n : presets) list += (list.empty() ? "" : ", ") + n;
    throw input_error("--sensor", 0, "unknown preset '" + options.sensor + "' (presets: " + list + ")");
  }
  if (!(options.mount_height > 0.0 && options.mount_height < options.ceiling))
    throw input_error("--mount-height", 0, "must lie between 0 and the ceiling");
}

/// The scene file's header: where it came from, and its walls' file when it has walls.
std::string import_header(const ImportMapOptions& options, const io::RoomLabels& labels,
                          const std::string& voxel_file, bool has_walls) {
  namespace fs = std::filesystem;
  std::ostringstream header;
  header << "Imported by `tsgraphs import-map` (docs/import-map.md) from "
         << fs::path(options.map).filename().string();
  if (!options.rooms.empty()) header << " with rooms from " << fs::path(options.rooms).filename().string();
  if (!options.rooms.empty()) header << " (" << io::convention_name(labels.convention) << ")";
  header << ".";
  if (has_walls)
    header << "\nWalls: " << voxel_file
           << " (voxel centres, one column per wall cell next to the floor or unknown space).";
  return header.str();
}

}  // namespace

void import_map(const ImportMapOptions& options) {
  namespace fs = std::filesystem;
  check_import_options(options);
  const fs::path out(options.out);
  const std::string voxel_file = out.stem().string() + "_walls.pcd";  // beside the scene
  const std::string walls_pcd = (out.parent_path() / voxel_file).string();
  std::vector<std::string> inputs = map_inputs(options.map);
  inputs.push_back(options.rooms);
  check_output_apart("--out", options.out, inputs);
  check_output_apart("--out", walls_pcd, inputs);

  const auto t0 = std::chrono::steady_clock::now();
  const io::OccupancyMap map = io::read_occupancy_map(options.map);
  io::RoomLabels labels;
  if (!options.rooms.empty()) {
    labels = io::read_room_labels(options.rooms, map);
    for (const std::string& w : labels.warnings)
      std::fprintf(stderr, "tsgraphs: warning: %s: %s\n", options.rooms.c_str(), w.c_str());
  }

  map_import::MapImportConfig config;
  config.name = fs::path(options.map).stem().string();
  config.voxel_file = voxel_file;
  config.ceiling = options.ceiling;
  config.clearance = options.clearance;
  config.laps = options.laps;
  config.sensor_preset = options.sensor;
  config.mount_height = options.mount_height;
  map_import::ImportedMap imported;
  try {
    imported = map_import::import_map(raster_of(map), labels.room, labels.count, config);
  } catch (const InputError& e) {
    throw input_error(options.map, 0, e.what());
  }
  for (const std::string& w : imported.warnings)
    std::fprintf(stderr, "tsgraphs: warning: %s: %s\n", options.map.c_str(), w.c_str());

  const bool has_walls = !imported.scene.voxel_maps.empty();  // a map without an occupied cell has none
  const std::string yaml =
      scene::scene_yaml(imported.scene, import_header(options, labels, config.voxel_file, has_walls));
  const fs::path dir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  const fs::path pcd = out.parent_path() / config.voxel_file;  // beside the scene, named as the user named it
  if (has_walls) {
    PointCloud cloud;
    cloud.points = std::move(imported.voxels);
    io::write_file_atomic(pcd.string(), io::encode_pcd(cloud));
  }
  // The scene must read back as written (and its PCD beside it) before it is put in place.
  try {
    scene::Scene check;
    try {
      check = scene::parse_scene(yaml, options.out, dir.string());
    } catch (const InputError& e) {
      throw std::runtime_error(std::string("the imported scene does not read back: ") +
                               e.what());  // a bug here
    }
    for (const std::string& w : check.warnings) std::fprintf(stderr, "tsgraphs: warning: %s\n", w.c_str());
    io::write_file_atomic(options.out, yaml);
  } catch (...) {
    std::error_code ec;
    if (has_walls) fs::remove(pcd, ec);
    throw;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!options.quiet) print_summary(options, map, labels, imported, has_walls ? pcd.string() : "", seconds);
}

}  // namespace tsgraphs::app
