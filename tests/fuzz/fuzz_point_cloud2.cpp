/// Fuzz target: a serialized sensor_msgs/PointCloud2 (ROS1 wire format) taken apart and its
/// points decoded, as the bag reader does with each message.
#include "fuzz_support.hpp"
#include "tsgraphs/io/point_cloud2.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  fuzz::only_input_errors("point_cloud2", [&] {
    const io::PointCloud2Message message = io::parse_point_cloud2_message(data, size, "fuzz");
    io::decode_point_cloud2(message.layout, data + message.data_offset, message.data_size, "fuzz");
  });
  return 0;
}
