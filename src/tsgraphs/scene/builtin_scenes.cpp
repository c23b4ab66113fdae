#include "tsgraphs/scene/builtin_scenes.hpp"

namespace tsgraphs::scene {

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : builtin_scenes()) names.push_back(name);
  return names;
}

std::optional<std::string> builtin_scene_text(const std::string& name) {
  for (const auto& [n, text] : builtin_scenes()) {
    if (n == name) return text;
  }
  return std::nullopt;
}

}  // namespace tsgraphs::scene
