#include "tsgraphs/map_import/map_import.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/core/raster_morphology.hpp"
#include "tsgraphs/map_import/map_rooms.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/survey_path.hpp"
#include "tsgraphs/scene/trajectory.hpp"
#include "tsgraphs/scene/walkable_grid.hpp"

namespace tsgraphs::map_import {
namespace {

constexpr double kCellEdgeBound =
    0.71;  // cells from a cell's centre to its farthest point (half diagonal, rounded up)
constexpr double kCellsSlack = 1e-9;  // a width that is a whole number of cells stays that number

using Cell = std::array<int, 2>;

Polygon2 transform(const Polygon2& cells, double scale, const MapRaster& map) {
  Polygon2 out;
  out.reserve(cells.size());
  for (const Vec2& p : cells) out.push_back(map.to_world(scale * p));
  return out;
}

std::string fmt(double v, int digits = 2) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

/// The scene's floor on the map's raster.
struct Floor {
  std::vector<std::uint8_t> slab;   ///< per cell: on the slab
  std::vector<std::uint8_t> speck;  ///< per cell: in an unknown hole too small to be a void (floor)
  std::vector<Polygon2> outlines;   ///< cell units: [0] the slab, then the voids
};

/// The known cells and a laser map's fringe at its walls: the unknown cells on a run of unknown
/// along a row, a column or a diagonal, no longer than the fringe width, between two known
/// cells, within the fringe width of an occupied cell. Unknown gaps away from walls (an unscanned
/// patch's corners, speckle) are not fringe; they stay as they are.
std::vector<std::uint8_t> known_and_fringe(const MapRaster& map, const MapImportConfig& config) {
  const std::size_t n = map.cells.size();
  const double width = config.fringe_width / map.resolution;  // cells
  std::vector<std::uint8_t> known(n), unknown(n), occupied(n);
  for (std::size_t i = 0; i < n; ++i) {
    known[i] = map.cells[i] != MapCell::kUnknown;
    unknown[i] = !known[i];
    occupied[i] = map.cells[i] == MapCell::kOccupied;
  }
  const std::vector<std::uint8_t> bridged = bridge_gaps(known, unknown, map.cols, map.rows, width);
  const std::vector<std::uint8_t> near_wall = dilate(occupied, map.cols, map.rows, width);
  for (std::size_t i = 0; i < n; ++i) known[i] = known[i] || (bridged[i] && near_wall[i]);
  return known;
}

/// The slab's holes: 8-connected regions of other cells that do not reach the raster's edge.
/// Those larger than min_void_area are voids (their index per cell, -1 elsewhere); the smaller
/// ones are floor (`floor->speck`). Returns the number of voids.
int find_voids(const MapRaster& map, const MapImportConfig& config, Floor* floor,
               std::vector<int>* void_label, MapImportStats* stats) {
  const int cols = map.cols, rows = map.rows;
  const std::size_t n = map.cells.size();
  std::vector<std::uint8_t> off_slab(n);
  for (std::size_t i = 0; i < n; ++i) off_slab[i] = !floor->slab[i];
  std::vector<std::size_t> sizes;
  const std::vector<int> hole = label_regions(off_slab, cols, rows, true, &sizes);
  std::vector<bool> exterior(sizes.size(), false);
  for (int c = 0; c < cols; ++c)
    for (int r : {0, rows - 1})
      if (const int id = hole[static_cast<std::size_t>(r) * cols + c]; id >= 0) exterior[id] = true;
  for (int r = 0; r < rows; ++r)
    for (int c : {0, cols - 1})
      if (const int id = hole[static_cast<std::size_t>(r) * cols + c]; id >= 0) exterior[id] = true;
  std::vector<int> void_of_hole(sizes.size(), -1);
  int n_voids = 0;
  for (std::size_t h = 0; h < sizes.size(); ++h) {
    if (exterior[h]) continue;
    if (sizes[h] * map.resolution * map.resolution > config.min_void_area) {
      void_of_hole[h] = n_voids++;
    } else {
      ++stats->small_holes;
    }
  }
  void_label->assign(n, -1);
  floor->speck.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const int h = hole[i];
    if (h < 0 || exterior[h]) continue;
    (*void_label)[i] = void_of_hole[h];
    floor->speck[i] = void_of_hole[h] < 0;
  }
  return n_voids;
}

/// The slab: the largest 4-connected region of the known cells and the fringe; its voids; their
/// outlines (cell units), simplified together so that no void crosses the slab's edge.
Floor find_floor(const MapRaster& map, const MapImportConfig& config, MapImportStats* stats) {
  const int cols = map.cols, rows = map.rows;
  const std::size_t n = map.cells.size();
  std::vector<std::size_t> sizes;
  const std::vector<int> region = label_regions(known_and_fringe(map, config), cols, rows, false, &sizes);
  if (sizes.empty()) throw InputError("the map has no known cell (every cell is unknown)");
  const int slab_id = static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  Floor floor;
  floor.slab.assign(n, 0);
  std::vector<int> slab_label(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    floor.slab[i] = region[i] == slab_id;
    slab_label[i] = floor.slab[i] ? 0 : -1;
    stats->known_cells += floor.slab[i];
    stats->bridged_cells += floor.slab[i] && map.cells[i] == MapCell::kUnknown;
  }
  std::vector<int> void_label;
  const int n_voids = find_voids(map, config, &floor, &void_label, stats);
  floor.outlines = trace_outlines(slab_label, cols, rows, 1, false);
  const std::vector<Polygon2> voids = trace_outlines(void_label, cols, rows, n_voids, true);
  floor.outlines.insert(floor.outlines.end(), voids.begin(), voids.end());
  floor.outlines = simplify_outlines(floor.outlines, 1.0);
  stats->slab_vertices = floor.outlines.front().size();
  return floor;
}

/// Per cell: a wall. The occupied cells of the slab, and its unknown cells on a run of unknown no
/// longer than the fringe width between two occupied cells (along a row, a column or a
/// diagonal): a wall the laser saw in dashes is one wall, which the sensor must not see through.
std::vector<std::uint8_t> find_walls(const MapRaster& map, const Floor& floor, const MapImportConfig& config,
                                     MapImportStats* stats) {
  const std::size_t n = map.cells.size();
  std::vector<std::uint8_t> occupied(n), unknown(n);
  for (std::size_t i = 0; i < n; ++i) {
    occupied[i] = map.cells[i] == MapCell::kOccupied;
    unknown[i] = map.cells[i] == MapCell::kUnknown;
    stats->occupied_cells += occupied[i] && floor.slab[i];
    stats->occupied_off_slab += occupied[i] && !floor.slab[i];
  }
  const std::vector<std::uint8_t> gaps =
      bridge_gaps(occupied, unknown, map.cols, map.rows, config.fringe_width / map.resolution);
  std::vector<std::uint8_t> wall(n);
  for (std::size_t i = 0; i < n; ++i) {
    wall[i] = floor.slab[i] && (occupied[i] || gaps[i]);
    stats->wall_gap_cells += floor.slab[i] && gaps[i];
  }
  return wall;
}

/// A column of cubes from the floor to the ceiling on each wall cell next to a cell that is not
/// wall (or the map's edge): the inside of a thick wall is never seen.
std::vector<Eigen::Vector3f> wall_voxels(const MapRaster& map, const std::vector<std::uint8_t>& wall,
                                         const MapImportConfig& config, MapImportStats* stats) {
  const int cols = map.cols, rows = map.rows;
  const double res = map.resolution;
  const int n_z = std::max(1, static_cast<int>(std::ceil(config.ceiling / res - kCellsSlack)));
  const auto is_wall = [&](int c, int r) {
    return c >= 0 && r >= 0 && c < cols && r < rows && wall[static_cast<std::size_t>(r) * cols + c];
  };
  std::vector<Eigen::Vector3f> out;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (!is_wall(c, r)) continue;
      bool skin = false;
      for (const Cell& d : {Cell{1, 0}, Cell{-1, 0}, Cell{0, 1}, Cell{0, -1}})
        skin = skin || !is_wall(c + d[0], r + d[1]);
      if (!skin) continue;
      ++stats->skin_cells;
      for (int k = 0; k < n_z; ++k)
        out.emplace_back(static_cast<float>((c + 0.5) * res), static_cast<float>((r + 0.5) * res),
                         static_cast<float>((k + 0.5) * res));
    }
  }
  stats->voxels = out.size();
  return out;
}

/// Each room's polygon in the map frame (metres), traced round its region and simplified with
/// the others so that none crosses another; empty for a room left without a cell.
std::vector<Polygon2> room_polygons(const MapRaster& map, const std::vector<int>& room_of_cell,
                                    int room_count, const MapImportConfig& config, MapImportStats* stats) {
  if (room_count == 0) return {};
  const MapRoomRegions regions =
      room_regions(room_of_cell, room_count, map.cols, map.rows, 0.5 * config.room_closing / map.resolution);
  for (std::size_t k : regions.labelled_out) stats->room_cells_left_out += k;
  stats->room_slits = regions.slits;
  std::vector<Polygon2> out =
      simplify_outlines(trace_outlines(regions.region, map.cols, map.rows, room_count, true), 1.0);
  for (Polygon2& p : out)
    for (Vec2& q : p) q *= map.resolution;
  return out;
}

/// Where one may stand: the slab's floor that is no wall (its small unknown holes too: a map's
/// speckle noise must not wall rooms off), with its clearance.
scene::WalkableGrid walkable_grid(const MapRaster& map, const Floor& floor,
                                  const std::vector<std::uint8_t>& wall) {
  scene::WalkableGrid grid;
  grid.level = 0;
  grid.frame.origin = Vec2::Zero();
  grid.frame.resolution = map.resolution;
  grid.frame.cols = map.cols;
  grid.frame.rows = map.rows;
  grid.free.assign(map.cells.size(), 0);
  for (std::size_t i = 0; i < grid.free.size(); ++i)
    grid.free[i] = (floor.slab[i] && !wall[i]) || floor.speck[i];
  scene::compute_clearance(&grid);
  return grid;
}

/// The tour's region: the region of the cells that keep the planning clearance holding the most
/// rooms' most interior points (ties: the largest). Its grid is free only there.
scene::WalkableGrid tour_region(const scene::WalkableGrid& grid, const std::vector<Polygon2>& rooms,
                                double plan_clearance) {
  const GridFrame& f = grid.frame;
  std::vector<std::uint8_t> passable(f.size());
  for (std::size_t i = 0; i < passable.size(); ++i)
    passable[i] = grid.free[i] && grid.clearance[i] >= plan_clearance;
  std::vector<std::size_t> sizes;
  const std::vector<int> region = label_regions(passable, f.cols, f.rows, false, &sizes);
  if (sizes.empty())
    throw InputError("no free cell of the map is " + fmt(plan_clearance) +
                     " m from every wall and unmapped cell: no survey path (try a smaller --clearance)");
  std::vector<int> rooms_in(sizes.size(), 0);
  for (const Polygon2& room : rooms) {
    Vec2 p;
    int c, r;
    if (!room.empty() && scene::most_interior_point(grid, room, &p) && f.cell_of(p, &c, &r)) {
      if (const int id = region[f.index(c, r)]; id >= 0) ++rooms_in[id];
    }
  }
  int main_id = 0;
  for (std::size_t id = 1; id < sizes.size(); ++id) {
    if (std::tie(rooms_in[id], sizes[id]) > std::tie(rooms_in[main_id], sizes[main_id]))
      main_id = static_cast<int>(id);
  }
  scene::WalkableGrid reach = grid;  // clearances unchanged
  for (std::size_t i = 0; i < reach.free.size(); ++i) reach.free[i] = region[i] == main_id;
  return reach;
}

/// The path's stops: one in each reachable room, or without rooms one in each tile of the tour's
/// region; with a single stop, the region's farthest cell from it as a second.
struct Stops {
  std::vector<scene::SurveyStop> stops;
  std::vector<std::string> names;
};

void add_coverage_stops(const scene::WalkableGrid& reach, const MapImportConfig& config, Stops* out) {
  const GridFrame& f = reach.frame;
  int c0 = f.cols, c1 = -1, r0 = f.rows, r1 = -1;
  for (std::size_t i = 0; i < reach.free.size(); ++i) {
    if (!reach.free[i]) continue;
    const int c = static_cast<int>(i % f.cols), r = static_cast<int>(i / f.cols);
    c0 = std::min(c0, c), c1 = std::max(c1, c), r0 = std::min(r0, r), r1 = std::max(r1, r);
  }
  const double res = f.resolution;
  const int tile = std::max(1, static_cast<int>(std::lround(config.coverage_tile / res)));
  const int nx = (c1 - c0) / tile + 1, ny = (r1 - r0) / tile + 1;
  for (int ty = 0; ty < ny; ++ty) {
    for (int tx = 0; tx < nx; ++tx) {
      const Vec2 lo = res * Vec2(c0 + tx * tile, r0 + ty * tile), hi = lo + Vec2::Constant(res * tile);
      const Polygon2 box = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
      Vec2 p;
      if (!scene::most_interior_point(reach, box, &p)) continue;
      out->stops.push_back({0, p});
      out->names.push_back("tile " + std::to_string(tx) + "," + std::to_string(ty));
    }
  }
}

void add_far_end(const scene::WalkableGrid& reach, Stops* out) {
  std::size_t best = 0;
  double best_d = -1.0;
  for (std::size_t i = 0; i < reach.free.size(); ++i) {
    if (!reach.free[i]) continue;
    const double d = (reach.frame.center(i) - out->stops[0].xy).squaredNorm();
    if (d > best_d) best_d = d, best = i;
  }
  if (best_d < 1e-12)
    throw InputError("the free space that keeps the clearance is a single cell: no survey path");
  out->stops.push_back({0, reach.frame.center(best)});
  out->names.push_back("the far end of the free space");
}

/// The scene's rooms, and a stop in each one the tour's region reaches (a warning for the others).
Stops room_stops(const MapRaster& map, const std::vector<Polygon2>& rooms, const scene::WalkableGrid& reach,
                 const MapImportConfig& config, ImportedMap* out) {
  Stops s;
  for (std::size_t k = 0; k < rooms.size(); ++k) {
    const std::string name = "room_" + std::to_string(k + 1);
    if (rooms[k].empty()) {
      out->warnings.push_back("room '" + name +
                              "' keeps no cell of its own (its labels touch other rooms' only): left out");
      continue;
    }
    scene::Room room;
    room.name = name;
    room.level = 0;
    room.polygon = transform(rooms[k], 1.0, map);
    Vec2 p;
    if (scene::most_interior_point(reach, rooms[k], &p)) {
      s.stops.push_back({0, p});
      s.names.push_back(room.name);
    } else {
      const Vec2 at = centroid(room.polygon);
      out->warnings.push_back("room '" + room.name + "' (centre [" + fmt(at.x()) + ", " + fmt(at.y()) +
                              "], " + fmt(area(room.polygon), 1) + " m²) cannot be reached keeping " +
                              fmt(config.clearance) +
                              " m from every wall and unmapped cell: left out of the survey path");
    }
    out->scene.rooms.push_back(room);
  }
  if (rooms.empty()) add_coverage_stops(reach, config, &s);
  if (s.stops.empty()) throw InputError("no room can be reached keeping the clearance: no survey path");
  if (s.stops.size() == 1) add_far_end(reach, &s);  // one place to visit: go to the farthest cell and back
  return s;
}

/// The level, the wall voxel map and the sensor of the scene, in the world frame.
void add_level_and_walls(const MapRaster& map, const Floor& floor, bool has_walls,
                         const MapImportConfig& config, scene::Scene* scene) {
  scene->name = config.name;
  if (!scene::apply_preset(config.sensor_preset, &scene->sensor))
    throw InputError("--sensor: unknown sensor preset '" + config.sensor_preset + "'");
  scene->sensor.preset = config.sensor_preset;
  scene->sensor.mount_height = config.mount_height;
  scene::Level level;
  level.name = "L0";
  level.elevation = 0.0;
  level.ceiling = config.ceiling;
  level.slab = transform(floor.outlines.front(), map.resolution, map);
  for (std::size_t v = 1; v < floor.outlines.size(); ++v)
    level.voids.push_back(transform(floor.outlines[v], map.resolution, map));
  scene->levels.push_back(level);
  if (!has_walls) return;
  scene::VoxelMap walls;
  walls.file = config.voxel_file;
  walls.voxel_size = map.resolution;
  walls.level = 0;
  walls.label = scene::VoxelLabel::kWall;
  walls.offset = Eigen::Vector3d(map.origin.x(), map.origin.y(), 0.0);
  walls.yaw_deg = map.yaw * 180.0 / M_PI;
  scene->voxel_maps.push_back(walls);
}

/// The survey path through the stops, in the world frame, its corners kept clear of the walls.
void add_path(const MapRaster& map, const scene::WalkableGrid& grid, const scene::WalkableGrid& reach,
              const Stops& s, const MapImportConfig& config, ImportedMap* out) {
  scene::SurveyConfig survey;
  survey.clearance = config.clearance;
  std::vector<scene::Waypoint> lap;
  try {
    lap = scene::plan_survey({reach}, {}, s.stops, survey, [&](std::size_t i) { return s.names[i]; });
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("import_map: ") + e.what());  // the stops were checked: a bug
  }
  scene::Scene& scene = out->scene;
  scene::TrajectorySpec& t = scene.trajectory;
  t.level = 0;
  for (scene::Waypoint w : lap) {
    w.xy = map.to_world(w.xy);
    t.waypoints.push_back(w);
  }
  t.closed = true;
  t.laps = std::min(config.laps, 2);  // planned on two laps (the laps after repeat them), the laps set last
  t.speed = config.speed;
  t.yaw_rate_deg = config.yaw_rate_deg;
  // The distance to the nearest blocked cell's edge, at most: the raster's centre-to-centre
  // distance less a half diagonal.
  const double res = map.resolution;
  const scene::ClearanceAt clearance_at = [&](const Vec2& xy, double, int) {
    return grid.clearance_at(map.to_map(xy)) - kCellEdgeBound * res;
  };
  scene::keep_clearance_on_turns(&scene, clearance_at, survey);
  const scene::PathClearance worst = scene::path_clearance(scene, clearance_at);
  out->stats.min_path_clearance = worst.min_clearance;
  if (worst.min_clearance < config.clearance) {
    // Millimetres: at centimetres a path 0.349 m from a wall read "0.35 m, less than 0.35 m".
    out->warnings.push_back("the survey path comes " + fmt(worst.min_clearance, 3) +
                            " m from a wall or unmapped cell at [" + fmt(worst.where.x()) + ", " +
                            fmt(worst.where.y()) + "], less than " + fmt(config.clearance, 3) + " m");
  }
  out->stats.path_length = scene::Trajectory(scene).length() / t.laps;
  t.laps = config.laps;
  if (const std::string over = scene::recording_over_limits(scene); !over.empty())
    throw InputError("--laps: " + over);
}

/// Refuses a map whose corners lie beyond a scene's coordinates (core/limits.hpp): its scene
/// would not load.
void check_extent(const MapRaster& map) {
  const auto g = [](double v) {  // a coordinate of any size, in a few digits
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return std::string(text);
  };
  const Vec2 size(map.cols * map.resolution, map.rows * map.resolution);
  for (const Vec2& corner : {Vec2(0.0, 0.0), Vec2(size.x(), 0.0), Vec2(0.0, size.y()), size}) {
    const Vec2 p = map.to_world(corner);
    if (!(p.cwiseAbs().maxCoeff() <= limits::kMaxSceneCoordinate))
      throw InputError("origin: the map reaches [" + g(p.x()) + ", " + g(p.y()) + "], beyond " +
                       g(limits::kMaxSceneCoordinate) + " m of the scene's origin");
  }
  if (!(size.maxCoeff() <= limits::kMaxSceneExtent))
    throw InputError("the map spans " + g(size.maxCoeff()) + " m, more than a scene's " +
                     g(limits::kMaxSceneExtent) + " m");
}

/// Why the scene has no wall, when it has none.
std::string no_wall_warning(const MapImportStats& stats, const MapImportConfig& config) {
  if (stats.occupied_cells + stats.occupied_off_slab == 0)
    return "the map has no occupied cell: the scene has no wall";
  return "none of the map's " + std::to_string(stats.occupied_off_slab) +
         " occupied cells lies on the slab (the known area, gaps of unknown up to " +
         fmt(config.fringe_width) + " m bridged): the scene has no wall";
}

}  // namespace

Vec2 MapRaster::to_world(const Vec2& p) const {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return origin + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y());
}

Vec2 MapRaster::to_map(const Vec2& p) const {
  const double c = std::cos(yaw), s = std::sin(yaw);
  const Vec2 d = p - origin;
  return Vec2(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
}

ImportedMap import_map(const MapRaster& map, const std::vector<int>& room_of_cell, int room_count,
                       const MapImportConfig& config) {
  const std::size_t n = static_cast<std::size_t>(map.cols) * map.rows;
  if (map.cols < 1 || map.rows < 1 || map.cells.size() != n || !(map.resolution > 0.0))
    throw std::invalid_argument("import_map: the raster's size disagrees with its cells");
  if (room_count < 0 || (room_count > 0 && room_of_cell.size() != n))
    throw std::invalid_argument("import_map: the room labels' size differs from the map's");
  check_extent(map);
  ImportedMap out;
  const Floor floor = find_floor(map, config, &out.stats);
  const std::vector<std::uint8_t> wall = find_walls(map, floor, config, &out.stats);
  out.voxels = wall_voxels(map, wall, config, &out.stats);
  if (out.voxels.empty()) out.warnings.push_back(no_wall_warning(out.stats, config));
  const std::vector<Polygon2> rooms = room_polygons(map, room_of_cell, room_count, config, &out.stats);

  const scene::WalkableGrid grid = walkable_grid(map, floor, wall);
  scene::SurveyConfig survey;
  const scene::WalkableGrid reach =
      tour_region(grid, rooms, config.clearance + survey.plan_margin_cells * map.resolution);
  const Stops stops = room_stops(map, rooms, reach, config, &out);
  add_level_and_walls(map, floor, !out.voxels.empty(), config, &out.scene);
  add_path(map, grid, reach, stops, config, &out);
  return out;
}

}  // namespace tsgraphs::map_import
