// `tsgraphs bag-info` for ROS 1 bags: each topic's type, count and rate.
#include "tsgraphs/ros1_bag/ros_bag.hpp"

#include <ros/exception.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <cstdio>
#include <map>
#include <string>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/ros1_bag/ros_bag_internal.hpp"

namespace tsgraphs::ros1_bag {

using ros_bag_internal::check_bag;
using ros_bag_internal::is_bag_file;
using ros_bag_internal::RosbagLines;

std::string bag_info(const std::string& path) {
  if (!is_bag_file(path)) throw input_error(path, 0, "no such bag");
  check_bag(path);
  const RosbagLines rosbag_lines;
  try {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    rosbag::View view(bag);
    struct Topic {
      std::string type;
      std::size_t count = 0;
      double first = 0.0, last = 0.0;
    };
    std::map<std::string, Topic> topics;
    for (const rosbag::ConnectionInfo* c : view.getConnections()) topics[c->topic].type = c->datatype;
    for (const rosbag::MessageInstance& m : view) {
      Topic& t = topics[m.getTopic()];
      const double s = m.getTime().toSec();
      if (t.count == 0) t.first = s;
      t.last = s;
      ++t.count;
    }
    std::string out = path + ": " + std::to_string(view.size()) + " messages, " +
                      std::to_string(view.getEndTime().toSec() - view.getBeginTime().toSec()) + " s\n";
    for (const auto& [name, t] : topics) {
      char line[512];
      const double rate = t.count > 1 && t.last > t.first ? (t.count - 1) / (t.last - t.first) : 0.0;
      std::snprintf(line, sizeof(line), "  %-32s %-28s %8zu msgs  %7.2f Hz\n", name.c_str(), t.type.c_str(),
                    t.count, rate);
      out += line;
    }
    for (const std::string& line : rosbag_lines.lines()) out += "  warning: rosbag: " + line + "\n";
    return out;
  } catch (const ros::Exception& e) {
    throw input_error(path, 0, std::string("cannot read the bag: ") + e.what() + rosbag_lines.last());
  }
}

}  // namespace tsgraphs::ros1_bag
