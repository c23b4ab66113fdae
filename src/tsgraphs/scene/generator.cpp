#include "tsgraphs/scene/generator.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/scene/building_styles.hpp"
#include "tsgraphs/scene/clutter.hpp"
#include "tsgraphs/scene/door_leaves.hpp"
#include "tsgraphs/scene/floor_plan.hpp"
#include "tsgraphs/scene/furnishing.hpp"
#include "tsgraphs/scene/random.hpp"
#include "tsgraphs/scene/room_shapes.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/survey_path.hpp"
#include "tsgraphs/scene/trajectory.hpp"
#include "tsgraphs/scene/walkable_grid.hpp"
#include "tsgraphs/scene/windows.hpp"

namespace tsgraphs::scene {
namespace {

// Storeys.
constexpr double kCeilingMin = 2.6;  // m: ceiling heights
constexpr double kCeilingMax = 3.4;
constexpr double kSlabThickness = 0.3;    // m between a ceiling and the floor above
constexpr double kInteriorWallMin = 0.1;  // m: wall thicknesses
constexpr double kInteriorWallMax = 0.2;
constexpr double kFacadeMin = 0.2;
constexpr double kFacadeMax = 0.3;
constexpr double kGlassTransmissionMin = 0.5;  // glass railings let this share of rays through
constexpr double kGlassTransmissionMax = 0.9;
constexpr double kExtraDoorChance = 0.2;  // of a room getting a second door into a neighbour room

// Ramps between storeys (multi_storey).
constexpr double kRampSlopeMin =
    0.16;  // rise per run: 9 to 12 degrees (a robot's ramp, steeper than a wheelchair's)
constexpr double kRampSlopeMax = 0.21;
constexpr double kRampWidthMin = 1.8;  // m
constexpr double kRampWidthMax = 2.4;
constexpr double kGalleryMin = 1.6;  // m: the corridor along a ramp
constexpr double kGalleryMax = 2.6;
constexpr double kRampEndMin = 3.0;  // m of storey beyond each end of a ramp

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

struct StyleSize {
  double w_lo, w_hi, h_lo, h_hi;
};
StyleSize size_of(const std::string& style, double scale) {
  StyleSize z = style == "office"      ? StyleSize{14, 28, 9, 20}
                : style == "atrium"    ? StyleSize{18, 30, 16, 24}
                : style == "library"   ? StyleSize{18, 32, 14, 22}
                : style == "open_plan" ? StyleSize{20, 40, 15, 30}
                                       : StyleSize{14, 22, 14, 18};  // irregular: its second wing
  // Scaled down, but never below what the style needs.
  const Vec2 m = minimum_region(style);
  return {std::max(m.x(), z.w_lo * scale), std::max(m.x(), z.w_hi * scale), std::max(m.y(), z.h_lo * scale),
          std::max(m.y(), z.h_hi * scale)};
}

void fill(const std::string& style, FloorPlan* plan, const Region& r, Rng& rng, const std::string& prefix,
          IrregularVariant variant = IrregularVariant::kAny) {
  if (style == "office")
    fill_office(plan, r, rng, prefix);
  else if (style == "atrium")
    fill_atrium(plan, r, rng, prefix);
  else if (style == "library")
    fill_library(plan, r, rng, prefix);
  else if (style == "open_plan")
    fill_open_plan(plan, r, rng, prefix);
  else
    fill_irregular(plan, r, rng, prefix, variant);
}

Polygon2 rect_polygon(const Vec2& lo, const Vec2& hi) { return {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}}; }

/// Wings side by side along x, their floors at y = 0: a staircase outline.
Polygon2 staircase(const std::vector<Region>& wings) {
  Polygon2 pts = {wings.front().lo, {wings.back().hi.x(), 0.0}};
  for (int i = static_cast<int>(wings.size()) - 1; i >= 0; --i) {
    pts.push_back({wings[i].hi.x(), wings[i].hi.y()});
    pts.push_back({wings[i].lo.x(), wings[i].hi.y()});
  }
  Polygon2 out;
  for (const Vec2& p : pts) {
    if (out.empty() || (out.back() - p).norm() > 1e-9) out.push_back(p);
  }
  while (out.size() > 1 && (out.back() - out.front()).norm() < 1e-9) out.pop_back();
  Polygon2 simple;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Vec2 d0 = out[i] - out[(i + out.size() - 1) % out.size()], d1 = out[(i + 1) % out.size()] - out[i];
    if (std::abs(d0.x() * d1.y() - d0.y() * d1.x()) > 1e-12) simple.push_back(out[i]);
  }
  return simple;
}

/// A storey being built: its plan and where its slab is.
struct Storey {
  std::string name;
  FloorPlan plan;
  Polygon2 slab;
  double ceiling = 3.0;
  bool walked = true;
};

struct Building {
  std::vector<Storey> storeys;
  std::vector<Ramp> ramps;  ///< levels as storey indices
};

FloorPlanRules draw_rules(Rng& rng) {
  FloorPlanRules r;
  r.interior_wall = rng.uniform(kInteriorWallMin, kInteriorWallMax);
  r.exterior_wall = rng.uniform(kFacadeMin, kFacadeMax);
  const double u = rng.unit();
  r.railing = u < 1.0 / 3 ? RailingStyle::kSolid : u < 2.0 / 3 ? RailingStyle::kBars : RailingStyle::kGlass;
  r.glass_transmission = rng.uniform(kGlassTransmissionMin, kGlassTransmissionMax);
  return r;
}

/// An open lobby under an atrium: the storey below that its void shows.
Storey lobby_below(const Region& r, const FloorPlanRules& rules, double ceiling) {
  Storey s;
  s.name = "L0";
  s.plan.rules = rules;
  s.plan.ground_truth = false;
  s.plan.add_rect("lobby", SpaceKind::kHall, r.lo, r.hi, Furnishing::kLobby);
  s.slab = rect_polygon(r.lo, r.hi);
  s.ceiling = ceiling;
  s.walked = false;
  return s;
}

Building single_wing(const std::string& style, double scale, bool realistic, Rng& rng) {
  const StyleSize z = size_of(style, scale);
  const Region r{{0, 0}, {rng.uniform(z.w_lo, z.w_hi), rng.uniform(z.h_lo, z.h_hi)}};
  const FloorPlanRules rules = draw_rules(rng);
  const double ceiling = rng.uniform(kCeilingMin, kCeilingMax);
  Building b;
  if (style == "atrium") b.storeys.push_back(lobby_below(r, rules, rng.uniform(kCeilingMin, kCeilingMax)));
  Storey s;
  s.name = "L" + std::to_string(b.storeys.size());
  s.plan.rules = rules;
  s.plan.realistic = realistic;
  s.slab = rect_polygon(r.lo, r.hi);
  s.ceiling = ceiling;
  if (style == "irregular") {
    // Two wings: rooms merged into L and T shapes beside a diagonal corridor or a pentagonal ring.
    const double w0 = std::max(minimum_region("irregular").x(), rng.uniform(10.0, 15.0) * scale);
    const Region a{{0, 0}, {w0, r.hi.y()}}, c{{w0, 0}, {w0 + r.hi.x(), r.hi.y()}};
    fill("irregular", &s.plan, a, rng, "west_", IrregularVariant::kMergedRooms);
    fill("irregular", &s.plan, c, rng, "east_",
         rng.chance(0.5) ? IrregularVariant::kDiagonal : IrregularVariant::kPentagon);
    s.slab = rect_polygon(a.lo, c.hi);
  } else {
    fill(style, &s.plan, r, rng, "");
  }
  b.storeys.push_back(std::move(s));
  return b;
}

Building mixed(double scale, bool realistic, Rng& rng) {
  static const std::vector<std::string> kWingStyles = {"office", "atrium", "library", "open_plan",
                                                       "irregular"};
  const int n = rng.chance(0.7) ? 2 : 3;
  std::vector<std::string> styles;
  for (int i = 0; i < n; ++i) styles.push_back(rng.pick(kWingStyles));
  if (std::adjacent_find(styles.begin(), styles.end()) != styles.end() && n == 2)
    styles[1] = styles[0] == "office" ? "library" : "office";
  std::vector<Region> wings;
  double x = 0.0;
  for (const std::string& st : styles) {
    // Wings are smaller than whole buildings of their style.
    const StyleSize z = size_of(st, scale * 0.7);
    const double w = rng.uniform(z.w_lo, z.w_hi);
    const double h = rng.uniform(z.h_lo, z.h_hi);
    wings.push_back({{x, 0.0}, {x + w, h}});
    x += w;
  }
  const FloorPlanRules rules = draw_rules(rng);
  Building b;
  const auto atrium = std::find(styles.begin(), styles.end(), "atrium");
  if (atrium != styles.end())
    b.storeys.push_back(
        lobby_below(wings[atrium - styles.begin()], rules, rng.uniform(kCeilingMin, kCeilingMax)));
  Storey s;
  s.name = "L" + std::to_string(b.storeys.size());
  s.plan.rules = rules;
  s.plan.realistic = realistic;
  s.ceiling = rng.uniform(kCeilingMin, kCeilingMax);
  for (std::size_t i = 0; i < wings.size(); ++i)
    fill(styles[i], &s.plan, wings[i], rng, "wing" + std::to_string(i + 1) + "_");
  s.slab = staircase(wings);
  b.storeys.push_back(std::move(s));
  return b;
}

Building multi_storey(double scale, bool realistic, Rng& rng) {
  static const std::vector<std::string> kGround = {"office", "library", "open_plan", "irregular"};
  static const std::vector<std::string> kUpper = {"office", "library", "open_plan", "irregular", "atrium"};
  const int n = rng.chance(0.8) ? 2 : 3;
  const double ceiling = rng.uniform(kCeilingMin, 3.0);
  const double rise = ceiling + kSlabThickness;
  const double run = rise / rng.uniform(kRampSlopeMin, kRampSlopeMax);
  const double wr = rng.uniform(kRampWidthMin, kRampWidthMax), wg = rng.uniform(kGalleryMin, kGalleryMax);
  const double ws = wr + wg;
  const double W = run + rng.uniform(2 * kRampEndMin + 1.0, 2 * kRampEndMin + 4.0);
  const double H =
      std::max(minimum_region("office").y(), rng.uniform(8.0, 13.0) * scale) + ws * (n == 3 ? 2 : 1);
  const FloorPlanRules rules = draw_rules(rng);
  Building b;
  // Ramp k joins storeys k and k + 1: along the south facade for even k, the north for odd.
  struct RampPlace {
    bool south;
    double x0;
  };
  std::vector<RampPlace> places;
  for (int k = 0; k + 1 < n; ++k)
    places.push_back({k % 2 == 0, rng.uniform(kRampEndMin, W - run - kRampEndMin)});
  for (int j = 0; j < n; ++j) {
    Storey s;
    s.name = "L" + std::to_string(j);
    s.plan.rules = rules;
    s.plan.realistic = realistic;
    s.ceiling = ceiling;
    s.slab = rect_polygon({0, 0}, {W, H});
    double y_lo = 0.0, y_hi = H;
    for (int k = 0; k + 1 < n; ++k) {
      if (k != j && k + 1 != j) continue;
      const RampPlace& p = places[k];
      const bool lower = k == j;
      const double s0 = p.south ? 0.0 : H - wr, s1 = p.south ? wr : H;      // the ramp's strip
      const double g0 = p.south ? wr : H - ws, g1 = p.south ? ws : H - wr;  // the gallery beside it
      if (p.south)
        y_lo = ws;
      else
        y_hi = H - ws;
      const std::string side = s.name + "_" + (p.south ? "south_" : "north_");
      const int gallery = s.plan.add_rect(side + "gallery", SpaceKind::kCorridor, {0, g0}, {W, g1});
      const int west =
          s.plan.add_rect(side + (lower ? "landing" : "balcony"), SpaceKind::kCorridor, {0, s0}, {p.x0, s1});
      s.plan.open_joints.push_back({gallery, west});
      if (lower) {
        const int ramp = s.plan.add_rect(side + "ramp", SpaceKind::kRamp, {p.x0, s0}, {p.x0 + run, s1});
        s.plan.open_joints.push_back({west, ramp});
        const int store =
            s.plan.add_rect(side + "store", SpaceKind::kRoom, {p.x0 + run, s0}, {W, s1}, Furnishing::kOffice);
        s.plan.doors.push_back(random_door(store, gallery, rng));
        Ramp r;
        r.from_level = j;
        r.to_level = j + 1;
        r.polygon = rect_polygon({p.x0, s0}, {p.x0 + run, s1});
        r.axis = Vec2::UnitX();
        b.ramps.push_back(r);
      } else {
        const int well = s.plan.add_rect(side + "ramp_well", SpaceKind::kVoid, {p.x0, s0}, {p.x0 + run, s1});
        const int top = s.plan.add_rect(side + "landing", SpaceKind::kCorridor, {p.x0 + run, s0}, {W, s1});
        s.plan.open_joints.push_back({gallery, top});
        s.plan.no_railing.push_back({well, top});
      }
    }
    const std::string st = rng.pick(j == 0 ? kGround : kUpper);
    fill(st, &s.plan, {{0, y_lo}, {W, y_hi}}, rng, s.name + "_");  // names unique over the storeys
    b.storeys.push_back(std::move(s));
  }
  return b;
}

/// Storey `level`'s doors, walls and furniture into `scene` (its level exists); for a
/// realistic building its rooms reshaped first, then windows, door leaves and clutter.
void build_storey(Storey* s, int level, const GeneratorConfig& config, Rng& rng, Scene* scene) {
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
void draw_platform(Scene* scene, Rng& rng, const GeneratorConfig& config) {
  apply_preset(rng.pick(preset_names()), &scene->sensor);
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
std::vector<SurveyStop> survey_stops(const Scene& scene, const std::vector<WalkableGrid>& grids,
                                     const std::vector<int>& grid_of_level, const GeneratorConfig& config,
                                     std::vector<std::string>* names) {
  std::vector<SurveyStop> stops;
  const double min_clearance = config.clearance + 2.0 * config.grid_resolution;
  // Corridors first, so that the tour starts in one.
  std::vector<std::size_t> order(scene.rooms.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_partition(order.begin(), order.end(), [&](std::size_t i) {
    return scene.rooms[i].name.find("corridor") != std::string::npos;
  });
  for (std::size_t i : order) {
    const Room& room = scene.rooms[i];
    const int g = grid_of_level[room.level];
    Vec2 p;
    if (g < 0 || !most_interior_point(grids[g], room.polygon, &p)) continue;
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
        if (tile.size() < 3 || !most_interior_point(grids[g], tile, &q)) continue;
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

/// One attempt: the building, its furniture and its path; throws when any part does not hold.
/// `count` people, each walking a stretch of two to kPersonStretchMax consecutive waypoints of
/// the survey path on one level's flat floor (clear of walls and boxes as the path is), there
/// and back. A person whose draws all fall on ramps or level changes is left out.
void add_people(int count, Rng& rng, Scene* scene) {
  const std::vector<Waypoint>& w = scene->trajectory.waypoints;
  const auto on_flat_floor = [&](int level, const Vec2& xy) {
    double z = 0.0;
    return walkable_height(*scene, level, xy, &z) && std::abs(z - scene->levels[level].elevation) < 1e-6;
  };
  for (int i = 0; i < count; ++i) {
    for (int draw = 0; draw < kPersonDraws; ++draw) {
      const int first = rng.integer(0, static_cast<int>(w.size()) - 2);
      const std::size_t points = static_cast<std::size_t>(rng.integer(2, kPersonStretchMax));
      Person p;
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

GeneratedBuilding attempt_building(const std::string& style, std::uint64_t seed, int attempt,
                                   const GeneratorConfig& config) {
  Rng rng(seed_of(style, seed, attempt));
  Scene scene;
  scene.name = style + "_" + std::to_string(seed);
  scene.seed = seed;
  draw_platform(&scene, rng, config);
  Building b = style == "mixed"          ? mixed(config.size, config.realistic, rng)
               : style == "multi_storey" ? multi_storey(config.size, config.realistic, rng)
                                         : single_wing(style, config.size, config.realistic, rng);
  double elevation = 0.0;
  for (const Storey& s : b.storeys) {
    Level l;
    l.name = s.name;
    l.elevation = elevation;
    l.ceiling = s.ceiling;
    l.slab = s.slab;
    scene.levels.push_back(l);
    elevation += s.ceiling + kSlabThickness;
  }
  for (std::size_t i = 0; i < b.storeys.size(); ++i)
    build_storey(&b.storeys[i], static_cast<int>(i), config, rng, &scene);
  scene.ramps = b.ramps;
  join_wall_ends(&scene);
  // A first path so that the scene loads; the survey path replaces it.
  int first_walked = 0;
  while (!b.storeys[first_walked].walked) ++first_walked;
  scene.trajectory.level = first_walked;
  scene.trajectory.waypoints = {{Vec2::Zero(), first_walked, 0}, {Vec2::Zero(), first_walked, 0}};

  // The survey path over the walked storeys.
  const GridFrame frame = frame_covering(scene, config.grid_resolution, 0.5);
  std::vector<WalkableGrid> grids;
  std::vector<int> grid_of_level(scene.levels.size(), -1);
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    if (!b.storeys[i].walked) continue;
    grid_of_level[i] = static_cast<int>(grids.size());
    grids.push_back(rasterise_walkable(scene, static_cast<int>(i), frame));
  }
  std::vector<GridLink> links;
  for (const Ramp& r : scene.ramps)
    links.push_back({grid_of_level[r.from_level], grid_of_level[r.to_level], r.polygon});
  std::vector<std::string> names;
  const std::vector<SurveyStop> stops = survey_stops(scene, grids, grid_of_level, config, &names);
  if (stops.empty()) throw std::runtime_error("no room to visit");
  SurveyConfig survey;
  survey.clearance = config.clearance;
  scene.trajectory.waypoints =
      plan_survey(grids, links, stops, survey, [&](std::size_t i) { return names[i]; });
  scene.trajectory.level = scene.trajectory.waypoints.front().level;
  // Exact distances where the raster says an obstacle may be near; the raster's elsewhere.
  const double near = config.clearance + 4.0 * config.grid_resolution;
  const auto clearance_at = [&](const Vec2& xy, double floor_z, int level) {
    const int g = grid_of_level[level];
    const double raster = g < 0 ? 0.0 : grids[g].clearance_at(xy);
    return raster > near ? raster : obstacle_distance(scene, xy, floor_z, config.clearance + 0.05);
  };
  keep_clearance_on_turns(&scene, clearance_at, survey);
  scene.trajectory.laps = config.laps;
  if (const std::string over = recording_over_limits(scene); !over.empty())
    throw RecordingOverLimits("--laps: " + over);
  // Last, from a draw of its own: a building with people is the same building without them.
  if (config.people > 0) {
    Rng walkers = rng.fork(300);
    add_people(config.people, walkers, &scene);
  }

  GeneratedBuilding out;
  std::ostringstream header;
  header << "Generated by `tsgraphs generate --style " << style << " --seed " << seed
         << (config.realistic ? " --realistic" : "") << "` (docs/generator.md).\n"
         << "Ground truth: every room, hall and corridor segment bounded by walls, doors and railings.";
  out.yaml = scene_yaml(scene, header.str());
  out.scene = parse_scene(out.yaml, scene.name + ".yaml", ".");
  out.attempts = attempt + 1;
  const std::vector<std::string> problems = check_building(out.scene, config.clearance);
  if (!problems.empty()) {
    throw std::runtime_error(problems.front());
  }
  return out;
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

std::vector<std::string> check_building(const Scene& scene, double clearance) {
  std::vector<std::string> problems = scene.warnings;
  const Trajectory trajectory(scene);
  for (const std::string& w : trajectory.warnings()) problems.push_back("trajectory: " + w);
  const auto clearance_at = [&](const Vec2& xy, double floor_z, int) {
    return obstacle_distance(scene, xy, floor_z, clearance + 0.05);
  };
  const double step = SurveyConfig{}.check_step;  // the same sampling as the planner's own check
  const PathClearance c = path_clearance(scene, clearance_at, step);
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
    const int level = level_under(scene, p.translation().head<2>(),
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
    const Room& a = scene.rooms[i];
    for (std::size_t j = i + 1; j < scene.rooms.size(); ++j) {
      const Room& b = scene.rooms[j];
      if (a.level == b.level && intersection_area(a.polygon, b.polygon) > kRoomOverlapArea)
        problems.push_back("rooms '" + a.name + "' and '" + b.name + "' overlap");
    }
    const Level& l = scene.levels[a.level];
    double outside = area(a.polygon) - intersection_area(a.polygon, l.slab);
    for (const Polygon2& v : l.voids) outside += intersection_area(a.polygon, v);
    if (outside > kRoomOverlapArea) problems.push_back("room '" + a.name + "' leaves the walkable slab");
  }
  return problems;
}

}  // namespace tsgraphs::scene
