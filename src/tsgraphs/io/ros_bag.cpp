// ROS1 bags through rosbag_storage. The only file of tsgraphs that sees ROS types.
#include "tsgraphs/io/ros_bag.hpp"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <console_bridge/console.h>
#include <ros/exception.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <set>
#include <stdexcept>
#include <system_error>
#include <unistd.h>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/io/recorded_sequence.hpp"
#include "tsgraphs/io/point_cloud2.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs::io {

namespace {

namespace fs = std::filesystem;

constexpr const char* kCloudType = "sensor_msgs/PointCloud2";
constexpr const char* kOdometryType = "nav_msgs/Odometry";
constexpr const char* kPoseType = "geometry_msgs/PoseStamped";
constexpr const char* kTfStaticTopic = "/tf_static";

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

/// rosbag's record time: the stamp, or its earliest allowed time for a stamp of 0.
ros::Time record_time(double t) { return std::max(ros::Time(t), ros::TIME_MIN); }

// ROS bag format 2.0 (wiki.ros.org/Bags/Format/2.0), as much as the structure check needs.
// rosbag trusts every length it reads (a flipped byte in a chunk header is a SIGSEGV, a header
// length near 2^32 its assert), so each is checked here, against the bytes that exist, first.
constexpr char kBagMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kBagMagicBytes = sizeof(kBagMagic) - 1;
constexpr std::uint8_t kOpMessageData = 0x02, kOpBagHeader = 0x03, kOpIndexData = 0x04, kOpChunk = 0x05,
                       kOpChunkInfo = 0x06, kOpConnection = 0x07;
constexpr std::uint64_t kLengthBytes = 4;       // every length word
constexpr std::uint64_t kIndexEntryBytes = 12;  // index data entry: time (8), offset (4)
// A TransformStamped serialized at its smallest: header (seq 4, stamp 8, empty frame_id 4), an
// empty child_frame_id (4), translation and rotation (7 doubles, 56).
constexpr std::uint64_t kMinTransformBytes = 76;
constexpr std::uint64_t kChunkInfoEntryBytes = 8;  // chunk info entry: conn (4), count (4)
constexpr std::uint32_t kIndexVersion = 1;         // `ver` of index data and chunk info
// ROS's own header parser refuses a field over 1e6 bytes; real record headers are tens of bytes.
constexpr std::uint64_t kMaxRecordHeaderBytes = 1u << 20;
// rosbag allocates a chunk's declared uncompressed size at once; writers close a chunk near
// 768 KB, so a chunk over a gigabyte is corruption, not data.
constexpr std::uint64_t kMaxChunkBytes = 1ull << 30;
constexpr const char* kNoEncryptor = "rosbag/NoEncryptor";

std::uint64_t little_endian(const std::string& bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = bytes.size(); i-- > 0;) v = v << 8 | static_cast<std::uint8_t>(bytes[i]);
  return v;
}

std::string op_name(std::uint8_t op) {
  switch (op) {
    case kOpMessageData:
      return "message data";
    case kOpBagHeader:
      return "bag header";
    case kOpIndexData:
      return "index data";
    case kOpChunk:
      return "chunk";
    case kOpChunkInfo:
      return "chunk info";
    case kOpConnection:
      return "connection";
  }
  return "unknown";
}

struct BagRecord {
  std::uint64_t pos = 0;  ///< of its header length word
  std::uint8_t op = 0;
  std::map<std::string, std::string> fields;
  std::uint64_t data_pos = 0, data_len = 0;
  std::uint64_t end() const { return data_pos + data_len; }
};

/// What the reads after the check may rely on.
struct BagLimits {
  std::uint64_t largest_chunk = 0;  ///< no message can be longer
};

/// Walks every record of a bag (and every record inside its uncompressed chunks) and throws an
/// InputError "bag: byte N: what" at the first length, count or offset that does not fit.
class BagChecker {
 public:
  explicit BagChecker(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    std::error_code ec;
    size_ = fs::file_size(path, ec);
    if (ec || !in_)
      throw input_error(path, 0, "cannot read the bag" + (ec ? ": " + ec.message() : std::string()));
  }

  BagLimits check() {
    if (size_ < kBagMagicBytes || read(0, kBagMagicBytes) != kBagMagic)
      throw input_error(path_, 0, "not a ROS bag 2.0 (it does not start with '#ROSBAG V2.0')");
    const std::string eof = "the end of the file (" + std::to_string(size_) + " bytes)";
    const BagRecord head = record(kBagMagicBytes, size_, eof);
    if (head.op != kOpBagHeader)
      fail(head.pos, "the first record is " + op_name(head.op) + ", not the bag header");
    const std::uint64_t index_pos = number(head, "index_pos", 8);
    const std::uint64_t conn_count = number(head, "conn_count", 4),
                        chunk_count = number(head, "chunk_count", 4);
    const auto encryptor = head.fields.find("encryptor");
    const bool encrypted =
        encryptor != head.fields.end() && !encryptor->second.empty() && encryptor->second != kNoEncryptor;
    if (index_pos > size_) fail(head.pos, "index_pos " + std::to_string(index_pos) + " is past " + eof);

    BagLimits limits;
    std::vector<BagRecord> records;  // the top-level ones, in file order (headers only kept)
    struct Chunk {
      std::uint64_t size = 0;
      bool opaque = false;                 ///< compressed or encrypted: its records cannot be seen
      std::set<std::uint64_t> message_at;  ///< offsets of its message data records
    };
    std::map<std::uint64_t, Chunk> chunks;
    Chunk* last_chunk = nullptr;
    for (std::uint64_t pos = head.end(); pos < size_;) {
      BagRecord r = record(pos, size_, eof);
      switch (r.op) {
        case kOpChunk: {
          Chunk c;
          const std::string compression = text(r, "compression");
          if (compression != "none" && compression != "bz2" && compression != "lz4")
            fail(r.pos, "chunk compression '" + printable(compression) + "' is none of none, bz2, lz4");
          c.size = number(r, "size", 4);
          if (c.size > kMaxChunkBytes)
            fail(r.pos, "chunk size " + std::to_string(c.size) + " is over the " +
                            std::to_string(kMaxChunkBytes) + " bytes any chunk has");
          c.opaque = compression != "none" || encrypted;
          if (!c.opaque) {
            if (c.size != r.data_len)
              fail(r.pos, "uncompressed chunk of size " + std::to_string(c.size) + " holds " +
                              std::to_string(r.data_len) + " bytes");
            const std::string chunk_end = "the end of its chunk (byte " + std::to_string(r.end()) + ")";
            for (std::uint64_t p = r.data_pos; p < r.end();) {
              const BagRecord inner = record(p, r.end(), chunk_end);
              if (inner.op == kOpMessageData) {
                number(inner, "conn", 4);
                number(inner, "time", 8);
                c.message_at.insert(p - r.data_pos);
              } else if (inner.op == kOpConnection) {
                connection(inner);
              } else {
                fail(p, op_name(inner.op) + " record inside a chunk");
              }
              p = inner.end();
            }
          }
          limits.largest_chunk = std::max(limits.largest_chunk, c.size);
          if (last_chunk) last_chunk->message_at.clear();  // only the latest chunk's index records follow it
          last_chunk = &(chunks[r.pos] = std::move(c));
          break;
        }
        case kOpIndexData: {
          if (number(r, "ver", 4) != kIndexVersion) fail(r.pos, "index data version is not 1");
          number(r, "conn", 4);
          const std::uint64_t count = number(r, "count", 4);
          if (count * kIndexEntryBytes != r.data_len)
            fail(r.pos, "index data of " + std::to_string(count) + " entries holds " +
                            std::to_string(r.data_len) + " bytes");
          if (!last_chunk) fail(r.pos, "index data before any chunk");
          const std::string entries = read(r.data_pos, r.data_len);
          for (std::uint64_t i = 0; i < count; ++i) {
            const std::uint64_t at = i * kIndexEntryBytes + 8;  // past the entry's time
            const std::uint64_t offset = little_endian(entries.substr(at, kLengthBytes));
            if (offset >= last_chunk->size)
              fail(r.data_pos + at, "index offset " + std::to_string(offset) + " is past its chunk's " +
                                        std::to_string(last_chunk->size) + " bytes");
            if (!last_chunk->opaque && !last_chunk->message_at.count(offset))
              fail(r.data_pos + at,
                   "index offset " + std::to_string(offset) + " is not a message in its chunk");
          }
          break;
        }
        case kOpConnection:
          connection(r);
          break;
        case kOpChunkInfo: {
          if (number(r, "ver", 4) != kIndexVersion) fail(r.pos, "chunk info version is not 1");
          const std::uint64_t chunk_pos = number(r, "chunk_pos", 8);
          number(r, "start_time", 8);
          number(r, "end_time", 8);
          const std::uint64_t count = number(r, "count", 4);
          if (count * kChunkInfoEntryBytes != r.data_len)
            fail(r.pos, "chunk info of " + std::to_string(count) + " entries holds " +
                            std::to_string(r.data_len) + " bytes");
          if (!chunks.count(chunk_pos))
            fail(r.pos, "chunk info points at byte " + std::to_string(chunk_pos) + ", where no chunk starts");
          break;
        }
        default:
          fail(r.pos, op_name(r.op) + " record (op " + std::to_string(r.op) +
                          ") where a chunk, index or connection belongs");
      }
      pos = r.end();
      r.fields.clear();  // only op and place are looked at again
      records.push_back(std::move(r));
    }

    // What rosbag reads at open: conn_count connections and chunk_count chunk infos from
    // index_pos on, and after each chunk the index data records its chunk info counts.
    if (index_pos == 0) return limits;  // an unindexed bag: rosbag says so itself
    const auto at = [&](std::uint64_t pos) {
      return std::lower_bound(records.begin(), records.end(), pos,
                              [](const BagRecord& r, std::uint64_t p) { return r.pos < p; });
    };
    auto it = at(index_pos);
    if (it == records.end() || it->pos != index_pos)
      fail(head.pos, "index_pos " + std::to_string(index_pos) + " is not the start of a record");
    for (std::uint64_t i = 0; i < conn_count + chunk_count; ++i, ++it) {
      const std::uint8_t wanted = i < conn_count ? kOpConnection : kOpChunkInfo;
      if (it == records.end())
        fail(size_, "the index ends after " + std::to_string(i) + " of " + std::to_string(conn_count) +
                        " connections and " + std::to_string(chunk_count) + " chunk infos");
      if (it->op != wanted)
        fail(it->pos, op_name(it->op) + " record where the index has a " + op_name(wanted));
      if (wanted == kOpChunkInfo) chunk_indexes(at, records, it->pos);
    }
    return limits;
  }

 private:
  [[noreturn]] void fail(std::uint64_t pos, const std::string& what) const {
    throw input_error(path_, 0, "byte " + std::to_string(pos) + ": " + what);
  }

  /// `n` bytes at `pos` (the caller has checked that they exist).
  std::string read(std::uint64_t pos, std::uint64_t n) {
    std::string bytes(n, '\0');
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(pos));
    if (!in_.read(bytes.data(), static_cast<std::streamsize>(n)))
      fail(pos, "cannot read " + std::to_string(n) + " bytes");
    return bytes;
  }

  /// `name=value` fields, each after its 4-byte length, filling `bytes` (which start at byte `pos`).
  std::map<std::string, std::string> fields(const std::string& bytes, std::uint64_t pos,
                                            const std::string& what) const {
    std::map<std::string, std::string> out;
    for (std::uint64_t i = 0; i < bytes.size();) {
      if (bytes.size() - i < kLengthBytes) fail(pos + i, what + " ends inside a field's length");
      const std::uint64_t length = little_endian(bytes.substr(i, kLengthBytes));
      if (length > bytes.size() - i - kLengthBytes)
        fail(pos + i, what + " field length " + std::to_string(length) + " runs past its " +
                          std::to_string(bytes.size()) + " bytes");
      const std::string field = bytes.substr(i + kLengthBytes, length);
      const std::size_t eq = field.find('=');
      if (eq == std::string::npos) fail(pos + i, what + " field without '='");
      out[field.substr(0, eq)] = field.substr(eq + 1);
      i += kLengthBytes + length;
    }
    return out;
  }

  /// The record at `pos`, every length of it checked against `end` (described by `where`).
  BagRecord record(std::uint64_t pos, std::uint64_t end, const std::string& where) {
    BagRecord r;
    r.pos = pos;
    if (end - pos < kLengthBytes) fail(pos, "a record cut short by " + where);
    const std::uint64_t header_len = little_endian(read(pos, kLengthBytes));
    if (header_len > end - pos - kLengthBytes)
      fail(pos, "record header length " + std::to_string(header_len) + " runs past " + where);
    if (header_len > kMaxRecordHeaderBytes)
      fail(pos, "record header length " + std::to_string(header_len) + " is over the " +
                    std::to_string(kMaxRecordHeaderBytes) + " bytes any record header has");
    if (end - pos - kLengthBytes - header_len < kLengthBytes)
      fail(pos, "record has no data length before " + where);
    const std::string bytes = read(pos + kLengthBytes, header_len + kLengthBytes);
    r.fields = fields(bytes.substr(0, header_len), pos + kLengthBytes, "record header");
    const auto op = r.fields.find("op");
    if (op == r.fields.end() || op->second.size() != 1) fail(pos, "record header has no 1-byte op field");
    r.op = static_cast<std::uint8_t>(op->second[0]);
    r.data_pos = pos + 2 * kLengthBytes + header_len;
    r.data_len = little_endian(bytes.substr(header_len));
    if (r.data_len > end - r.data_pos)
      fail(pos,
           op_name(r.op) + " record's data length " + std::to_string(r.data_len) + " runs past " + where);
    return r;
  }

  /// A little-endian number field of exactly `bytes` bytes.
  std::uint64_t number(const BagRecord& r, const std::string& name, std::size_t bytes) const {
    const auto f = r.fields.find(name);
    if (f == r.fields.end() || f->second.size() != bytes)
      fail(r.pos, op_name(r.op) + " header field '" + name + "' is missing or not " + std::to_string(bytes) +
                      " bytes");
    return little_endian(f->second);
  }

  std::string text(const BagRecord& r, const std::string& name) const {
    const auto f = r.fields.find(name);
    if (f == r.fields.end()) fail(r.pos, op_name(r.op) + " header has no field '" + name + "'");
    return f->second;
  }

  /// A connection record: its data is a field list too (topic, type, md5sum, definition).
  void connection(const BagRecord& r) {
    number(r, "conn", 4);
    text(r, "topic");
    fields(read(r.data_pos, r.data_len), r.data_pos, "connection data");
  }

  /// The index data records rosbag reads after the chunk a chunk info (at `info_pos`) names.
  template <class At>
  void chunk_indexes(const At& at, const std::vector<BagRecord>& records, std::uint64_t info_pos) {
    const BagRecord info = record(info_pos, size_, "the end of the file");
    const std::uint64_t chunk_pos = number(info, "chunk_pos", 8), count = number(info, "count", 4);
    auto it = at(chunk_pos);
    for (std::uint64_t i = 0; i < count; ++i) {
      if (++it == records.end() || it->op != kOpIndexData)
        fail(info_pos, "chunk info counts " + std::to_string(count) + " connections, the chunk at byte " +
                           std::to_string(chunk_pos) + " is followed by " + std::to_string(i) +
                           " index records");
    }
  }

  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

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

/// Whether `path` is a regular file; a symlink loop or an unreadable path is an InputError.
bool is_bag_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && status.type() != fs::file_type::not_found)
    throw input_error(path, 0, "cannot read the bag: " + ec.message());
  return fs::is_regular_file(status);
}

/// rosbag's own log lines (console_bridge) gathered instead of printed on stderr, so they
/// reach the user as part of our messages: an error's text, or the sequence's warnings. A
/// reading operation collects the lines of its thread while a RosbagLines is alive.
class RosbagLines {
 public:
  RosbagLines() {
    static std::once_flag once;
    std::call_once(once, [] {
      static Forwarder forwarder;
      console_bridge::useOutputHandler(&forwarder);
      console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
    });
    previous_ = sink_;
    sink_ = &lines_;
  }
  ~RosbagLines() { sink_ = previous_; }
  RosbagLines(const RosbagLines&) = delete;
  RosbagLines& operator=(const RosbagLines&) = delete;
  const std::vector<std::string>& lines() const { return lines_; }
  /// " (rosbag: last line)" for an error's text, "" when rosbag said nothing.
  std::string last() const { return lines_.empty() ? "" : " (rosbag: " + lines_.back() + ")"; }

 private:
  /// The handler console_bridge calls, from the logging thread.
  struct Forwarder : console_bridge::OutputHandler {
    void log(const std::string& text, console_bridge::LogLevel, const char*, int) override {
      if (sink_ != nullptr) {
        sink_->push_back(text);
      } else {  // outside any reading operation (not expected): still one line of ours
        std::fprintf(stderr, "tsgraphs: rosbag: %s\n", text.c_str());
      }
    }
  };
  static thread_local std::vector<std::string>* sink_;
  std::vector<std::string>* previous_ = nullptr;
  std::vector<std::string> lines_;
};
thread_local std::vector<std::string>* RosbagLines::sink_ = nullptr;

}  // namespace

struct BagSequence::Impl {
  rosbag::Bag bag;
  BagLimits limits;
  std::vector<rosbag::MessageInstance> clouds;  ///< one per kept scan
  mutable std::mutex mutex;                     ///< rosbag reads seek one file
};

BagSequence::BagSequence(const BagOptions& options)
    : RecordedSequence(options.bag), impl_(std::make_unique<Impl>()) {
  const std::string& path = options.bag;
  if (!is_bag_file(path)) throw input_error(path, 0, "no such bag");
  if (options.points_topic.empty())
    throw input_error(path, 0, "no points topic given (--points-topic; see bag-info)");
  impl_->limits = BagChecker(path).check();
  const RosbagLines rosbag_lines;
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
        if (const auto o = m.instantiate<nav_msgs::Odometry>())
          odom.push_back({o->header.stamp.toSec(), pose_of(o->pose.pose)});
        else if (const auto p = m.instantiate<geometry_msgs::PoseStamped>())
          odom.push_back({p->header.stamp.toSec(), pose_of(p->pose)});
      }
    } else if (!options.odom_tum.empty()) {
      for (const StampedPose& p : read_tum(options.odom_tum)) odom.push_back({p.t, p.pose});
    }
    const bool has_odometry = !options.odom_topic.empty() || !options.odom_tum.empty();
    if (has_odometry && odom.empty())
      throw input_error(
          path, 0,
          "no odometry messages on " + (options.odom_topic.empty() ? options.odom_tum : options.odom_topic));

    // The clouds, in stamp order; their frame finds the sensor-to-base transform.
    struct Cloud {
      double t;
      rosbag::MessageInstance message;
    };
    std::vector<Cloud> clouds;
    std::string cloud_frame;
    rosbag::View view(impl_->bag, rosbag::TopicQuery(options.points_topic));
    for (const rosbag::MessageInstance& m : view) {
      if (!m.isType<sensor_msgs::PointCloud2>()) continue;
      // Taken apart by hand: rosbag's deserializer allocates whatever a corrupt length says.
      const std::string where =
          path + ": " + options.points_topic + ", message " + std::to_string(clouds.size());
      const std::vector<std::uint8_t> bytes = message_bytes(m, impl_->limits, where);
      const PointCloud2Message c = parse_point_cloud2_message(bytes.data(), bytes.size(), where);
      if (cloud_frame.empty()) cloud_frame = c.frame_id;
      clouds.push_back({c.stamp, m});
    }
    if (clouds.empty()) throw input_error(path, 0, "no messages on " + options.points_topic);

    if (options.sensor_to_base) {
      sensor_to_base_ = *options.sensor_to_base;
      sensor_to_base_known_ = true;
    } else if (types.count(kTfStaticTopic)) {
      rosbag::View tf(impl_->bag, rosbag::TopicQuery(kTfStaticTopic));
      std::size_t index = 0;
      for (const rosbag::MessageInstance& m : tf) {
        if (!m.isType<tf2_msgs::TFMessage>()) continue;
        // rosbag's deserializer sizes the transforms array from its length word before reading
        // a byte of it (found by fuzzing: 584 GB asked for): the word is checked here first.
        const std::string where = path + ": " + kTfStaticTopic + ", message " + std::to_string(index++);
        const std::vector<std::uint8_t> bytes = message_bytes(m, impl_->limits, where);
        const std::uint64_t count =
            bytes.size() < kLengthBytes
                ? 0
                : little_endian(std::string(bytes.begin(), bytes.begin() + kLengthBytes));
        if (bytes.size() < kLengthBytes || count > (bytes.size() - kLengthBytes) / kMinTransformBytes) {
          throw input_error(where, 0,
                            "claims " + std::to_string(count) + " transforms, more than its " +
                                std::to_string(bytes.size()) + " bytes hold");
        }
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
    std::vector<double> stamps;
    for (const Cloud& c : clouds) stamps.push_back(c.t);
    ScanPlacement placed = place_scans(stamps, std::move(odom), has_odometry, sensor_to_base_);
    for (const std::size_t i : placed.kept) impl_->clouds.push_back(clouds[i].message);
    info_.times = std::move(placed.times);
    info_.odometry = std::move(placed.odometry);
    dropped_ = placed.dropped;
    if (info_.times.empty())
      throw input_error(path, 0,
                        "no scan on " + options.points_topic + " lies within the odometry's time span");
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
  const PointCloud2Message msg = parse_point_cloud2_message(bytes.data(), bytes.size(), where);
  return decode_point_cloud2(msg.layout, bytes.data() + msg.data_offset, msg.data_size, where);
}

std::string bag_info(const std::string& path) {
  if (!is_bag_file(path)) throw input_error(path, 0, "no such bag");
  BagChecker(path).check();
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
