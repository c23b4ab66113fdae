/// Fuzz target: ROS 2 messages in CDR through each of the four parsers (PointCloud2 with its
/// points decoded, Odometry, PoseStamped, TFMessage) on the same bytes.
#include "fuzz_support.hpp"
#include "tsgraphs/io/point_cloud2.hpp"
#include "tsgraphs/ros2_bag/ros2_messages.hpp"

namespace ros2 = tsgraphs::ros2_bag::ros2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string cdr(reinterpret_cast<const char*>(data), size);
  tsgraphs::fuzz::only_input_errors("parse_point_cloud2", [&] {
    const tsgraphs::io::PointCloud2Message m = ros2::parse_point_cloud2(cdr, "message");
    tsgraphs::io::decode_point_cloud2(m.layout, data + m.data_offset, m.data_size, "message");
  });
  tsgraphs::fuzz::only_input_errors("parse_odometry", [&] { ros2::parse_odometry(cdr, "message"); });
  tsgraphs::fuzz::only_input_errors("parse_pose_stamped", [&] { ros2::parse_pose_stamped(cdr, "message"); });
  tsgraphs::fuzz::only_input_errors("parse_tf_message", [&] { ros2::parse_tf_message(cdr, "message"); });
  return 0;
}
