#pragma once
/// Where one can stand on a level, as a raster: the walkable surface (slab minus voids, the
/// ramps that join the level) minus what stands on it (walls outside their doors, railings,
/// furniture), with each free cell's clearance to the nearest blocked cell. Survey paths are
/// planned on it (survey_path.hpp); imported occupancy maps arrive in the same form.
#include <cstdint>
#include <vector>

#include "tsgraphs/core/grid_frame.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::scene {

using tsgraphs::GridFrame;

/// A frame covering every level's slab of `scene` with `margin` metres around.
GridFrame frame_covering(const Scene& scene, double resolution, double margin);

/// One level's free space for planning.
struct WalkableGrid {
  int level = 0;  ///< index into Scene::levels (or 0 for an imported map)
  GridFrame frame;
  std::vector<std::uint8_t> free;  ///< 1 where one may stand, one per cell
  std::vector<float> clearance;    ///< m from the cell's centre to the nearest blocked cell's centre

  bool is_free(int c, int r) const { return frame.inside(c, r) && free[frame.index(c, r)] != 0; }
  /// Clearance at the cell holding `p`; 0 outside the raster or on a blocked cell.
  double clearance_at(const Vec2& p) const;
};

/// Heights that decide what blocks a walker (a robot or a person).
struct WalkableRules {
  double headroom =
      2.0;  ///< m: a wall piece, box or railing starting below this blocks; above it is walked under
  double step = 0.25;  ///< m: what ends this little above the feet is stepped over (and a surface
                       ///< this far from them is not the walker's)
};

/// The free space of `level` on `frame`: a cell is free when its centre is on the walkable
/// surface (walkable_height) and inside no blocking wall piece (walls' solid pieces that begin
/// below the headroom: everything but the lintels over doors), railing or box. Clearances
/// are computed (compute_clearance).
WalkableGrid rasterise_walkable(const Scene& scene, int level, const GridFrame& frame,
                                const WalkableRules& rules = {});

/// Fills grid->clearance with the exact Euclidean distance transform of the blocked cells
/// (Felzenszwalb and Huttenlocher's two-pass lower envelope), in metres. Cells outside the
/// raster count as blocked.
void compute_clearance(WalkableGrid* grid);

/// The distance from a walker standing at `xy` on a surface at height `floor_z` to the
/// nearest thing that stops it, computed on the scene's geometry rather than a raster:
/// blocking wall pieces, railings and boxes of any level whose heights meet the walker's
/// (above its knees, below the headroom: on a ramp the walls of the storey below fall away
/// under it), exactly; and the edge of the walkable surface (walkable_height within a step of
/// floor_z, probed on rings of radius up to `probe_radius`, so a result >= probe_radius means
/// "at least probe_radius").
double obstacle_distance(const Scene& scene, const Vec2& xy, double floor_z, double probe_radius,
                         const WalkableRules& rules = {});

}  // namespace tsgraphs::scene
