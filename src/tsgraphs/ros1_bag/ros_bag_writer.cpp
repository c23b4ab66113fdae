// A sequence written as a ROS 1 bag through rosbag_storage.
#include "tsgraphs/ros1_bag/ros_bag.hpp"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/ros1_bag/ros_bag_internal.hpp"

namespace tsgraphs::ros1_bag {

using ros_bag_internal::kTfStaticTopic;

namespace {

namespace fs = std::filesystem;

geometry_msgs::Pose message_of(const Pose3& T) {
  geometry_msgs::Pose p;
  p.position.x = T.translation().x();
  p.position.y = T.translation().y();
  p.position.z = T.translation().z();
  const Eigen::Quaterniond q(T.linear());
  p.orientation.w = q.w();
  p.orientation.x = q.x();
  p.orientation.y = q.y();
  p.orientation.z = q.z();
  return p;
}

/// rosbag's record time: the stamp, or its earliest allowed time for a stamp of 0.
ros::Time record_time(double t) { return std::max(ros::Time(t), ros::TIME_MIN); }

}  // namespace

void write_bag(const io::ScanSequence& sequence, const std::string& path, BagCompression compression,
               const Pose3& sensor_to_base) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  try {
    rosbag::Bag bag(tmp, rosbag::bagmode::Write);
    bag.setCompression(compression == BagCompression::bz2   ? rosbag::compression::BZ2
                       : compression == BagCompression::lz4 ? rosbag::compression::LZ4
                                                            : rosbag::compression::Uncompressed);
    const io::SequenceInfo& info = sequence.info();
    const double first = info.times.empty() ? 0.0 : info.times.front();
    tf2_msgs::TFMessage tf;
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time(first);
    t.header.frame_id = "base_link";
    t.child_frame_id = "lidar";
    const geometry_msgs::Pose p = message_of(sensor_to_base);
    t.transform.translation.x = p.position.x;
    t.transform.translation.y = p.position.y;
    t.transform.translation.z = p.position.z;
    t.transform.rotation = p.orientation;
    tf.transforms.push_back(t);
    bag.write(kTfStaticTopic, record_time(first), tf);
    const Pose3 base_to_sensor = sensor_to_base.inverse();
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const ros::Time stamp(info.times[i]);
      const PointCloud cloud = sequence.scan(i);
      sensor_msgs::PointCloud2 pc;
      pc.header.stamp = stamp;
      pc.header.frame_id = "lidar";
      pc.height = 1;
      pc.width = static_cast<std::uint32_t>(cloud.size());
      // A swept scan's per-point times as Velodyne's driver writes them: float32 `time`,
      // seconds after the stamp.
      const bool timed = cloud.has_times();
      for (const char* name : {"x", "y", "z", "intensity", "time"}) {
        if (!timed && std::string(name) == "time") continue;
        sensor_msgs::PointField f;
        f.name = name;
        f.offset = static_cast<std::uint32_t>(4 * pc.fields.size());
        f.datatype = sensor_msgs::PointField::FLOAT32;
        f.count = 1;
        pc.fields.push_back(f);
      }
      pc.point_step = static_cast<std::uint32_t>(4 * pc.fields.size());
      pc.row_step = pc.point_step * pc.width;
      pc.is_dense = true;
      pc.data.resize(pc.row_step);
      for (std::size_t k = 0; k < cloud.size(); ++k) {
        const float v[5] = {cloud.points[k].x(), cloud.points[k].y(), cloud.points[k].z(),
                            cloud.has_intensity() ? cloud.intensity[k] : 0.0f, timed ? cloud.times[k] : 0.0f};
        std::memcpy(pc.data.data() + pc.point_step * k, v, pc.point_step);
      }
      bag.write("/points", record_time(info.times[i]), pc);
      nav_msgs::Odometry odom;
      odom.header.stamp = stamp;
      odom.header.frame_id = "odom";
      odom.child_frame_id = "base_link";
      odom.pose.pose = message_of(info.odometry[i] * base_to_sensor);
      bag.write("/odom", record_time(info.times[i]), odom);
      if (i < info.groundtruth.size()) {
        geometry_msgs::PoseStamped gt;
        gt.header.stamp = stamp;
        gt.header.frame_id = "world";
        gt.pose = message_of(info.groundtruth[i]);
        bag.write("/groundtruth", record_time(info.times[i]), gt);
      }
    }
    bag.close();
  } catch (const rosbag::BagException& e) {
    fs::remove(tmp);
    throw input_error(path, 0, std::string("cannot write the bag: ") + e.what());
  } catch (...) {
    fs::remove(tmp);
    throw;
  }
  fs::rename(tmp, path);
}

}  // namespace tsgraphs::ros1_bag
