#pragma once
/// Writing a scene as YAML in the scene format (docs/scene-format.md), so that generated
/// buildings and imported maps are ordinary scene files: parse_scene reads the text back to
/// the same scene (coordinates to 0.1 mm).
#include <string>

#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::scene {

/// The scene's YAML text. `header` (may be empty) is written first as comment lines.
/// Voxel-map paths are written as they are held.
std::string scene_yaml(const Scene& scene, const std::string& header = "");

}  // namespace tsgraphs::scene
