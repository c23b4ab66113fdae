/// Fuzz target: ROS1 bags through bag-info and through the sequence `run --bag` reads (its
/// first scans decoded), with the topics the seed bags have.
#include <algorithm>

#include "fuzz_support.hpp"
#include "tsgraphs/ros1_bag/ros_bag.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  const std::string file = fuzz::input_file(data, size, "run.bag");
  fuzz::only_input_errors("bag_info", [&] { ros1_bag::bag_info(file); });
  fuzz::only_input_errors("BagSequence", [&] {
    io::BagOptions options;
    options.bag = file;
    options.points_topic = "/points";
    options.odom_topic = "/odom";
    const ros1_bag::BagSequence sequence(options);
    for (std::size_t i = 0; i < std::min<std::size_t>(sequence.size(), 4); ++i) sequence.scan(i);
  });
  return 0;
}
