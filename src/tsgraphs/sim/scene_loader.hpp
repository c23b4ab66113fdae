#pragma once
/// Reading and validating scene files (docs/scene-format.md).
#include <string>

#include "tsgraphs/sim/scene.hpp"

namespace tsgraphs::sim {

/// Loads and validates a scene file. Every problem is an InputError naming the file, the
/// line and the key: unknown keys, missing slabs, zero-length walls, self-intersecting
/// polygons, openings wider than their wall, waypoints inside walls or off every slab,
/// unknown levels or presets, and out-of-range values.
Scene load_scene(const std::string& file);

/// The same from text; `file` names it in messages and relative paths resolve against
/// `base_dir`.
Scene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir);

/// The walkable surface height at `xy` on `level` (the level's elevation, or a ramp's height
/// where a ramp joining that level covers the point); false when nothing walkable is there.
bool walkable_height(const Scene& scene, int level, const Vec2& xy, double* z);

/// Height of a ramp's surface at `xy` (which need not be inside the footprint).
double ramp_height(const Scene& scene, const Ramp& ramp, const Vec2& xy);

}  // namespace tsgraphs::sim
