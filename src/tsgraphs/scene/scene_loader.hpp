#pragma once
/// Reading and validating scene files (docs/scene-format.md).
#include <string>

#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::scene {

/// Loads and validates a scene file. Every problem is an InputError naming the file, the
/// line and the key: unknown keys, missing slabs, zero-length walls, self-intersecting
/// polygons, openings wider than their wall, waypoints inside walls or off every slab,
/// unknown levels or presets, and out-of-range values.
Scene load_scene(const std::string& file);

/// The same from text; `file` names it in messages and relative paths resolve against
/// `base_dir`.
Scene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir);

}  // namespace tsgraphs::scene
