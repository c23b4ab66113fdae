// ROS 1 bags read through rosbag_storage: a topic's clouds placed by the odometry.
#include "tsgraphs/ros1_bag/ros_bag.hpp"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/exception.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <cstdint>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <set>
#include <stdexcept>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/recorded_sequence.hpp"
#include "tsgraphs/io/point_cloud2.hpp"
#include "tsgraphs/ros1_bag/ros_bag_internal.hpp"

namespace tsgraphs::ros1_bag {

using ros_bag_internal::BagLimits;
using ros_bag_internal::check_bag;
using ros_bag_internal::is_bag_file;
using ros_bag_internal::kLengthBytes;
using ros_bag_internal::kTfStaticTopic;
using ros_bag_internal::little_endian;
using ros_bag_internal::RosbagLines;

namespace {

constexpr const char* kCloudType = "sensor_msgs/PointCloud2";
constexpr const char* kOdometryType = "nav_msgs/Odometry";
constexpr const char* kPoseType = "geometry_msgs/PoseStamped";
// A TransformStamped serialized at its smallest: header (seq 4, stamp 8, empty frame_id 4), an
// empty child_frame_id (4), translation and rotation (7 doubles, 56).
constexpr std::uint64_t kMinTransformBytes = 76;

Pose3 pose_of(const geometry_msgs::Pose& p) {
  Pose3 T = Pose3::Identity();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  T.linear() = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
                   .normalized()
                   .toRotationMatrix();
  return T;
}

/// The serialized bytes of a message, refused when longer than any chunk of the bag.
std::vector<std::uint8_t> message_bytes(const rosbag::MessageInstance& m, const BagLimits& limits,
                                        const std::string& where) {
  const std::uint32_t n = m.size();
  if (n > limits.largest_chunk)
    throw input_error(where, 0,
                      "message of " + std::to_string(n) + " bytes, longer than any chunk of the bag (" +
                          std::to_string(limits.largest_chunk) + ")");
  std::vector<std::uint8_t> bytes(n);
  ros::serialization::OStream stream(bytes.data(), n);
  m.write(stream);
  return bytes;
}

}  // namespace

struct BagSequence::Impl {
  rosbag::Bag bag;
  BagLimits limits;
  std::vector<rosbag::MessageInstance> clouds;  ///< one per kept scan
  mutable std::mutex mutex;                     ///< rosbag reads seek one file
};

namespace {

/// Each topic's message type.
std::map<std::string, std::string> topic_types(const rosbag::Bag& bag) {
  rosbag::View all(bag);
  std::map<std::string, std::string> types;
  for (const rosbag::ConnectionInfo* c : all.getConnections()) types[c->topic] = c->datatype;
  return types;
}

/// An InputError unless the bag at `path` has `topic`, of one of the `wanted` types.
void require_topic(const std::string& path, const std::map<std::string, std::string>& types,
                   const std::string& topic, const std::set<std::string>& wanted) {
  const auto it = types.find(topic);
  if (it == types.end()) {
    std::string list;
    for (const auto& [t, type] : types) list += (list.empty() ? "" : ", ") + t;
    throw input_error(path, 0, "no topic " + topic + " (topics: " + list + ")");
  }
  if (!wanted.count(it->second)) {
    std::string names;
    for (const std::string& w : wanted) names += (names.empty() ? "" : " or ") + w;
    throw input_error(path, 0, topic + " is " + it->second + ", expected " + names);
  }
}

/// Odometry of the base: from the topic or the TUM file; none asked for is none.
std::vector<io::StampedBase> read_odometry(const rosbag::Bag& bag, const io::BagOptions& options,
                                           const std::map<std::string, std::string>& types) {
  std::vector<io::StampedBase> odom;
  if (!options.odom_topic.empty()) {
    require_topic(options.bag, types, options.odom_topic, {kOdometryType, kPoseType});
    rosbag::View view(bag, rosbag::TopicQuery(options.odom_topic));
    for (const rosbag::MessageInstance& m : view) {
      if (const auto o = m.instantiate<nav_msgs::Odometry>())
        odom.push_back({o->header.stamp.toSec(), pose_of(o->pose.pose)});
      else if (const auto p = m.instantiate<geometry_msgs::PoseStamped>())
        odom.push_back({p->header.stamp.toSec(), pose_of(p->pose)});
    }
  }
  io::add_tum_odometry(options, odom);
  return odom;
}

/// A cloud message and its stamp.
struct BagCloud {
  double t;
  rosbag::MessageInstance message;
};

/// The clouds of the points topic, in file order; `cloud_frame` is the first one's frame.
std::vector<BagCloud> read_clouds(const rosbag::Bag& bag, const io::BagOptions& options,
                                  const BagLimits& limits, std::string& cloud_frame) {
  std::vector<BagCloud> clouds;
  rosbag::View view(bag, rosbag::TopicQuery(options.points_topic));
  for (const rosbag::MessageInstance& m : view) {
    if (!m.isType<sensor_msgs::PointCloud2>()) continue;
    // Taken apart by hand: rosbag's deserializer allocates whatever a corrupt length says.
    const std::string where =
        options.bag + ": " + options.points_topic + ", message " + std::to_string(clouds.size());
    const std::vector<std::uint8_t> bytes = message_bytes(m, limits, where);
    const io::PointCloud2Message c = io::parse_point_cloud2_message(bytes.data(), bytes.size(), where);
    if (cloud_frame.empty()) cloud_frame = c.frame_id;
    clouds.push_back({c.stamp, m});
  }
  if (clouds.empty()) throw input_error(options.bag, 0, "no messages on " + options.points_topic);
  return clouds;
}

/// rosbag's deserializer sizes a TFMessage's transforms array from its length word before
/// reading a byte of it (found by fuzzing: 584 GB asked for): the word is checked here first.
void check_transform_count(const std::vector<std::uint8_t>& bytes, const std::string& where) {
  const std::uint64_t count = bytes.size() < kLengthBytes
                                  ? 0
                                  : little_endian(std::string(bytes.begin(), bytes.begin() + kLengthBytes));
  if (bytes.size() < kLengthBytes || count > (bytes.size() - kLengthBytes) / kMinTransformBytes) {
    throw input_error(where, 0,
                      "claims " + std::to_string(count) + " transforms, more than its " +
                          std::to_string(bytes.size()) + " bytes hold");
  }
}

/// The sensor-to-base transform of /tf_static: the last one whose child is `cloud_frame`, if any.
std::optional<Pose3> tf_static_mount(const rosbag::Bag& bag, const std::string& path, const BagLimits& limits,
                                     const std::string& cloud_frame) {
  std::optional<Pose3> mount;
  rosbag::View tf(bag, rosbag::TopicQuery(kTfStaticTopic));
  std::size_t index = 0;
  for (const rosbag::MessageInstance& m : tf) {
    if (!m.isType<tf2_msgs::TFMessage>()) continue;
    const std::string where = path + ": " + kTfStaticTopic + ", message " + std::to_string(index++);
    check_transform_count(message_bytes(m, limits, where), where);
    const auto msg = m.instantiate<tf2_msgs::TFMessage>();
    if (!msg) continue;
    for (const geometry_msgs::TransformStamped& t : msg->transforms) {
      if (t.child_frame_id != cloud_frame) continue;
      geometry_msgs::Pose p;
      p.position.x = t.transform.translation.x;
      p.position.y = t.transform.translation.y;
      p.position.z = t.transform.translation.z;
      p.orientation = t.transform.rotation;
      mount = pose_of(p);
    }
  }
  return mount;
}

}  // namespace

BagSequence::BagSequence(const io::BagOptions& options)
    : io::RecordedSequence(options.bag), impl_(std::make_unique<Impl>()) {
  const std::string& path = options.bag;
  if (!is_bag_file(path)) throw input_error(path, 0, "no such bag");
  if (options.points_topic.empty())
    throw input_error(path, 0, "no points topic given (--points-topic; see bag-info)");
  impl_->limits = check_bag(path);
  const RosbagLines rosbag_lines;
  try {
    impl_->bag.open(path, rosbag::bagmode::Read);
    const std::map<std::string, std::string> types = topic_types(impl_->bag);
    require_topic(path, types, options.points_topic, {kCloudType});
    std::vector<io::StampedBase> odom = read_odometry(impl_->bag, options, types);
    const bool has_odometry = !options.odom_topic.empty() || !options.odom_tum.empty();

    // The clouds, in stamp order; their frame finds the sensor-to-base transform.
    std::string cloud_frame;
    const std::vector<BagCloud> clouds = read_clouds(impl_->bag, options, impl_->limits, cloud_frame);
    if (options.sensor_to_base) {
      sensor_to_base_ = *options.sensor_to_base;
      sensor_to_base_known_ = true;
    } else if (types.count(kTfStaticTopic)) {
      if (const auto mount = tf_static_mount(impl_->bag, path, impl_->limits, cloud_frame)) {
        sensor_to_base_ = *mount;
        sensor_to_base_known_ = true;
      }
    }

    // Each scan's sensor pose, the odometry interpolated to its stamp (none without odometry:
    // run estimates it from the scans).
    std::vector<double> stamps;
    for (const BagCloud& c : clouds) stamps.push_back(c.t);
    for (const std::size_t i : place(stamps, std::move(odom), has_odometry, options.points_topic))
      impl_->clouds.push_back(clouds[i].message);
    for (const std::string& line : rosbag_lines.lines()) warnings_.push_back("rosbag: " + line);
  } catch (const ros::Exception& e) {  // rosbag's, and the deserializer's stream overruns
    throw input_error(path, 0, std::string("cannot read the bag: ") + e.what() + rosbag_lines.last());
  } catch (const std::bad_alloc&) {  // a message length that no memory holds: a corrupt bag
    throw input_error(path, 0, "cannot read the bag: a message claims more memory than there is (corrupt?)");
  } catch (const std::length_error&) {
    throw input_error(path, 0, "cannot read the bag: a message claims more memory than there is (corrupt?)");
  }
}

BagSequence::~BagSequence() = default;

PointCloud BagSequence::scan(std::size_t index) const {
  const rosbag::MessageInstance& m = impl_->clouds.at(index);
  const std::string where = name_ + ": " + m.getTopic() + ", scan " + std::to_string(index);
  std::vector<std::uint8_t> bytes;
  {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    const RosbagLines rosbag_lines;
    try {
      bytes = message_bytes(m, impl_->limits, where);
    } catch (const ros::Exception& e) {
      throw input_error(where, 0, e.what() + rosbag_lines.last());
    }
  }
  const io::PointCloud2Message msg = io::parse_point_cloud2_message(bytes.data(), bytes.size(), where);
  return io::decode_point_cloud2(msg.layout, bytes.data() + msg.data_offset, msg.data_size, where);
}

}  // namespace tsgraphs::ros1_bag
