#include "tsgraphs/scene/map_import.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/survey_path.hpp"
#include "tsgraphs/scene/trajectory.hpp"
#include "tsgraphs/scene/walkable_grid.hpp"

namespace tsgraphs::scene {
namespace {

constexpr double kCellEdgeBound = 0.71;  // cells from a cell's centre to its farthest point (half diagonal, rounded up)

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


ImportedMap import_map(const MapRaster& map, const std::vector<std::uint8_t>& room_grey,
                       const MapImportConfig& config) {
  const int cols = map.cols, rows = map.rows;
  const std::size_t n = static_cast<std::size_t>(cols) * rows;
  if (cols < 1 || rows < 1 || map.cells.size() != n || !(map.resolution > 0.0))
    throw std::invalid_argument("import_map: the raster's size disagrees with its cells");
  if (!room_grey.empty() && room_grey.size() != n)
    throw std::invalid_argument("import_map: the room labels' size differs from the map's");
  const double res = map.resolution;
  ImportedMap out;
  MapImportStats& stats = out.stats;

  // The slab: the largest 4-connected region of known cells.
  std::vector<std::uint8_t> known(n);
  for (std::size_t i = 0; i < n; ++i) known[i] = map.cells[i] != MapCell::kUnknown;
  std::vector<std::size_t> sizes;
  const std::vector<int> known_label = label_regions(known, cols, rows, false, &sizes);
  if (sizes.empty()) throw InputError("the map has no known cell (every cell is unknown)");
  const int slab_id = static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  stats.known_cells = sizes[slab_id];
  std::vector<int> slab_label(n, -1);
  std::vector<std::uint8_t> off_slab(n);
  for (std::size_t i = 0; i < n; ++i) {
    slab_label[i] = known_label[i] == slab_id ? 0 : -1;
    off_slab[i] = known_label[i] != slab_id;
  }
  // Holes: 8-connected regions of everything else that do not reach the raster's border.
  const std::vector<int> hole_label = label_regions(off_slab, cols, rows, true, &sizes);
  std::vector<bool> exterior(sizes.size(), false);
  for (int c = 0; c < cols; ++c) {
    for (int r : {0, rows - 1}) {
      const int id = hole_label[static_cast<std::size_t>(r) * cols + c];
      if (id >= 0) exterior[id] = true;
    }
  }
  for (int r = 0; r < rows; ++r) {
    for (int c : {0, cols - 1}) {
      const int id = hole_label[static_cast<std::size_t>(r) * cols + c];
      if (id >= 0) exterior[id] = true;
    }
  }
  std::vector<int> void_label(n, -1);
  int n_voids = 0;
  std::vector<int> void_of_hole(sizes.size(), -1);
  for (std::size_t h = 0; h < sizes.size(); ++h) {
    if (exterior[h]) continue;
    if (sizes[h] * res * res > config.min_void_area) {
      void_of_hole[h] = n_voids++;
    } else {
      ++stats.small_holes;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (hole_label[i] >= 0) void_label[i] = void_of_hole[hole_label[i]];
  }
  // Outlines (cell units), simplified together so that no void crosses the slab's edge.
  std::vector<Polygon2> floor_outlines = trace_outlines(slab_label, cols, rows, 1, false);
  const std::vector<Polygon2> void_outlines = trace_outlines(void_label, cols, rows, n_voids, true);
  floor_outlines.insert(floor_outlines.end(), void_outlines.begin(), void_outlines.end());
  floor_outlines = simplify_outlines(floor_outlines, 1.0);
  stats.slab_vertices = floor_outlines.front().size();

  // Rooms: 8-connected white regions of more than kRoomMaxSmallCells cells, in reading order
  // of the label image (top row first).
  std::vector<Polygon2> room_cells;  // map frame, metres
  if (!room_grey.empty()) {
    std::vector<std::uint8_t> white(n);
    for (std::size_t i = 0; i < n; ++i) white[i] = room_grey[i] > kRoomWhiteAbove;
    std::vector<int> room_label = label_regions(white, cols, rows, true, &sizes);
    std::vector<std::size_t> top_first(sizes.size(), 0);  // reading-order key of each region's first cell
    std::vector<bool> seen(sizes.size(), false);
    for (int r = rows - 1; r >= 0; --r) {
      for (int c = 0; c < cols; ++c) {
        const int id = room_label[static_cast<std::size_t>(r) * cols + c];
        if (id >= 0 && !seen[id]) {
          seen[id] = true;
          top_first[id] = static_cast<std::size_t>(rows - 1 - r) * cols + c;
        }
      }
    }
    std::vector<int> order;
    for (std::size_t id = 0; id < sizes.size(); ++id) {
      if (sizes[id] > kRoomMaxSmallCells) order.push_back(static_cast<int>(id));
    }
    std::sort(order.begin(), order.end(), [&](int a, int b) { return top_first[a] < top_first[b]; });
    std::vector<int> rank(sizes.size(), -1);
    for (std::size_t k = 0; k < order.size(); ++k) rank[order[k]] = static_cast<int>(k);
    for (int& id : room_label) id = id >= 0 ? rank[id] : -1;
    const std::vector<Polygon2> outlines =
        simplify_outlines(trace_outlines(room_label, cols, rows, static_cast<int>(order.size()), true), 1.0);
    for (const Polygon2& p : outlines) {
      Polygon2 m;
      for (const Vec2& q : p) m.push_back(res * q);
      room_cells.push_back(m);
    }
  }

  // Walls: the occupied cells of the slab next to a free or unknown cell (or the map's edge),
  // each a column of cubes from the floor to the ceiling; the inside of thick walls is never seen.
  const int n_z = std::max(1, static_cast<int>(std::ceil(config.ceiling / res - 1e-9)));
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * cols + c;
      if (slab_label[i] != 0 || map.cells[i] != MapCell::kOccupied) continue;
      ++stats.occupied_cells;
      bool skin = false;
      for (const Cell& d : {Cell{1, 0}, Cell{-1, 0}, Cell{0, 1}, Cell{0, -1}}) {
        const int cc = c + d[0], rr = r + d[1];
        skin = skin || cc < 0 || rr < 0 || cc >= cols || rr >= rows || map.at(cc, rr) != MapCell::kOccupied;
      }
      if (!skin) continue;
      ++stats.skin_cells;
      for (int k = 0; k < n_z; ++k)
        out.voxels.emplace_back(static_cast<float>((c + 0.5) * res), static_cast<float>((r + 0.5) * res),
                                static_cast<float>((k + 0.5) * res));
    }
  }
  stats.voxels = out.voxels.size();

  // Where one may stand: the free cells of the slab, with their clearance.
  WalkableGrid grid;
  grid.level = 0;
  grid.frame.origin = Vec2::Zero();
  grid.frame.resolution = res;
  grid.frame.cols = cols;
  grid.frame.rows = rows;
  grid.free.assign(n, 0);
  // Unknown specks too small to be voids are floor in the scene, so they are floor to the path
  // too (a map's speckle noise must not wall rooms off).
  for (std::size_t i = 0; i < n; ++i) {
    const int h = hole_label[i];
    const bool floor_speck = h >= 0 && !exterior[h] && void_of_hole[h] < 0 && map.cells[i] == MapCell::kUnknown;
    grid.free[i] = (slab_label[i] == 0 && map.cells[i] == MapCell::kFree) || floor_speck;
  }
  compute_clearance(&grid);
  SurveyConfig survey;
  survey.clearance = config.clearance;
  const double plan_clearance = config.clearance + survey.plan_margin_cells * res;
  std::vector<std::uint8_t> passable(n);
  for (std::size_t i = 0; i < n; ++i) passable[i] = grid.free[i] && grid.clearance[i] >= plan_clearance;
  const std::vector<int> reach_label = label_regions(passable, cols, rows, false, &sizes);
  if (sizes.empty())
    throw InputError("no free cell of the map is " + fmt(plan_clearance) +
                     " m from every occupied or unknown cell: no survey path (try a smaller --clearance)");

  // The tour's region: the passable region holding the most rooms' interior points (or the largest).
  std::vector<int> rooms_in(sizes.size(), 0);
  for (const Polygon2& room : room_cells) {
    Vec2 p;
    int c, r;
    if (most_interior_point(grid, room, &p) && grid.frame.cell_of(p, &c, &r)) {
      const int id = reach_label[grid.frame.index(c, r)];
      if (id >= 0) ++rooms_in[id];
    }
  }
  int main_id = 0;
  for (std::size_t id = 1; id < sizes.size(); ++id) {
    if (std::tie(rooms_in[id], sizes[id]) > std::tie(rooms_in[main_id], sizes[main_id])) main_id = static_cast<int>(id);
  }
  WalkableGrid reach = grid;  // free only where the tour can go; clearances unchanged
  for (std::size_t i = 0; i < n; ++i) reach.free[i] = reach_label[i] == main_id;

  std::vector<SurveyStop> stops;
  std::vector<std::string> stop_names;
  Scene& scene = out.scene;
  for (std::size_t k = 0; k < room_cells.size(); ++k) {
    Room room;
    room.name = "room_" + std::to_string(k + 1);
    room.level = 0;
    room.polygon = transform(room_cells[k], 1.0, map);
    Vec2 p;
    if (most_interior_point(reach, room_cells[k], &p)) {
      stops.push_back({0, p});
      stop_names.push_back(room.name);
    } else {
      const Vec2 at = centroid(room.polygon);
      out.warnings.push_back("room '" + room.name + "' (centre [" + fmt(at.x()) + ", " + fmt(at.y()) + "], " +
                             fmt(area(room.polygon), 1) + " m²) cannot be reached keeping " + fmt(config.clearance) +
                             " m from every occupied or unknown cell: left out of the survey path");
    }
    scene.rooms.push_back(room);
  }
  if (room_cells.empty()) {
    // Cover the free space: a stop in each tile of the tour's region.
    int c0 = cols, c1 = -1, r0 = rows, r1 = -1;
    for (std::size_t i = 0; i < n; ++i) {
      if (!reach.free[i]) continue;
      const int c = static_cast<int>(i % cols), r = static_cast<int>(i / cols);
      c0 = std::min(c0, c), c1 = std::max(c1, c), r0 = std::min(r0, r), r1 = std::max(r1, r);
    }
    const int tile = std::max(1, static_cast<int>(std::lround(config.coverage_tile / res)));
    const int nx = (c1 - c0) / tile + 1, ny = (r1 - r0) / tile + 1;
    for (int ty = 0; ty < ny; ++ty) {
      for (int tx = 0; tx < nx; ++tx) {
        const Vec2 lo = res * Vec2(c0 + tx * tile, r0 + ty * tile), hi = lo + Vec2::Constant(res * tile);
        const Polygon2 box = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
        Vec2 p;
        if (!most_interior_point(reach, box, &p)) continue;
        stops.push_back({0, p});
        stop_names.push_back("tile " + std::to_string(tx) + "," + std::to_string(ty));
      }
    }
  }
  if (stops.empty()) throw InputError("no room can be reached keeping the clearance: no survey path");
  if (stops.size() == 1) {
    // One place to visit: go to the reachable cell farthest from it and back.
    std::size_t best = 0;
    double best_d = -1.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!reach.free[i]) continue;
      const double d = (grid.frame.center(i) - stops[0].xy).squaredNorm();
      if (d > best_d) best_d = d, best = i;
    }
    if (best_d < 1e-12) throw InputError("the free space that keeps the clearance is a single cell: no survey path");
    stops.push_back({0, grid.frame.center(best)});
    stop_names.push_back("the far end of the free space");
  }
  std::vector<Waypoint> lap;
  try {
    lap = plan_survey({reach}, {}, stops, survey, [&](std::size_t i) { return stop_names[i]; });
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("import_map: ") + e.what());  // the stops were checked: a bug
  }

  // The scene, in the world frame.
  scene.name = config.name;
  if (!apply_preset(config.sensor_preset, &scene.sensor))
    throw InputError("--sensor: unknown sensor preset '" + config.sensor_preset + "'");
  scene.sensor.preset = config.sensor_preset;
  scene.sensor.mount_height = config.mount_height;
  Level level;
  level.name = "L0";
  level.elevation = 0.0;
  level.ceiling = config.ceiling;
  level.slab = transform(floor_outlines.front(), res, map);
  for (std::size_t v = 1; v < floor_outlines.size(); ++v) level.voids.push_back(transform(floor_outlines[v], res, map));
  scene.levels.push_back(level);
  VoxelMap walls;
  walls.file = config.voxel_file;
  walls.voxel_size = res;
  walls.level = 0;
  walls.label = VoxelLabel::kWall;
  walls.offset = Eigen::Vector3d(map.origin.x(), map.origin.y(), 0.0);
  walls.yaw_deg = map.yaw * 180.0 / M_PI;
  if (!out.voxels.empty()) scene.voxel_maps.push_back(walls);
  TrajectorySpec& t = scene.trajectory;
  t.level = 0;
  for (Waypoint w : lap) {
    w.xy = map.to_world(w.xy);
    t.waypoints.push_back(w);
  }
  t.closed = true;
  t.laps = config.laps;
  t.speed = config.speed;
  t.yaw_rate_deg = config.yaw_rate_deg;
  // The distance to the nearest blocked cell's edge, at most: the raster's centre-to-centre
  // distance less a half diagonal.
  const ClearanceAt clearance_at = [&](const Vec2& xy, double, int) {
    return grid.clearance_at(map.to_map(xy)) - kCellEdgeBound * res;
  };
  keep_clearance_on_turns(&scene, clearance_at, survey);
  const PathClearance worst = path_clearance(scene, clearance_at);
  stats.min_path_clearance = worst.min_clearance;
  if (worst.min_clearance < config.clearance) {
    out.warnings.push_back("the survey path comes " + fmt(worst.min_clearance) +
                           " m from an occupied or unknown cell at [" + fmt(worst.where.x()) + ", " +
                           fmt(worst.where.y()) + "], less than " + fmt(config.clearance) + " m");
  }
  stats.path_length = Trajectory(scene).length() / std::max(1, config.laps);
  return out;
}

}  // namespace tsgraphs::scene
