// `tsgraphs bag-info`: the topics of a bag.
#include <memory>
#include <string>

#include "command.hpp"
#include "commands.hpp"

namespace tsgraphs::app::cli {

Command add_bag_info(CLI::App& app, const GlobalOptions&) {
  auto bag = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("bag-info",
                                 "topics of a ROS1 bag or a rosbag2 recording: types, message counts, rates");
  cmd->add_option("BAG", *bag, "the .bag file, or the rosbag2 folder, .db3 or .mcap file")->required();
  return {cmd, [bag] {
            print_bag_info(*bag);
            return 0;
          }};
}

}  // namespace tsgraphs::app::cli
