#pragma once
/// An occupancy map (free / occupied / unknown cells, as ROS map_server gives them) made a
/// scene (docs/import-map.md): one level whose slab is the known area (a laser map's fringe of
/// unknown at the walls bridged), unknown holes as voids, occupied cells as a voxel map of wall
/// columns, ground-truth rooms from per-cell room labels (io/room_labels.hpp reads them from a
/// label image), and a survey path. No file I/O: the caller reads the map and the labels and
/// writes the scene and the voxel points.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/core/raster_regions.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::map_import {

enum class MapCell : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

/// A map raster: cell (c, r) covers [c, c + 1) x [r, r + 1) resolutions from the map's
/// lower-left corner, row 0 at the bottom; the map frame is placed in the world by `origin`
/// (the corner's position) and `yaw` (rotation about it), as map_server's origin [x, y, yaw].
struct MapRaster {
  int cols = 0, rows = 0;
  double resolution = 0.05;    ///< m per cell
  Vec2 origin = Vec2::Zero();  ///< world position of the lower-left corner
  double yaw = 0.0;            ///< rad
  std::vector<MapCell> cells;  ///< cols * rows, index r * cols + c

  MapCell at(int c, int r) const { return cells[static_cast<std::size_t>(r) * cols + c]; }
  /// The world position of a point given in the map frame (metres from the lower-left corner).
  Vec2 to_world(const Vec2& p) const;
  /// The inverse.
  Vec2 to_map(const Vec2& p) const;
};

struct MapImportConfig {
  std::string name = "imported_map";  ///< the scene's name
  std::string voxel_file =
      "walls.pcd";          ///< the voxel map's file as the scene names it (relative to the scene)
  double ceiling = 2.6;     ///< m: the level's ceiling and the walls' height
  double clearance = 0.35;  ///< m the survey path keeps from every wall and unmapped cell
  int laps = 2;             ///< laps of the survey path
  double min_void_area =
      1.0;  ///< m²: unknown holes in the known area larger than this are voids; smaller ones floor
  /// m: runs of unknown up to this long between known cells next to a wall are bridged (the slab
  /// spans them; between occupied cells they are wall): the band of uncertain occupancy a laser map
  /// leaves at a wall's face (range noise, beam width and pose error, a few centimetres each; 1-4
  /// cells at 0.05 m).
  double fringe_width = 0.2;
  /// m: the diameter of the disc that closes each ground-truth room (map_import/map_rooms.hpp): wider than
  /// what hides floor from a 2-D laser inside a room (desks, cabinets, the wedges between a fan's rays
  /// near its door), narrower than any room, so it never fills a space that could be a room of its own.
  double room_closing = 1.0;
  double coverage_tile = 7.0;  ///< m: without rooms, one stop per tile of this size of the free space
  std::string sensor_preset = "os1-64";  ///< the scene format's default sensor
  double mount_height = 0.55;            ///< m: the sensor above the floor
  double speed = 1.0;                    ///< m/s along the path
  double yaw_rate_deg = 90.0;            ///< deg/s at corners
};

/// What the import made, for the command's summary and the tests.
struct MapImportStats {
  std::size_t known_cells = 0;     ///< cells of the slab (known cells and the unknown gaps it bridges)
  std::size_t bridged_cells = 0;   ///< unknown cells of the slab: the fringe and the walls' gaps
  std::size_t occupied_cells = 0;  ///< occupied cells on the slab
  std::size_t occupied_off_slab =
      0;  ///< occupied cells off it (beyond more than fringe_width of unknown): no walls
  std::size_t wall_gap_cells = 0;  ///< unknown cells of the slab in the gaps between occupied ones: wall too
  std::size_t skin_cells = 0;      ///< wall cells next to a cell that is not wall: the ones that get voxels
  std::size_t voxels = 0;          ///< cubes written
  int small_holes = 0;             ///< unknown holes of at most min_void_area, left as floor
  std::size_t slab_vertices = 0;
  double path_length = 0.0;         ///< m, one lap
  double min_path_clearance = 0.0;  ///< m, along the driven path (all laps), to the nearest cell edge
  std::size_t room_cells_left_out =
      0;               ///< labelled cells outside their room's region (map_import/map_rooms.hpp)
  int room_slits = 0;  ///< holes of rooms opened because they hold other rooms
};

struct ImportedMap {
  scene::Scene scene;  ///< voxel_maps[0].file is config.voxel_file
  std::vector<Eigen::Vector3f>
      voxels;  ///< voxel centres in the voxel map's frame (the map frame, z up from the floor)
  std::vector<std::string> warnings;  ///< no wall; rooms left out of the tour, and why
  MapImportStats stats;
};

/// Builds the scene of `map`. `room_of_cell` (empty, or one room index in [0, room_count) or -1
/// per cell, row 0 at the bottom like `map.cells`: io::RoomLabels::room) gives the ground-truth
/// rooms `room_1` ... `room_<room_count>`, each room's polygon the outline of its region
/// (map_import/map_rooms.hpp). Throws an InputError when the map has no known cell or no free cell far
/// enough from every obstacle to start a path, and std::invalid_argument on a raster or labels
/// whose size disagrees with its cells.
ImportedMap import_map(const MapRaster& map, const std::vector<int>& room_of_cell, int room_count,
                       const MapImportConfig& config);

}  // namespace tsgraphs::map_import
