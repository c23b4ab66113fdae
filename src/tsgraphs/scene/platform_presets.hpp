#pragma once
/// The platforms a scene's sensor can ride (scene format `platform:`) and their defaults.
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::scene {

/// Each type's defaults (docs/scene-format.md): wheeled none of the motion and scans taken at
/// one instant (the format before platforms); handheld and legged their gait, scans swept.
PlatformSpec platform_defaults(PlatformType type);
/// "wheeled", "handheld", "legged".
const char* platform_name(PlatformType type);
/// The type of a name above, none for another.
std::optional<PlatformType> platform_type(const std::string& name);
/// The names above, in order.
const std::vector<std::string>& platform_names();

}  // namespace tsgraphs::scene
