#pragma once
/// Sensor presets (beam layouts and ranges from the makers' datasheets) and beam geometry.
#include <string>
#include <vector>

#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::scene {

/// Names accepted by `sensor.preset`.
const std::vector<std::string>& preset_names();

/// Fills `spec` with the named preset's fields (channels, columns, field of view, beam
/// table, ranges, rate, noise); installation fields (mount, tilt, dropout) are kept.
/// Returns false for an unknown name.
bool apply_preset(const std::string& name, SensorSpec* spec);

/// `channels` elevations from `max_deg` down to `min_deg`, evenly spaced.
std::vector<double> evenly_spaced_angles(int channels, double min_deg, double max_deg);

}  // namespace tsgraphs::scene
