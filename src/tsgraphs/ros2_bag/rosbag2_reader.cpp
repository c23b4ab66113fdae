// rosbag2 recordings read as a sequence: a topic's clouds placed by the odometry.
#include "tsgraphs/ros2_bag/rosbag2.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <tuple>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/point_cloud2.hpp"
#include "tsgraphs/ros2_bag/ros2_messages.hpp"
#include "tsgraphs/ros2_bag/rosbag2_internal.hpp"

namespace tsgraphs::ros2_bag {

using namespace rosbag2_internal;

struct Rosbag2Sequence::Impl {
  std::vector<std::unique_ptr<Storage>> storages;
  std::vector<Located> clouds;  ///< one per kept scan
  std::string topic;
};

namespace {

/// `topic` of `topics`, of one of the `wanted` types, serialized as CDR, with the definition
/// tsgraphs reads (if the storage keeps one); else an InputError naming the recording.
const Topic& require_topic(const std::map<std::string, Topic>& topics, const std::string& path,
                           const std::string& topic, const std::vector<const char*>& wanted) {
  const auto it = topics.find(topic);
  if (it == topics.end()) {
    std::string list;
    for (const auto& [t, info] : topics) list += (list.empty() ? "" : ", ") + t;
    throw input_error(path, 0, "no topic " + topic + " (topics: " + list + ")");
  }
  const Topic& t = it->second;
  if (std::find(wanted.begin(), wanted.end(), t.type) == wanted.end()) {
    std::string names;
    for (const char* w : wanted) names += std::string(names.empty() ? "" : " or ") + w;
    throw input_error(path, 0, topic + " is " + t.type + ", expected " + names);
  }
  if (t.format != "cdr")
    throw input_error(path, 0, topic + " is serialized as '" + t.format + "', expected cdr");
  if (const std::string why = ros2::definition_mismatch(t.type, t.definition); !why.empty()) {
    throw input_error(path, 0, topic + " (" + t.type + "): " + why);
  }
  return t;
}

/// A message for errors: the recording, the topic and the message's index in it.
std::string message_where(const std::string& path, const std::string& topic, std::size_t i) {
  return path + ": " + topic + ", message " + std::to_string(i);
}

/// A message to read in the first pass: an odometry message or a cloud, by its index in its topic.
struct PendingRead {
  const Located* m;
  bool cloud;
  std::size_t i;  ///< index in its topic, by time
};

/// The odometry messages and clouds in file order, so that an MCAP chunk holding both is
/// decompressed once.
std::vector<PendingRead> in_file_order(const std::vector<Located>& odom_messages,
                                       const std::vector<Located>& clouds) {
  std::vector<PendingRead> reads;
  for (std::size_t i = 0; i < odom_messages.size(); ++i) reads.push_back({&odom_messages[i], false, i});
  for (std::size_t i = 0; i < clouds.size(); ++i) reads.push_back({&clouds[i], true, i});
  const auto position = [](const Located& m) {
    const bool chunked = m.ref.chunk != mcap::MessageRef::kNoChunk;
    return std::make_tuple(m.file, chunked ? m.ref.chunk : m.ref.offset, chunked ? m.ref.offset : 0, m.row);
  };
  std::sort(reads.begin(), reads.end(),
            [&](const PendingRead& a, const PendingRead& b) { return position(*a.m) < position(*b.m); });
  return reads;
}

/// What the first pass reads: the odometry, and the clouds' stamps and frame.
struct FirstPass {
  std::vector<io::StampedBase> odom;
  std::vector<double> stamps;
  std::string cloud_frame;  // the first cloud's
};

/// The odometry (Odometry or PoseStamped messages) and the clouds' stamps, read in one pass.
FirstPass read_odometry_and_stamps(const std::vector<std::unique_ptr<Storage>>& storages,
                                   const io::BagOptions& options, bool is_odometry,
                                   const std::vector<Located>& odom_messages,
                                   const std::vector<Located>& clouds) {
  FirstPass out;
  out.odom.resize(odom_messages.size());
  out.stamps.resize(clouds.size());
  for (const PendingRead& r : in_file_order(odom_messages, clouds)) {
    const std::string cdr = storages[r.m->file]->read(*r.m);
    if (r.cloud) {
      const io::PointCloud2Message c =
          ros2::parse_point_cloud2(cdr, message_where(options.bag, options.points_topic, r.i));
      out.stamps[r.i] = c.stamp;
      if (r.i == 0) out.cloud_frame = c.frame_id;
    } else {
      const std::string where = message_where(options.bag, options.odom_topic, r.i);
      const ros2::StampedPoseMessage p =
          is_odometry ? ros2::parse_odometry(cdr, where) : ros2::parse_pose_stamped(cdr, where);
      out.odom[r.i] = {p.stamp, p.pose};
    }
  }
  return out;
}

/// The sensor-to-base transform of /tf_static: the last one whose child is `cloud_frame`, if any.
std::optional<Pose3> tf_static_mount(const std::vector<std::unique_ptr<Storage>>& storages,
                                     const std::string& path, const std::string& cloud_frame) {
  std::optional<Pose3> mount;
  std::size_t i = 0;
  for (const Located& m : messages_of(storages, kTfStaticTopic)) {
    for (const ros2::TransformMessage& t :
         ros2::parse_tf_message(storages[m.file]->read(m), message_where(path, kTfStaticTopic, i++))) {
      if (t.child != cloud_frame) continue;
      mount = t.transform;
    }
  }
  return mount;
}

}  // namespace

Rosbag2Sequence::Rosbag2Sequence(const io::BagOptions& options)
    : io::RecordedSequence(options.bag), impl_(std::make_unique<Impl>()) {
  const std::string& path = options.bag;
  if (options.points_topic.empty())
    throw input_error(path, 0, "no points topic given (--points-topic; see bag-info)");
  impl_->storages = open_recording(path);
  for (const auto& s : impl_->storages) {
    for (const std::string& w : s->warnings()) warnings_.push_back(w);
  }
  const std::map<std::string, Topic> topics = topics_of(impl_->storages, path);
  impl_->topic = options.points_topic;
  require_topic(topics, path, options.points_topic, {ros2::kPointCloud2});
  bool is_odometry = false;
  std::vector<Located> odom_messages;
  if (!options.odom_topic.empty()) {
    is_odometry =
        require_topic(topics, path, options.odom_topic, {ros2::kOdometry, ros2::kPoseStamped}).type ==
        ros2::kOdometry;
    odom_messages = messages_of(impl_->storages, options.odom_topic);
  }
  const std::vector<Located> clouds = messages_of(impl_->storages, options.points_topic);
  if (clouds.empty()) throw input_error(path, 0, "no messages on " + options.points_topic);
  FirstPass pass = read_odometry_and_stamps(impl_->storages, options, is_odometry, odom_messages, clouds);
  io::add_tum_odometry(options, pass.odom);
  const bool has_odometry = !options.odom_topic.empty() || !options.odom_tum.empty();

  if (options.sensor_to_base) {
    sensor_to_base_ = *options.sensor_to_base;
    sensor_to_base_known_ = true;
  } else if (topics.count(kTfStaticTopic)) {
    require_topic(topics, path, kTfStaticTopic, {ros2::kTfMessage});
    if (const auto mount = tf_static_mount(impl_->storages, path, pass.cloud_frame)) {
      sensor_to_base_ = *mount;
      sensor_to_base_known_ = true;
    }
  }

  for (const std::size_t i : place(pass.stamps, std::move(pass.odom), has_odometry, options.points_topic))
    impl_->clouds.push_back(clouds[i]);
}

Rosbag2Sequence::~Rosbag2Sequence() = default;

PointCloud Rosbag2Sequence::scan(std::size_t index) const {
  const Located& m = impl_->clouds.at(index);
  const std::string where = name_ + ": " + impl_->topic + ", scan " + std::to_string(index);
  const std::string cdr = impl_->storages[m.file]->read(m);
  const io::PointCloud2Message msg = ros2::parse_point_cloud2(cdr, where);
  return io::decode_point_cloud2(
      msg.layout, reinterpret_cast<const std::uint8_t*>(cdr.data()) + msg.data_offset, msg.data_size, where);
}

}  // namespace tsgraphs::ros2_bag
