#pragma once
/// Bird's-eye SVG of a scene: walls with doors and windows, railings, voids, boxes, ramps,
/// ground-truth rooms with their names, and the path with its direction; one panel per level.
#include <string>

#include "tsgraphs/scene/scene.hpp"
#include "tsgraphs/scene/trajectory.hpp"

namespace tsgraphs::report {

/// The SVG document text for `scene`, with the planned `trajectory` drawn on the levels it
/// crosses (its first lap, coloured along time, with arrows for the direction of travel).
std::string scene_svg(const scene::Scene& scene, const scene::Trajectory& trajectory);

}  // namespace tsgraphs::report
