#pragma once
/// The ROS 2 messages a bag gives the pipeline, in CDR (cdr.hpp), without ROS 2:
/// sensor_msgs/msg/PointCloud2, nav_msgs/msg/Odometry, geometry_msgs/msg/PoseStamped and
/// tf2_msgs/msg/TFMessage; and their definitions (ros2msg) as rosbag2 keeps them beside a
/// topic, so that a topic of another layout under the same name is refused.
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/io/point_cloud2.hpp"

namespace tsgraphs::ros2_bag::ros2 {

inline constexpr const char* kPointCloud2 = "sensor_msgs/msg/PointCloud2";
inline constexpr const char* kOdometry = "nav_msgs/msg/Odometry";
inline constexpr const char* kPoseStamped = "geometry_msgs/msg/PoseStamped";
inline constexpr const char* kTfMessage = "tf2_msgs/msg/TFMessage";

/// The ros2msg definition of one of the four types: its fields, then each type it uses after a
/// line of 80 '=' and "MSG: package/Type", as rosbag2 stores definitions in MCAP schemas.
/// std::invalid_argument for another type.
const std::string& definition(const std::string& type);
/// "" when the recorded definition `text` declares the fields this reader decodes for `type`
/// (its first section's fields, comments and constants aside, in order), else what differs.
/// An empty text (storages that keep none) is accepted.
std::string definition_mismatch(const std::string& type, const std::string& text);

/// A time in seconds as ROS splits it (ros::Time::fromSec: whole seconds, nanoseconds rounded),
/// in nanoseconds; header stamps are written so and read back as sec + 1e-9 nanosec, as ROS 1's.
std::uint64_t stamp_nanoseconds(double t);

/// A PointCloud2 message taken apart; data_offset counts from the start of `cdr`.
io::PointCloud2Message parse_point_cloud2(const std::string& cdr, const std::string& where);

/// A pose with its stamp and frames (Odometry: child_frame_id; PoseStamped: none).
struct StampedPoseMessage {
  double stamp = 0.0;  ///< header.stamp, s
  std::string frame_id, child_frame_id;
  Pose3 pose = Pose3::Identity();
};
StampedPoseMessage parse_odometry(const std::string& cdr, const std::string& where);
StampedPoseMessage parse_pose_stamped(const std::string& cdr, const std::string& where);

/// One transform of a TFMessage: T_parent_child.
struct TransformMessage {
  double stamp = 0.0;
  std::string parent, child;
  Pose3 transform = Pose3::Identity();
};
std::vector<TransformMessage> parse_tf_message(const std::string& cdr, const std::string& where);

/// Little-endian CDR of the same messages. A cloud is written as x y z intensity float32
/// (intensity 0 when it has none), and a swept scan's per-point times as float32 `time`
/// (seconds after the stamp, as Velodyne's driver writes them), unorganised, dense.
std::string encode_point_cloud2(double stamp, const std::string& frame_id, const PointCloud& cloud);
std::string encode_odometry(const StampedPoseMessage& m);
std::string encode_pose_stamped(const StampedPoseMessage& m);
std::string encode_tf_message(const std::vector<TransformMessage>& transforms);

}  // namespace tsgraphs::ros2_bag::ros2
