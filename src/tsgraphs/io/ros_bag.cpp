// ROS1 bags through rosbag_storage. The only file of tsgraphs that sees ROS types.
#include "tsgraphs/io/ros_bag.hpp"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <cstring>
#include <unistd.h>
#include <set>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/point_cloud2.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs::io {

namespace {

namespace fs = std::filesystem;

constexpr const char* kCloudType = "sensor_msgs/PointCloud2";
constexpr const char* kOdometryType = "nav_msgs/Odometry";
constexpr const char* kPoseType = "geometry_msgs/PoseStamped";
constexpr const char* kTfStaticTopic = "/tf_static";

struct StampedBase {
  double t = 0.0;
  Pose3 pose = Pose3::Identity();
};

Pose3 pose_of(const geometry_msgs::Pose& p) {
  Pose3 T = Pose3::Identity();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  T.linear() = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
                   .normalized()
                   .toRotationMatrix();
  return T;
}

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

/// The pose at time t between two samples: position linear, rotation slerp.
Pose3 interpolate(const StampedBase& a, const StampedBase& b, double t) {
  const double s = b.t > a.t ? (t - a.t) / (b.t - a.t) : 0.0;
  Pose3 T = Pose3::Identity();
  T.translation() = (1.0 - s) * a.pose.translation() + s * b.pose.translation();
  T.linear() = Eigen::Quaterniond(a.pose.linear()).slerp(s, Eigen::Quaterniond(b.pose.linear())).toRotationMatrix();
  return T;
}

/// rosbag's record time: the stamp, or its earliest allowed time for a stamp of 0.
ros::Time record_time(double t) { return std::max(ros::Time(t), ros::TIME_MIN); }

}  // namespace

struct BagSequence::Impl {
  rosbag::Bag bag;
  std::vector<rosbag::MessageInstance> clouds;  ///< one per kept scan
  mutable std::mutex mutex;                     ///< rosbag reads seek one file
};

BagSequence::BagSequence(const BagOptions& options) : impl_(std::make_unique<Impl>()), name_(options.bag) {
  const std::string& path = options.bag;
  if (!fs::is_regular_file(path)) throw input_error(path, 0, "no such bag");
  if (options.points_topic.empty()) throw input_error(path, 0, "no points topic given (--points-topic; see bag-info)");
  try {
    impl_->bag.open(path, rosbag::bagmode::Read);
    rosbag::View all(impl_->bag);
    std::map<std::string, std::string> types;
    for (const rosbag::ConnectionInfo* c : all.getConnections()) types[c->topic] = c->datatype;
    const auto require = [&](const std::string& topic, std::set<std::string> wanted) {
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
    };
    require(options.points_topic, {kCloudType});

    // Odometry of the base: from the topic or the TUM file.
    std::vector<StampedBase> odom;
    if (!options.odom_topic.empty()) {
      require(options.odom_topic, {kOdometryType, kPoseType});
      rosbag::View view(impl_->bag, rosbag::TopicQuery(options.odom_topic));
      for (const rosbag::MessageInstance& m : view) {
        if (const auto o = m.instantiate<nav_msgs::Odometry>()) odom.push_back({o->header.stamp.toSec(), pose_of(o->pose.pose)});
        else if (const auto p = m.instantiate<geometry_msgs::PoseStamped>())
          odom.push_back({p->header.stamp.toSec(), pose_of(p->pose)});
      }
    } else if (!options.odom_tum.empty()) {
      for (const StampedPose& p : read_tum(options.odom_tum)) odom.push_back({p.t, p.pose});
    }
    std::stable_sort(odom.begin(), odom.end(), [](const StampedBase& a, const StampedBase& b) { return a.t < b.t; });
    const bool has_odometry = !options.odom_topic.empty() || !options.odom_tum.empty();
    if (has_odometry && odom.empty())
      throw input_error(path, 0, "no odometry messages on " + (options.odom_topic.empty() ? options.odom_tum : options.odom_topic));

    // The clouds, in stamp order; their frame finds the sensor-to-base transform.
    struct Cloud {
      double t;
      rosbag::MessageInstance message;
    };
    std::vector<Cloud> clouds;
    std::string cloud_frame;
    rosbag::View view(impl_->bag, rosbag::TopicQuery(options.points_topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto c = m.instantiate<sensor_msgs::PointCloud2>();
      if (!c) continue;
      if (cloud_frame.empty()) cloud_frame = c->header.frame_id;
      clouds.push_back({c->header.stamp.toSec(), m});
    }
    if (clouds.empty()) throw input_error(path, 0, "no messages on " + options.points_topic);
    // In stamp order (messages cannot be reassigned: order their indices).
    std::vector<std::size_t> order(clouds.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return clouds[a].t < clouds[b].t; });

    if (options.sensor_to_base) {
      sensor_to_base_ = *options.sensor_to_base;
      sensor_to_base_known_ = true;
    } else if (types.count(kTfStaticTopic)) {
      rosbag::View tf(impl_->bag, rosbag::TopicQuery(kTfStaticTopic));
      for (const rosbag::MessageInstance& m : tf) {
        const auto msg = m.instantiate<tf2_msgs::TFMessage>();
        if (!msg) continue;
        for (const geometry_msgs::TransformStamped& t : msg->transforms) {
          if (t.child_frame_id != cloud_frame) continue;
          geometry_msgs::Pose p;
          p.position.x = t.transform.translation.x;
          p.position.y = t.transform.translation.y;
          p.position.z = t.transform.translation.z;
          p.orientation = t.transform.rotation;
          sensor_to_base_ = pose_of(p);
          sensor_to_base_known_ = true;
        }
      }
    }

    // Each scan's sensor pose, the odometry interpolated to its stamp (none without odometry:
    // run estimates it from the scans).
    std::size_t k = 0;
    for (const std::size_t i : order) {
      const Cloud& c = clouds[i];
      if (!has_odometry) {
        info_.times.push_back(c.t);
        impl_->clouds.push_back(c.message);
        continue;
      }
      if (c.t < odom.front().t || c.t > odom.back().t) {
        ++dropped_;
        continue;
      }
      while (k + 1 < odom.size() && odom[k + 1].t < c.t) ++k;
      const Pose3 base = k + 1 < odom.size() ? interpolate(odom[k], odom[k + 1], c.t) : odom[k].pose;
      info_.times.push_back(c.t);
      info_.odometry.push_back(base * sensor_to_base_);
      impl_->clouds.push_back(c.message);
    }
    if (info_.times.empty())
      throw input_error(path, 0, "no scan on " + options.points_topic + " lies within the odometry's time span");
  } catch (const rosbag::BagException& e) {
    throw input_error(path, 0, std::string("cannot read the bag: ") + e.what());
  }
}

BagSequence::~BagSequence() = default;

PointCloud BagSequence::scan(std::size_t index) const {
  sensor_msgs::PointCloud2::ConstPtr msg;
  {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    try {
      msg = impl_->clouds.at(index).instantiate<sensor_msgs::PointCloud2>();
    } catch (const rosbag::BagException& e) {
      throw input_error(name_, 0, "scan " + std::to_string(index) + ": " + e.what());
    }
  }
  PointCloud2Layout layout;
  layout.height = msg->height;
  layout.width = msg->width;
  layout.point_step = msg->point_step;
  layout.row_step = msg->row_step;
  layout.is_bigendian = msg->is_bigendian;
  for (const sensor_msgs::PointField& f : msg->fields) layout.fields.push_back({f.name, f.offset, f.datatype, f.count});
  return decode_point_cloud2(layout, msg->data.data(), msg->data.size(),
                             name_ + ": " + impl_->clouds[index].getTopic() + ", scan " + std::to_string(index));
}

std::string bag_info(const std::string& path) {
  if (!fs::is_regular_file(path)) throw input_error(path, 0, "no such bag");
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
      std::snprintf(line, sizeof(line), "  %-32s %-28s %8zu msgs  %7.2f Hz\n", name.c_str(), t.type.c_str(), t.count,
                    rate);
      out += line;
    }
    return out;
  } catch (const rosbag::BagException& e) {
    throw input_error(path, 0, std::string("cannot read the bag: ") + e.what());
  }
}

void write_bag(const ScanSequence& sequence, const std::string& path, BagCompression compression,
               const Pose3& sensor_to_base) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  try {
    rosbag::Bag bag(tmp, rosbag::bagmode::Write);
    bag.setCompression(compression == BagCompression::bz2   ? rosbag::compression::BZ2
                       : compression == BagCompression::lz4 ? rosbag::compression::LZ4
                                                            : rosbag::compression::Uncompressed);
    const SequenceInfo& info = sequence.info();
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

}  // namespace tsgraphs::io
