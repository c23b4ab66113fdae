#pragma once
/// MCAP files (mcap.dev/spec, major version 0) read and written without an MCAP library: the
/// record structure, chunks (uncompressed, lz4 frames, zstd; Debian's liblz4 and libzstd), the
/// CRC32s, and the summary's index when present. A reader that finds no usable index (no
/// summary, a summary cut off, chunks without message indexes) reads the data section from the
/// start instead. Messages are bytes here: what they encode is the caller's (ros2_messages.hpp).
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tsgraphs::mcap {

enum class Compression { none, lz4, zstd };

/// "", "lz4" or "zstd", as a Chunk record names it.
const char* compression_name(Compression c);

struct Schema {
  std::uint16_t id = 0;
  std::string name;      ///< e.g. "sensor_msgs/msg/PointCloud2"
  std::string encoding;  ///< e.g. "ros2msg"
  std::string data;      ///< the definition's text
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  ///< 0: none
  std::string topic;
  std::string message_encoding;  ///< e.g. "cdr"
  std::map<std::string, std::string> metadata;
};

/// Where a message is, and when it was logged: its bytes are read by Reader::data.
struct MessageRef {
  static constexpr std::uint64_t kNoChunk = std::numeric_limits<std::uint64_t>::max();
  std::uint16_t channel_id = 0;
  std::uint64_t log_time = 0;      ///< ns
  std::uint64_t chunk = kNoChunk;  ///< file offset of the Chunk record holding it, or kNoChunk
  std::uint64_t offset = 0;  ///< of its Message record: in the chunk's uncompressed records, or in the file
};

/// A message's fields as its record holds them.
struct Message {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0, publish_time = 0;  ///< ns
  std::string data;
};

/// An MCAP file opened for reading. Anything malformed (a bad magic, a record running past its
/// section or the file, a length field past its record, a chunk that does not decompress to
/// its size, a CRC that does not match, a message on a channel never defined) is an InputError
/// naming the file and the record's byte offset. Reading data is thread-safe.
class Reader {
 public:
  explicit Reader(const std::string& path);
  /// Reads the file at `path`, naming it `shown` in errors and warnings (a file decompressed to
  /// a temporary place is named as the user knows it).
  Reader(const std::string& path, const std::string& shown);
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  const std::string& path() const { return path_; }
  const std::string& profile() const { return profile_; }
  const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
  /// Every message, by log_time (file order among equal times).
  const std::vector<MessageRef>& messages() const { return messages_; }
  /// Whether the summary's chunk and message indexes gave the messages (else a linear scan).
  bool indexed() const { return indexed_; }
  /// Why the index was not used, if it was not and the file has a summary; for the front end.
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// The message `ref` points at (its chunk decompressed and its CRC checked when needed).
  Message read(const MessageRef& ref) const;
  /// Every message of `refs` in the order given, each chunk decompressed once for a run of
  /// refs in it: f(ref, message).
  void read_each(const std::vector<MessageRef>& refs,
                 const std::function<void(const MessageRef&, const Message&)>& f) const;

 private:
  struct File;
  void read_summary_or_scan();
  bool read_index(std::string* why_not);
  bool read_summary(std::uint64_t* summary_start, std::string* summary, std::string* why_not) const;
  bool read_message_indexes(std::uint64_t chunk_offset,
                            const std::map<std::uint16_t, std::uint64_t>& message_indexes,
                            std::string* why_not);
  void scan();
  std::shared_ptr<const std::string> chunk_records(
      std::uint64_t chunk_offset) const;  // cached, one at a time
  std::shared_ptr<const std::string> unpack_chunk(const std::string& content,
                                                  std::uint64_t chunk_offset) const;
  Message message_at(const std::string& bytes, std::uint64_t offset, const std::string& where) const;

  std::string path_;
  std::unique_ptr<File> file_;
  std::string profile_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::vector<MessageRef> messages_;
  bool indexed_ = false;
  std::vector<std::string> warnings_;
};

struct WriterOptions {
  std::string profile;  ///< e.g. "ros2"
  std::string library = "tsgraphs";
  Compression compression = Compression::zstd;
  std::uint64_t chunk_size = 1u << 20;  ///< a chunk is written once its records reach this many bytes
};

/// Writes an MCAP file with chunks, message indexes, a summary (schemas, channels, chunk
/// indexes, statistics), summary offsets and every CRC, under a temporary name renamed into
/// place by finish(); destroyed unfinished, it leaves nothing.
class Writer {
 public:
  Writer(const std::string& path, WriterOptions options = {});
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// Ids from 1, in the order added.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                            const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  /// A message on `channel_id` (sequence numbers counted per channel).
  void write(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time,
             const std::string& data);
  /// Adds a Metadata record (rosbag2 keeps its bag metadata in one named "rosbag2").
  void add_metadata(const std::string& name, const std::map<std::string, std::string>& metadata);
  void finish();

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace tsgraphs::mcap
