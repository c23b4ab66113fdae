#pragma once
/// The room-layer modes the demo and the suites compare: TS-graphs, S-Graphs+ and the two
/// ablations (docs/demo.md), each a free-space method and a room trigger.
#include <string>

#include "tsgraphs/room_layer/room_layer_config.hpp"

namespace tsgraphs::app {

struct Method {
  const char* name;
  const char* slug;  ///< run folder name (suffix in the demo)
  room_layer::FreeSpaceMethod free_space;
  room_layer::RoomTrigger room_trigger;
};

using room_layer::FreeSpaceMethod;
using room_layer::RoomTrigger;
inline constexpr Method kMethods[] = {
    {"TS-graphs", "ts-graphs", FreeSpaceMethod::traversable, RoomTrigger::flush},
    {"S-Graphs+", "s-graphs-plus", FreeSpaceMethod::esdf, RoomTrigger::timer},
    {"ablation: traversable + timer", "traversable-timer", FreeSpaceMethod::traversable, RoomTrigger::timer},
    {"ablation: esdf + flush", "esdf-flush", FreeSpaceMethod::esdf, RoomTrigger::flush},
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
