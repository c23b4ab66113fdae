#pragma once
/// The scenes of scenes/*.yaml, compiled into the library so commands work from any folder.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tsgraphs::scene {

/// (name, YAML text) of every built-in scene, sorted by name.
const std::vector<std::pair<std::string, std::string>>& builtin_scenes();

std::vector<std::string> builtin_scene_names();
/// The YAML text of a built-in scene, or nothing for an unknown name.
std::optional<std::string> builtin_scene_text(const std::string& name);

}  // namespace tsgraphs::scene
