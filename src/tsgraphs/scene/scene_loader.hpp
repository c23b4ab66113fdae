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

/// Bounds of a recording: laps of the path, and scans in all (28 hours at 10 Hz, terabytes of
/// scans); a scene beyond them is refused before any scan is made.
inline constexpr int kMaxLaps = 10000;
inline constexpr double kMaxSequenceScans = 1e6;

/// The scans the scene's path makes at its recording rate (sensor.record_hz, else rate_hz).
double sequence_scans(const Scene& scene);

}  // namespace tsgraphs::scene
