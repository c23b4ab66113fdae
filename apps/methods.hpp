#pragma once
/// The room-layer modes the demo and the suites compare: TS-graphs, S-Graphs+ and the two
/// ablations (docs/demo.md), each a free-space method and a room trigger.
#include <string>

namespace tsgraphs::app {

struct Method {
  const char* name;
  const char* slug;  ///< run folder name (suffix in the demo)
  const char* free_space;
  const char* room_trigger;
};

inline constexpr Method kMethods[] = {
    {"TS-graphs", "ts-graphs", "traversable", "flush"},
    {"S-Graphs+", "s-graphs-plus", "esdf", "timer"},
    {"ablation: traversable + timer", "traversable-timer", "traversable", "timer"},
    {"ablation: esdf + flush", "esdf-flush", "esdf", "flush"},
};

/// The method of `slug`, nullptr for none.
inline const Method* find_method(const std::string& slug) {
  for (const Method& m : kMethods)
    if (slug == m.slug) return &m;
  return nullptr;
}

/// "ts-graphs, s-graphs-plus, ...", for messages.
inline std::string method_slugs() {
  std::string out;
  for (const Method& m : kMethods) out += (out.empty() ? "" : ", ") + std::string(m.slug);
  return out;
}

}  // namespace tsgraphs::app
