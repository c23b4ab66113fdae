#pragma once
/// Geometry queries on a scene (no ray casting): the solid pieces of walls, the ceiling's
/// holes, and the walkable surface height.
#include <vector>

#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::scene {

/// The solid pieces of a wall once its openings are cut out: boxes along the wall given by
/// [s0, s1] along its centre line and [z0, z1] above its level.
struct WallPiece {
  double s0, s1, z0, z1;
};
std::vector<WallPiece> wall_pieces(const Wall& wall);

/// The glass panes of a wall's glazed openings (Opening::transmission < 1): each fills its
/// opening, [s0, s1] along the centre line and [z0, z1] above the level, and lets rays pass
/// with that probability. Solid pieces (wall_pieces) and panes together close the wall.
struct GlassPane {
  double s0, s1, z0, z1;
  double transmission;
};
std::vector<GlassPane> glass_panes(const Wall& wall);

/// Region of the ceiling of `level`: its slab minus its voids and the next level up's voids.
std::vector<Polygon2> ceiling_holes(const Scene& scene, int level);

/// The walkable surface height at `xy` on `level` (the level's elevation, or a ramp's height
/// where a ramp joining that level covers the point); false when nothing walkable is there.
bool walkable_height(const Scene& scene, int level, const Vec2& xy, double* z);

/// Height of a ramp's surface at `xy` (which need not be inside the footprint).
double ramp_height(const Scene& scene, const Ramp& ramp, const Vec2& xy);

/// Sets each wall's joined_from / joined_to: an end that meets an end of another wall of its
/// level, so that the wall reaches half its thickness past it and the corner is closed. The
/// loader calls it; so does anything that builds a scene in memory.
void join_wall_ends(Scene* scene);

/// The level whose walkable surface at `xy` is nearest to height `floor_z` and within
/// `tolerance` of it; `fallback` when there is none (a pose between storeys, off the slab).
int level_under(const Scene& scene, const Vec2& xy, double floor_z, double tolerance, int fallback);

}  // namespace tsgraphs::scene
