// `tsgraphs bag-info` for rosbag2 recordings: the storage files, each topic's type, count and rate.
#include "tsgraphs/ros2_bag/rosbag2.hpp"

#include <cstdio>

#include "tsgraphs/ros2_bag/rosbag2_internal.hpp"

namespace tsgraphs::ros2_bag {

using namespace rosbag2_internal;

std::string rosbag2_info(const std::string& path) {
  const auto storages = open_recording(path);
  std::string out =
      path + ": " + std::to_string(storages.size()) + " file" + (storages.size() == 1 ? "" : "s") + "\n";
  for (const auto& [name, t] : topics_of(storages, path)) {
    const std::vector<Located> m = messages_of(storages, name);
    const double span = m.size() >= 2 ? 1e-9 * static_cast<double>(m.back().time - m.front().time) : 0.0;
    char line[512];
    std::snprintf(line, sizeof line, "  %-24s %-32s %8zu msgs", name.c_str(), t.type.c_str(), m.size());
    out += line;
    if (span > 0) {
      std::snprintf(line, sizeof line, "  %8.2f Hz", static_cast<double>(m.size() - 1) / span);
      out += line;
    }
    out += "\n";
  }
  for (const auto& s : storages) {
    for (const std::string& w : s->warnings()) out += "  warning: " + w + "\n";
  }
  return out;
}

}  // namespace tsgraphs::ros2_bag
