// A sequence written as rosbag2 writes a recording: SQLite or MCAP, a bag folder or one file.
#include "tsgraphs/ros2_bag/rosbag2.hpp"

#include <sqlite3.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/mcap/compression.hpp"
#include "tsgraphs/ros2_bag/ros2_messages.hpp"
#include "tsgraphs/ros2_bag/rosbag2_internal.hpp"

namespace tsgraphs::ros2_bag {

using rosbag2_internal::kMetadataFile;
using rosbag2_internal::kTfStaticTopic;

namespace {

namespace fs = std::filesystem;

/// Offered QoS as rosbag2 records it (YAML): reliable; /tf_static transient local, as tf2 publishes it.
std::string qos_profile(bool transient_local) {
  return std::string("- history: 3\n  depth: 0\n  reliability: 1\n  durability: ") +
         (transient_local ? "1" : "2") +
         "\n  deadline:\n    sec: 2147483647\n    nsec: 4294967295\n  lifespan:\n    sec: 2147483647\n"
         "    nsec: 4294967295\n  liveliness: 1\n  liveliness_lease_duration:\n    sec: 2147483647\n"
         "    nsec: 4294967295\n  avoid_ros_namespace_conventions: false";
}

struct TopicToWrite {
  std::string name, type;
  bool transient_local = false;
};

/// One message to write: its topic's index in the list and its CDR.
struct Out {
  std::size_t topic;
  std::uint64_t time;
  std::string cdr;
};

/// What metadata.yaml says of the messages: per topic its count, and the time span.
struct Tally {
  std::vector<std::uint64_t> counts;
  std::uint64_t first = 0, last = 0, total = 0;
  void add(const Out& m) {
    if (counts.size() <= m.topic) counts.resize(m.topic + 1, 0);
    ++counts[m.topic];
    first = total ? std::min(first, m.time) : m.time;
    last = total ? std::max(last, m.time) : m.time;
    ++total;
  }
};

/// rosbag2's BagMetadata (version 5, as Humble writes it) for one file, listed as `file`.
std::string bag_metadata(const std::string& storage_id, const std::string& file,
                         const std::vector<TopicToWrite>& topics, const Tally& tally,
                         Rosbag2Compression compression) {
  YAML::Emitter y;
  const auto duration = [&] {
    y << YAML::BeginMap << YAML::Key << "nanoseconds" << YAML::Value << tally.last - tally.first
      << YAML::EndMap;
  };
  const auto starting = [&] {
    y << YAML::BeginMap << YAML::Key << "nanoseconds_since_epoch" << YAML::Value << tally.first
      << YAML::EndMap;
  };
  y << YAML::BeginMap << YAML::Key << "rosbag2_bagfile_information" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "version" << YAML::Value << 5;
  y << YAML::Key << "storage_identifier" << YAML::Value << storage_id;
  y << YAML::Key << "duration" << YAML::Value, duration();
  y << YAML::Key << "starting_time" << YAML::Value, starting();
  y << YAML::Key << "message_count" << YAML::Value << tally.total;
  y << YAML::Key << "topics_with_message_count" << YAML::Value << YAML::BeginSeq;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    y << YAML::BeginMap << YAML::Key << "topic_metadata" << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "name" << YAML::Value << topics[i].name;
    y << YAML::Key << "type" << YAML::Value << topics[i].type;
    y << YAML::Key << "serialization_format" << YAML::Value << "cdr";
    y << YAML::Key << "offered_qos_profiles" << YAML::Value << YAML::DoubleQuoted
      << qos_profile(topics[i].transient_local);
    y << YAML::EndMap;
    y << YAML::Key << "message_count" << YAML::Value << (i < tally.counts.size() ? tally.counts[i] : 0);
    y << YAML::EndMap;
  }
  y << YAML::EndSeq;
  const bool compressed = compression != Rosbag2Compression::none;
  y << YAML::Key << "compression_format" << YAML::Value << YAML::DoubleQuoted << (compressed ? "zstd" : "");
  y << YAML::Key << "compression_mode" << YAML::Value << YAML::DoubleQuoted
    << (!compressed                               ? ""
        : compression == Rosbag2Compression::file ? "FILE"
                                                  : "MESSAGE");
  y << YAML::Key << "relative_file_paths" << YAML::Value << YAML::BeginSeq << file << YAML::EndSeq;
  y << YAML::Key << "files" << YAML::Value << YAML::BeginSeq << YAML::BeginMap;
  y << YAML::Key << "path" << YAML::Value << file;
  y << YAML::Key << "starting_time" << YAML::Value, starting();
  y << YAML::Key << "duration" << YAML::Value, duration();
  y << YAML::Key << "message_count" << YAML::Value << tally.total;
  y << YAML::EndMap << YAML::EndSeq;
  y << YAML::EndMap << YAML::EndMap;
  return std::string(y.c_str()) + "\n";
}

/// How a bag is laid out: the name metadata.yaml lists its file under, rosbag2's own compression.
struct Layout {
  std::string file;
  Rosbag2Compression compression = Rosbag2Compression::none;
};

/// Every message of `sequence` in write_bag's order: /tf_static, then per scan /points, /odom
/// and /groundtruth; each message's data zstd-compressed in MESSAGE mode.
template <class Sink>
void for_each_message(const io::ScanSequence& sequence, const Pose3& sensor_to_base,
                      Rosbag2Compression compression, Sink&& write) {
  const auto sink = [&](Out m) {
    if (compression == Rosbag2Compression::message) m.cdr = mcap::compress_zstd(m.cdr);
    write(m);
  };
  const io::SequenceInfo& info = sequence.info();
  const double first = info.times.empty() ? 0.0 : info.times.front();
  const auto stamp_ns = ros2::stamp_nanoseconds;
  sink(Out{2, stamp_ns(first), ros2::encode_tf_message({{first, "base_link", "lidar", sensor_to_base}})});
  const Pose3 base_to_sensor = sensor_to_base.inverse();
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    sink(
        Out{0, stamp_ns(info.times[i]), ros2::encode_point_cloud2(info.times[i], "lidar", sequence.scan(i))});
    sink(Out{1, stamp_ns(info.times[i]),
             ros2::encode_odometry({info.times[i], "odom", "base_link", info.odometry[i] * base_to_sensor})});
    if (i < info.groundtruth.size())
      sink(Out{3, stamp_ns(info.times[i]),
               ros2::encode_pose_stamped({info.times[i], "world", "", info.groundtruth[i]})});
  }
}

/// Returns the bag's metadata (for metadata.yaml); `file` is the name it lists.
std::string write_sqlite(const io::ScanSequence& sequence, const std::string& tmp, const Layout& layout,
                         const std::vector<TopicToWrite>& topics, const Pose3& sensor_to_base) {
  std::string metadata;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(tmp.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    throw input_error(tmp, 0, "cannot create the SQLite file");
  }
  const auto exec = [&](const std::string& sql) {
    char* error = nullptr;
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
      const std::string why = error ? error : "unknown";
      sqlite3_free(error);
      throw std::runtime_error(tmp + ": SQLite: " + why);
    }
  };
  try {
    exec(
        "PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF; BEGIN;"
        "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
        "INSERT INTO schema VALUES (3, 'humble');"
        "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, metadata TEXT NOT "
        "NULL);"
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
        "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
        "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT "
        "NULL, "
        "data BLOB NOT NULL);"
        "CREATE INDEX timestamp_idx ON messages (timestamp ASC);");
    for (std::size_t i = 0; i < topics.size(); ++i) {
      sqlite3_stmt* s = nullptr;
      sqlite3_prepare_v2(db, "INSERT INTO topics VALUES (?1, ?2, ?3, 'cdr', ?4)", -1, &s, nullptr);
      sqlite3_bind_int64(s, 1, static_cast<sqlite3_int64>(i + 1));
      sqlite3_bind_text(s, 2, topics[i].name.c_str(), -1, SQLITE_TRANSIENT);
      sqlite3_bind_text(s, 3, topics[i].type.c_str(), -1, SQLITE_TRANSIENT);
      sqlite3_bind_text(s, 4, qos_profile(topics[i].transient_local).c_str(), -1, SQLITE_TRANSIENT);
      const int rc = sqlite3_step(s);
      sqlite3_finalize(s);
      if (rc != SQLITE_DONE) throw std::runtime_error(tmp + ": SQLite: " + sqlite3_errmsg(db));
    }
    sqlite3_stmt* insert = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?1, ?2, ?3)", -1,
                       &insert, nullptr);
    Tally tally;
    try {
      for_each_message(sequence, sensor_to_base, layout.compression, [&](const Out& m) {
        tally.add(m);
        sqlite3_reset(insert);
        sqlite3_bind_int64(insert, 1, static_cast<sqlite3_int64>(m.topic + 1));
        sqlite3_bind_int64(insert, 2, static_cast<sqlite3_int64>(m.time));
        sqlite3_bind_blob(insert, 3, m.cdr.data(), static_cast<int>(m.cdr.size()), SQLITE_TRANSIENT);
        if (sqlite3_step(insert) != SQLITE_DONE)
          throw std::runtime_error(tmp + ": SQLite: " + sqlite3_errmsg(db));
      });
    } catch (...) {
      sqlite3_finalize(insert);
      throw;
    }
    sqlite3_finalize(insert);
    metadata = bag_metadata("sqlite3", layout.file, topics, tally, layout.compression);
    sqlite3_stmt* s = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO metadata (metadata_version, metadata) VALUES (5, ?1)", -1, &s,
                       nullptr);
    sqlite3_bind_text(s, 1, metadata.c_str(), -1, SQLITE_TRANSIENT);
    const int rc = sqlite3_step(s);
    sqlite3_finalize(s);
    if (rc != SQLITE_DONE) throw std::runtime_error(tmp + ": SQLite: " + sqlite3_errmsg(db));
    exec("COMMIT;");
  } catch (...) {
    sqlite3_close(db);
    throw;
  }
  if (sqlite3_close(db) != SQLITE_OK) throw std::runtime_error(tmp + ": SQLite: cannot close");
  return metadata;
}

std::string write_mcap(const io::ScanSequence& sequence, const std::string& path, const Layout& layout,
                       const std::vector<TopicToWrite>& topics, mcap::Compression compression,
                       const Pose3& sensor_to_base) {
  mcap::WriterOptions o;
  o.profile = "ros2";
  o.compression = compression;
  mcap::Writer w(path, o);
  std::map<std::string, std::uint16_t> schemas;
  std::vector<std::uint16_t> channels;
  for (const TopicToWrite& t : topics) {
    if (!schemas.count(t.type)) schemas[t.type] = w.add_schema(t.type, "ros2msg", ros2::definition(t.type));
    channels.push_back(w.add_channel(schemas[t.type], t.name, "cdr",
                                     {{"offered_qos_profiles", qos_profile(t.transient_local)}}));
  }
  Tally tally;
  for_each_message(sequence, sensor_to_base, layout.compression, [&](const Out& m) {
    tally.add(m);
    w.write(channels[m.topic], m.time, m.time, m.cdr);
  });
  const std::string metadata = bag_metadata("mcap", layout.file, topics, tally, layout.compression);
  w.add_metadata("rosbag2", {{"serialized_metadata", metadata}, {"ROS_DISTRO", "humble"}});
  w.finish();
  return metadata;
}

}  // namespace

void write_rosbag2(const io::ScanSequence& sequence, const std::string& path, Rosbag2Storage storage,
                   mcap::Compression compression, const Pose3& sensor_to_base,
                   Rosbag2Compression bag_compression) {
  std::vector<TopicToWrite> topics = {{"/points", ros2::kPointCloud2, false},
                                      {"/odom", ros2::kOdometry, false},
                                      {kTfStaticTopic, ros2::kTfMessage, true}};
  if (!sequence.info().groundtruth.empty()) topics.push_back({"/groundtruth", ros2::kPoseStamped, false});
  const std::string ext = storage == Rosbag2Storage::mcap ? ".mcap" : ".db3";
  const bool folder = fs::path(path).extension() != ext;
  // A folder is made under a temporary name; a single file is written to one.
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  const std::string file =
      folder ? fs::path(path).filename().string() + "_0" + ext : fs::path(path).filename().string();
  const std::string target = folder ? (fs::path(tmp) / file).string() : tmp;
  const bool file_compressed = bag_compression == Rosbag2Compression::file;
  const Layout layout{file_compressed ? file + ".zstd" : file, bag_compression};
  std::error_code ec;
  if (!folder && bag_compression != Rosbag2Compression::none) {
    throw input_error(path, 0,
                      "rosbag2's own compression is for a bag folder, whose metadata.yaml records it: give a "
                      "name without " +
                          ext);
  }
  if (folder && fs::exists(path, ec)) throw input_error(path, 0, "exists: a bag folder is not written over");
  fs::remove_all(tmp, ec);
  try {
    if (folder && !fs::create_directory(tmp, ec))
      throw input_error(path, 0, "cannot make the bag folder: " + ec.message());
    const std::string metadata =
        storage == Rosbag2Storage::mcap
            ? write_mcap(sequence, target, layout, topics, compression, sensor_to_base)
            : write_sqlite(sequence, target, layout, topics, sensor_to_base);
    if (file_compressed) {  // as rosbag2 does once a file is closed: the file replaced by its .zstd
      mcap::compress_zstd_file(target, target + ".zstd");
      fs::remove(target);
    }
    if (folder) {
      std::ofstream out(fs::path(tmp) / kMetadataFile);
      out << metadata;
      if (!out) throw std::runtime_error(tmp + ": cannot write metadata.yaml");
    }
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove_all(tmp, ec);
    throw input_error(path, 0, "cannot rename into place: " + ec.message());
  }
}

}  // namespace tsgraphs::ros2_bag
