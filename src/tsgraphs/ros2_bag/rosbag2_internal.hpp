#pragma once
/// What the rosbag2 files share (rosbag2_storage, _metadata, _reader, _info and _writer.cpp): a
/// recording's storages (SQLite or MCAP files) as topics and located messages.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/mcap/mcap.hpp"

namespace tsgraphs::ros2_bag::rosbag2_internal {

constexpr const char* kTfStaticTopic = "/tf_static";
constexpr const char* kMetadataFile = "metadata.yaml";

/// A topic as a storage records it.
struct Topic {
  std::string name, type, format;
  std::string definition;  ///< ros2msg text when the storage keeps one
  std::uint64_t count = 0;
};

/// The receive times of a file's first and last messages (ns).
struct TimeSpan {
  std::uint64_t first = 0, last = 0;
};

/// A message's place: its file, and its row (SQLite) or record (MCAP) there.
struct Located {
  std::size_t file = 0;
  std::uint64_t time = 0;  ///< ns
  std::int64_t row = 0;
  mcap::MessageRef ref;
};

class Storage {
 public:
  virtual ~Storage() = default;
  virtual std::vector<Topic> topics() const = 0;
  /// The messages of `topic`, by receive time.
  virtual std::vector<Located> messages(const std::string& topic, std::size_t file) const = 0;
  virtual std::string read(const Located& m) const = 0;
  /// When its first and last messages were received; none for a file without one.
  virtual std::optional<TimeSpan> time_span() const = 0;
  virtual std::vector<std::string> warnings() const { return {}; }
};

/// The storages of a recording: a folder's files in metadata.yaml's order, or the one file.
std::vector<std::unique_ptr<Storage>> open_recording(const std::string& path);

/// Topics of every file, merged by name; a topic of two types is an error.
std::map<std::string, Topic> topics_of(const std::vector<std::unique_ptr<Storage>>& storages,
                                       const std::string& path);

/// The messages of `topic` in every file, by receive time (file order among equal times).
std::vector<Located> messages_of(const std::vector<std::unique_ptr<Storage>>& storages,
                                 const std::string& topic);

/// rosbag2 starts a split's next file once the last is full, so each file's messages follow the
/// previous file's. One that starts before the last message of the file before it is a file
/// listed again under another name (a copy): its messages would be read twice, time going back.
/// Equal times pass: two topics' messages of one instant may fall either side of a split.
void check_follows(const std::string& metadata, int line, const std::string& file, const TimeSpan& span,
                   const std::string& previous_file, const TimeSpan& previous);

}  // namespace tsgraphs::ros2_bag::rosbag2_internal
