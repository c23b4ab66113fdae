#pragma once
/// Survey paths: a closed tour that visits given places (each room's most interior point,
/// or points that cover the free space) over the free space of one or more levels, keeping
/// a clearance from every obstacle. Used by generated buildings and imported maps.
#include <functional>
#include <string>
#include <vector>

#include "tsgraphs/scene/scene.hpp"
#include "tsgraphs/scene/walkable_grid.hpp"

namespace tsgraphs::scene {

struct SurveyConfig {
  double clearance = 0.35;          ///< m kept from every obstacle by the whole path
  double plan_margin_cells = 1.0;   ///< planned this many cells wider still: the raster's error
  double simplify_tolerance = 0.2;  ///< m a straight leg may stray from the raster's shortest path
  double centre_weight = 0.3;  ///< m: a step costs (1 + centre_weight / clearance), so paths keep mid-aisle
  double stub_length = 0.1;    ///< m before a corner where the path stops to turn in place
  int max_turn_fixes = 200;    ///< corners made turns in place at most, per path
  double check_step = 0.02;    ///< m of travel between the poses whose clearance is checked
};

/// A place the tour must visit: a point on grid `grid` (an index into the grids given).
struct SurveyStop {
  int grid = 0;
  Vec2 xy = Vec2::Zero();
};

/// Where the free space of two grids is one place (a ramp's footprint): a walker may pass
/// from one to the other anywhere inside `area`.
struct GridLink {
  int grid_a = 0, grid_b = 0;
  Polygon2 area;
};

/// The point of `grid` inside `region` farthest from every obstacle (ties: the lowest cell
/// index); false when no free cell's centre lies in `region`.
bool most_interior_point(const WalkableGrid& grid, const Polygon2& region, Vec2* point);

/// One lap of a closed tour through every stop, starting at stops[0]: stops ordered by
/// nearest neighbour and then 2-opt over their path costs, each leg the cheapest raster path
/// through cells with clearance >= clearance + plan_margin_cells * resolution, simplified to
/// straight legs that keep to such cells. Waypoints carry the level of their grid
/// (WalkableGrid::level); a waypoint where the path passes between grids carries the new
/// one. Throws std::invalid_argument naming the stop when a stop lies on no such cell or
/// cannot be reached from stops[0]; `describe(i)` names stop i in that message.
std::vector<Waypoint> plan_survey(const std::vector<WalkableGrid>& grids, const std::vector<GridLink>& links,
                                  const std::vector<SurveyStop>& stops, const SurveyConfig& config,
                                  const std::function<std::string(std::size_t)>& describe = {});

/// Distance from a walker at `xy`, standing at height `floor_z` on level `level`, to the
/// nearest obstacle: for checking a planned path.
using ClearanceAt = std::function<double(const Vec2& xy, double floor_z, int level)>;

/// Where the smoothed path that the simulator drives (Trajectory: corners taken on arcs) comes
/// closer than `config.clearance` to an obstacle at a corner, makes that corner a turn in
/// place (a waypoint `stub_length` before it, so the arc no longer fits). Returns the
/// smallest clearance left along the whole path (all laps), sampled every `check_step`.
double keep_clearance_on_turns(Scene* scene, const ClearanceAt& clearance_at, const SurveyConfig& config);

/// The smallest clearance along the scene's planned path (all laps), sampled every `step`
/// metres of travel, and where it occurs.
struct PathClearance {
  double min_clearance = 0.0;
  Vec2 where = Vec2::Zero();
  int level = 0;
};
PathClearance path_clearance(const Scene& scene, const ClearanceAt& clearance_at, double step = 0.02);

}  // namespace tsgraphs::scene
