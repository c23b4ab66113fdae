#include "tsgraphs/generator/generator.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/generator/building_styles.hpp"
#include "tsgraphs/generator/clutter.hpp"
#include "tsgraphs/generator/door_leaves.hpp"
#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/generator/furnishing.hpp"
#include "tsgraphs/generator/generator_storeys.hpp"
#include "tsgraphs/generator/random.hpp"
#include "tsgraphs/generator/room_shapes.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/survey_path.hpp"
#include "tsgraphs/scene/trajectory.hpp"
#include "tsgraphs/scene/walkable_grid.hpp"
#include "tsgraphs/generator/windows.hpp"

namespace tsgraphs::generator {
namespace {

using internal::Building;
using internal::draw_building;
using internal::kSlabThickness;
using internal::rect_polygon;
using internal::Storey;

// Storeys.
constexpr double kExtraDoorChance = 0.2;  // of a room getting a second door into a neighbour room

// The platform.
constexpr double kPersonSpeedMin = 0.8;  // m/s: people walk at these paces
constexpr double kPersonSpeedMax = 1.5;
constexpr int kPersonStretchMax = 5;  // survey waypoints one person walks between (at least 2)
constexpr int kPersonDraws = 20;      // stretches drawn for one person before giving up on them
constexpr double kYawRateMin = 60.0;  // deg/s at corners
constexpr double kYawRateMax = 120.0;
constexpr double kDriftMin = 0.002;  // odometry drift per metre (and per radian) travelled
constexpr double kDriftMax = 0.03;

// Realistic buildings.
constexpr double kPassageSlack = 0.3;  // m a passage left by clutter or a door leaf has beyond the path's
                                       // two clearances: the planner's raster margin and room to turn
constexpr std::uint64_t kRealisticSalt =
    400;  // the realistic draws' own stream per storey (after 100 + i, 200 + i)

// Checks.
constexpr double kRoomOverlapArea = 1e-4;  // m^2 two ground-truth rooms may share (rounding)
constexpr double kLevelMatch = 0.3;        // m between a pose's floor height and its level

/// Storey `level`'s doors, walls and furniture into `scene` (its level exists); for a
/// realistic building its rooms reshaped first, then windows, door leaves and clutter.
void build_storey(Storey* s, int level, const GeneratorConfig& config, Rng& rng, scene::Scene* scene) {
  const std::uint64_t i = static_cast<std::uint64_t>(level);
  Rng doors = rng.fork(100 + i);
  // Drawn only for a realistic building: without it the main stream is as it always was.
  Rng real = config.realistic ? rng.fork(kRealisticSalt + i) : Rng(0);
  if (config.realistic && s->plan.ground_truth) shape_rooms(&s->plan, real);
  connect_spaces(&s->plan, doors);
  // Some rooms get a second door into a neighbour room.
  const std::size_t n = s->plan.spaces.size();
  for (std::size_t a = 0; a < n; ++a) {
    if (s->plan.spaces[a].kind != SpaceKind::kRoom || !doors.chance(kExtraDoorChance)) continue;
    for (std::size_t c = 0; c < n; ++c) {
      if (c == a || s->plan.spaces[c].kind != SpaceKind::kRoom) continue;
      if (!shared_boundary(s->plan, static_cast<int>(a), static_cast<int>(c)).empty()) {
        s->plan.doors.push_back(random_door(static_cast<int>(a), static_cast<int>(c), doors));
        break;
      }
    }
  }
  if (config.realistic) draw_door_widths(&s->plan, real);
  const PlanResult result = add_floor_plan(s->plan, level, scene);
  const double passage = 2.0 * config.clearance + kPassageSlack;
  std::vector<OrientedRect> leaves;
  if (config.realistic) {
    add_windows(s->plan, result, real, scene);
    // Furniture keeps a passage round each leaf (on top of its own spacing).
    for (OrientedRect r : hang_door_leaves(s->plan, result, level, passage, real, scene)) {
      r.size += Vec2::Constant(2.0 * passage);
      leaves.push_back(r);
    }
  }
  Rng furniture = rng.fork(200 + i);
  furnish(s->plan, result, level, furniture, scene, leaves);
  if (config.realistic) add_clutter(s->plan, result, level, passage, real, scene);
}

/// The platform: sensor, drift and path speed.
void draw_platform(scene::Scene* scene, Rng& rng, const GeneratorConfig& config) {
  scene::apply_preset(rng.pick(scene::preset_names()), &scene->sensor);
  scene->sensor.mount_height = rng.uniform(config.mount_height_min, config.mount_height_max);
  const double drift = rng.uniform(kDriftMin, kDriftMax);
  scene->odometry.trans_noise_per_m = drift;
  scene->odometry.yaw_noise_per_rad = rng.uniform(kDriftMin, kDriftMax);
  scene->odometry.yaw_noise_per_m = 0.2 * drift;
  scene->trajectory.speed = rng.uniform(config.speed_min, config.speed_max);
  scene->trajectory.yaw_rate_deg = rng.uniform(kYawRateMin, kYawRateMax);
  // The path is planned over two laps (every corner a lap turns, the laps after repeat them);
  // its laps are set once it is planned (attempt_building).
  scene->trajectory.laps = std::min(config.laps, 2);
  scene->trajectory.closed = true;
}

/// Places the survey path visits: every ground-truth room's most interior point, and in
/// large rooms one more per coverage tile.
std::vector<scene::SurveyStop> survey_stops(const scene::Scene& scene,
                                            const std::vector<scene::WalkableGrid>& grids,
                                            const std::vector<int>& grid_of_level,
                                            const GeneratorConfig& config, std::vector<std::string>* names) {
  std::vector<scene::SurveyStop> stops;
  const double min_clearance = config.clearance + 2.0 * config.grid_resolution;
  // Corridors first, so that the tour starts in one.
  std::vector<std::size_t> order(scene.rooms.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_partition(order.begin(), order.end(), [&](std::size_t i) {
    return scene.rooms[i].name.find("corridor") != std::string::npos;
  });
  for (std::size_t i : order) {
    const scene::Room& room = scene.rooms[i];
    const int g = grid_of_level[room.level];
    Vec2 p;
    if (g < 0 || !scene::most_interior_point(grids[g], room.polygon, &p)) continue;
    stops.push_back({g, p});
    names->push_back(room.name);
    if (area(room.polygon) < config.coverage_area) continue;
    Vec2 lo = room.polygon.front(), hi = lo;
    for (const Vec2& q : room.polygon) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const double t = config.coverage_spacing;
    for (double x = lo.x(); x < hi.x() - 0.25 * t; x += t) {
      for (double y = lo.y(); y < hi.y() - 0.25 * t; y += t) {
        const Polygon2 tile = clip_to_convex(room.polygon, rect_polygon({x, y}, {x + t, y + t}));
        Vec2 q;
        if (tile.size() < 3 || !scene::most_interior_point(grids[g], tile, &q)) continue;
        if (grids[g].clearance_at(q) < min_clearance || (q - p).norm() < 0.5 * t) continue;
        stops.push_back({g, q});
        names->push_back(room.name + " (coverage)");
      }
    }
  }
  return stops;
}

std::uint64_t seed_of(const std::string& style, std::uint64_t seed, int attempt) {
  std::uint64_t h = 1469598103934665603ULL;
  for (char c : style) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  Rng mix(h ^ (seed * 0x9E3779B97F4A7C15ULL) ^ (static_cast<std::uint64_t>(attempt) << 48));
  return mix.next();
}

/// `count` people, each walking a stretch of two to kPersonStretchMax consecutive waypoints of
/// the survey path on one level's flat floor (clear of walls and boxes as the path is), there
/// and back. A person whose draws all fall on ramps or level changes is left out.
void add_people(int count, Rng& rng, scene::Scene* scene) {
  const std::vector<scene::Waypoint>& w = scene->trajectory.waypoints;
  const auto on_flat_floor = [&](int level, const Vec2& xy) {
    double z = 0.0;
    return scene::walkable_height(*scene, level, xy, &z) &&
           std::abs(z - scene->levels[level].elevation) < 1e-6;
  };
  for (int i = 0; i < count; ++i) {
    for (int draw = 0; draw < kPersonDraws; ++draw) {
      const int first = rng.integer(0, static_cast<int>(w.size()) - 2);
      const std::size_t points = static_cast<std::size_t>(rng.integer(2, kPersonStretchMax));
      scene::Person p;
      p.level = w[first].level;
      for (std::size_t k = first; k < w.size() && p.path.size() < points && w[k].level == p.level; ++k) {
        if (!on_flat_floor(p.level, w[k].xy)) break;
        if (p.path.empty() || (w[k].xy - p.path.back()).norm() > 1e-3) p.path.push_back(w[k].xy);
      }
      if (p.path.size() < 2) continue;
      double length = 0.0;
      for (std::size_t k = 1; k < p.path.size(); ++k) length += (p.path[k] - p.path[k - 1]).norm();
      p.speed = rng.uniform(kPersonSpeedMin, kPersonSpeedMax);
      p.offset = rng.uniform(0.0, 2.0 * length);
      scene->people.push_back(std::move(p));
      break;
    }
  }
}

/// The path passes a limit of core/limits.hpp with the laps asked for.
struct RecordingOverLimits : InputError {
  using InputError::InputError;
};

/// The scene's levels, one per storey, each a slab above the ceiling of the one below.
void add_levels(const Building& b, scene::Scene* scene) {
  double elevation = 0.0;
  for (const Storey& s : b.storeys) {
    scene::Level l;
    l.name = s.name;
    l.elevation = elevation;
    l.ceiling = s.ceiling;
    l.slab = s.slab;
    scene->levels.push_back(l);
    elevation += s.ceiling + kSlabThickness;
  }
}

/// The planning rasters of the walked storeys, and each level's index into them (-1: not walked).
struct WalkedGrids {
  std::vector<scene::WalkableGrid> grids;
  std::vector<int> grid_of_level;
};

WalkedGrids walked_grids(const scene::Scene& scene, const Building& b, const GeneratorConfig& config) {
  const GridFrame frame = scene::frame_covering(scene, config.grid_resolution, 0.5);
  WalkedGrids out;
  out.grid_of_level.assign(scene.levels.size(), -1);
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    if (!b.storeys[i].walked) continue;
    out.grid_of_level[i] = static_cast<int>(out.grids.size());
    out.grids.push_back(scene::rasterise_walkable(scene, static_cast<int>(i), frame));
  }
  return out;
}

/// The survey path over the walked storeys, in place of the scene's first path, its turns kept
/// clear of obstacles.
void plan_survey_path(const Building& b, const GeneratorConfig& config, scene::Scene* scene) {
  const WalkedGrids walked = walked_grids(*scene, b, config);
  const std::vector<scene::WalkableGrid>& grids = walked.grids;
  const std::vector<int>& grid_of_level = walked.grid_of_level;
  std::vector<scene::GridLink> links;
  for (const scene::Ramp& r : scene->ramps)
    links.push_back({grid_of_level[r.from_level], grid_of_level[r.to_level], r.polygon});
  std::vector<std::string> names;
  const std::vector<scene::SurveyStop> stops = survey_stops(*scene, grids, grid_of_level, config, &names);
  if (stops.empty()) throw std::runtime_error("no room to visit");
  scene::SurveyConfig survey;
  survey.clearance = config.clearance;
  scene->trajectory.waypoints =
      scene::plan_survey(grids, links, stops, survey, [&](std::size_t i) { return names[i]; });
  scene->trajectory.level = scene->trajectory.waypoints.front().level;
  // Exact distances where the raster says an obstacle may be near; the raster's elsewhere.
  const double near = config.clearance + 4.0 * config.grid_resolution;
  const auto clearance_at = [&](const Vec2& xy, double floor_z, int level) {
    const int g = grid_of_level[level];
    const double raster = g < 0 ? 0.0 : grids[g].clearance_at(xy);
    return raster > near ? raster : scene::obstacle_distance(*scene, xy, floor_z, config.clearance + 0.05);
  };
  scene::keep_clearance_on_turns(scene, clearance_at, survey);
}

/// The scene file of the finished scene and what it loads to; throws when a check fails.
GeneratedBuilding scene_file(const scene::Scene& scene, const std::string& style, std::uint64_t seed,
                             int attempt, const GeneratorConfig& config) {
  GeneratedBuilding out;
  std::ostringstream header;
  header << "Generated by `tsgraphs generate --style " << style << " --seed " << seed
         << (config.realistic ? " --realistic" : "") << "` (docs/generator.md).\n"
         << "Ground truth: every room, hall and corridor segment bounded by walls, doors and railings.";
  out.yaml = scene::scene_yaml(scene, header.str());
  out.scene = scene::parse_scene(out.yaml, scene.name + ".yaml", ".");
  out.attempts = attempt + 1;
  const std::vector<std::string> problems = check_building(out.scene, config.clearance);
  if (!problems.empty()) {
    throw std::runtime_error(problems.front());
  }
  return out;
}

/// One attempt: the building, its furniture and its path; throws when any part does not hold.
GeneratedBuilding attempt_building(const std::string& style, std::uint64_t seed, int attempt,
                                   const GeneratorConfig& config) {
  Rng rng(seed_of(style, seed, attempt));
  scene::Scene scene;
  scene.name = style + "_" + std::to_string(seed);
  scene.seed = seed;
  draw_platform(&scene, rng, config);
  Building b = draw_building(style, config.size, config.realistic, rng);
  add_levels(b, &scene);
  for (std::size_t i = 0; i < b.storeys.size(); ++i)
    build_storey(&b.storeys[i], static_cast<int>(i), config, rng, &scene);
  scene.ramps = b.ramps;
  scene::join_wall_ends(&scene);
  // A first path so that the scene loads; the survey path replaces it.
  int first_walked = 0;
  while (!b.storeys[first_walked].walked) ++first_walked;
  scene.trajectory.level = first_walked;
  scene.trajectory.waypoints = {{Vec2::Zero(), first_walked, 0}, {Vec2::Zero(), first_walked, 0}};
  plan_survey_path(b, config, &scene);
  scene.trajectory.laps = config.laps;
  if (const std::string over = scene::recording_over_limits(scene); !over.empty())
    throw RecordingOverLimits("--laps: " + over);
  // Last, from a draw of its own: a building with people is the same building without them.
  if (config.people > 0) {
    Rng walkers = rng.fork(300);
    add_people(config.people, walkers, &scene);
  }
  return scene_file(scene, style, seed, attempt, config);
}

}  // namespace

const std::vector<std::string>& building_style_names() {
  static const std::vector<std::string> names = {"office",    "atrium",       "library", "open_plan",
                                                 "irregular", "multi_storey", "mixed"};
  return names;
}

GeneratedBuilding generate_building(const std::string& style, std::uint64_t seed,
                                    const GeneratorConfig& config) {
  const auto& names = building_style_names();
  if (std::find(names.begin(), names.end(), style) == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError("--style: unknown building style '" + style + "' (styles: " + list + ")");
  }
  // The scene file's seed is read back as a signed 64-bit number.
  if (seed > static_cast<std::uint64_t>(std::numeric_limits<long long>::max()))
    throw InputError("--seed: " + std::to_string(seed) + " is more than " +
                     std::to_string(std::numeric_limits<long long>::max()));
  if (config.laps < 1 || config.laps > limits::kMaxLaps)
    throw InputError("--laps: must be in [1, " + std::to_string(limits::kMaxLaps) + "]");
  if (config.people < 0 || config.people > kMaxGeneratedPeople)
    throw InputError("--people: must lie in [0, " + std::to_string(kMaxGeneratedPeople) + "]");
  std::string last;
  for (int attempt = 0; attempt < config.max_attempts; ++attempt) {
    try {
      return attempt_building(style, seed, attempt, config);
    } catch (const RecordingOverLimits&) {
      throw;  // another draw of the building would not shorten it
    } catch (const InputError& e) {
      last = e.what();
    } catch (const std::exception& e) {  // a layout that does not hold: draw another
      last = e.what();
    }
  }
  throw std::runtime_error("generate: no " + style + " building for seed " + std::to_string(seed) + " in " +
                           std::to_string(config.max_attempts) + " attempts (last: " + last + ")");
}

std::vector<std::string> check_building(const scene::Scene& scene, double clearance) {
  std::vector<std::string> problems = scene.warnings;
  const scene::Trajectory trajectory(scene);
  for (const std::string& w : trajectory.warnings()) problems.push_back("trajectory: " + w);
  const auto clearance_at = [&](const Vec2& xy, double floor_z, int) {
    return scene::obstacle_distance(scene, xy, floor_z, clearance + 0.05);
  };
  const double step = scene::SurveyConfig{}.check_step;  // the same sampling as the planner's own check
  const scene::PathClearance c = scene::path_clearance(scene, clearance_at, step);
  if (c.min_clearance < clearance) {
    std::ostringstream s;
    s << "the path comes " << c.min_clearance << " m from an obstacle at [" << c.where.x() << ", "
      << c.where.y() << "] (level " << scene.levels[c.level].name << "), less than " << clearance << " m";
    problems.push_back(s.str());
  }
  // Every room entered: a true pose inside it, on its level.
  std::vector<bool> entered(scene.rooms.size(), false);
  const double dt = step / scene.trajectory.speed;
  for (double t = 0.0; t <= trajectory.duration(); t += dt) {
    const Pose3 p = trajectory.body_pose(t);
    const int level = scene::level_under(scene, p.translation().head<2>(),
                                         p.translation().z() - scene.sensor.mount_height, kLevelMatch, -1);
    for (std::size_t i = 0; i < scene.rooms.size(); ++i) {
      if (!entered[i] && scene.rooms[i].level == level &&
          contains(scene.rooms[i].polygon, p.translation().head<2>()))
        entered[i] = true;
    }
  }
  for (std::size_t i = 0; i < scene.rooms.size(); ++i) {
    if (!entered[i]) problems.push_back("the path does not enter room '" + scene.rooms[i].name + "'");
  }
  for (std::size_t i = 0; i < scene.rooms.size(); ++i) {
    const scene::Room& a = scene.rooms[i];
    for (std::size_t j = i + 1; j < scene.rooms.size(); ++j) {
      const scene::Room& b = scene.rooms[j];
      if (a.level == b.level && intersection_area(a.polygon, b.polygon) > kRoomOverlapArea)
        problems.push_back("rooms '" + a.name + "' and '" + b.name + "' overlap");
    }
    const scene::Level& l = scene.levels[a.level];
    double outside = area(a.polygon) - intersection_area(a.polygon, l.slab);
    for (const Polygon2& v : l.voids) outside += intersection_area(a.polygon, v);
    if (outside > kRoomOverlapArea) problems.push_back("room '" + a.name + "' leaves the walkable slab");
  }
  return problems;
}

}  // namespace tsgraphs::generator
