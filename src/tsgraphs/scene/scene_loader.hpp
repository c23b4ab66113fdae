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

/// The scans the scene's path makes at its recording rate (sensor.record_hz, else rate_hz),
/// from two laps of the path whatever its laps (a path of 10,000 laps is not built to count them).
double sequence_scans(const Scene& scene);

/// Why the scene's recording passes the limits of core/limits.hpp (its laps, or the scans its
/// path makes), as a phrase naming the figure and the limit; "" when it keeps within them. Every
/// command that sets a scene's laps checks this before it builds the path.
std::string recording_over_limits(const Scene& scene);

}  // namespace tsgraphs::scene
