// The structure of a ROS 1 bag checked before rosbag reads it.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/ros1_bag/ros_bag_internal.hpp"

namespace tsgraphs::ros1_bag::ros_bag_internal {

namespace {

namespace fs = std::filesystem;

// ROS bag format 2.0 (wiki.ros.org/Bags/Format/2.0), as much as the structure check needs.
// rosbag trusts every length it reads (a flipped byte in a chunk header is a SIGSEGV, a header
// length near 2^32 its assert), so each is checked here, against the bytes that exist, first.
constexpr char kBagMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kBagMagicBytes = sizeof(kBagMagic) - 1;
constexpr std::uint8_t kOpMessageData = 0x02, kOpBagHeader = 0x03, kOpIndexData = 0x04, kOpChunk = 0x05,
                       kOpChunkInfo = 0x06, kOpConnection = 0x07;
constexpr std::uint64_t kIndexEntryBytes = 12;     // index data entry: time (8), offset (4)
constexpr std::uint64_t kChunkInfoEntryBytes = 8;  // chunk info entry: conn (4), count (4)
constexpr std::uint32_t kIndexVersion = 1;         // `ver` of index data and chunk info
// ROS's own header parser refuses a field over 1e6 bytes; real record headers are tens of bytes.
constexpr std::uint64_t kMaxRecordHeaderBytes = 1u << 20;
// rosbag allocates a chunk's declared uncompressed size at once; writers close a chunk near
// 768 KB, so a chunk over a gigabyte is corruption, not data.
constexpr std::uint64_t kMaxChunkBytes = 1ull << 30;
constexpr const char* kNoEncryptor = "rosbag/NoEncryptor";

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

/// check_bag's walk through the bag.
class BagChecker {
 public:
  explicit BagChecker(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    std::error_code ec;
    size_ = fs::file_size(path, ec);
    if (ec || !in_)
      throw input_error(path, 0, "cannot read the bag" + (ec ? ": " + ec.message() : std::string()));
    eof_ = "the end of the file (" + std::to_string(size_) + " bytes)";
  }

  BagLimits check() {
    const BagHead head = bag_header();
    for (std::uint64_t pos = head.record.end(); pos < size_;) {
      BagRecord r = record(pos, size_, eof_);
      switch (r.op) {
        case kOpChunk:
          chunk(r, head.encrypted);
          break;
        case kOpIndexData:
          index_data(r);
          break;
        case kOpConnection:
          connection(r);
          break;
        case kOpChunkInfo:
          chunk_info(r);
          break;
        default:
          fail(r.pos, op_name(r.op) + " record (op " + std::to_string(r.op) +
                          ") where a chunk, index or connection belongs");
      }
      pos = r.end();
      r.fields.clear();  // only op and place are looked at again
      records_.push_back(std::move(r));
    }
    if (head.index_pos == 0) return limits_;  // an unindexed bag: rosbag says so itself
    check_index(head);
    return limits_;
  }

 private:
  /// The bag header record and what it says of the rest.
  struct BagHead {
    BagRecord record;
    std::uint64_t index_pos = 0, conn_count = 0, chunk_count = 0;
    bool encrypted = false;
  };

  struct Chunk {
    std::uint64_t size = 0;
    bool opaque = false;                 ///< compressed or encrypted: its records cannot be seen
    std::set<std::uint64_t> message_at;  ///< offsets of its message data records
  };

  /// The magic and the bag header record after it.
  BagHead bag_header() {
    if (size_ < kBagMagicBytes || read(0, kBagMagicBytes) != kBagMagic)
      throw input_error(path_, 0, "not a ROS bag 2.0 (it does not start with '#ROSBAG V2.0')");
    BagHead head;
    head.record = record(kBagMagicBytes, size_, eof_);
    const BagRecord& r = head.record;
    if (r.op != kOpBagHeader) fail(r.pos, "the first record is " + op_name(r.op) + ", not the bag header");
    head.index_pos = number(r, "index_pos", 8);
    head.conn_count = number(r, "conn_count", 4);
    head.chunk_count = number(r, "chunk_count", 4);
    const auto encryptor = r.fields.find("encryptor");
    head.encrypted =
        encryptor != r.fields.end() && !encryptor->second.empty() && encryptor->second != kNoEncryptor;
    if (head.index_pos > size_)
      fail(r.pos, "index_pos " + std::to_string(head.index_pos) + " is past " + eof_);
    return head;
  }

  /// A chunk record: its compression and size, and the records inside when it is not opaque.
  void chunk(const BagRecord& r, bool encrypted) {
    Chunk c;
    const std::string compression = text(r, "compression");
    if (compression != "none" && compression != "bz2" && compression != "lz4")
      fail(r.pos, "chunk compression '" + printable(compression) + "' is none of none, bz2, lz4");
    c.size = number(r, "size", 4);
    if (c.size > kMaxChunkBytes)
      fail(r.pos, "chunk size " + std::to_string(c.size) + " is over the " + std::to_string(kMaxChunkBytes) +
                      " bytes any chunk has");
    c.opaque = compression != "none" || encrypted;
    if (!c.opaque) {
      if (c.size != r.data_len)
        fail(r.pos, "uncompressed chunk of size " + std::to_string(c.size) + " holds " +
                        std::to_string(r.data_len) + " bytes");
      chunk_records(r, c);
    }
    limits_.largest_chunk = std::max(limits_.largest_chunk, c.size);
    if (last_chunk_) last_chunk_->message_at.clear();  // only the latest chunk's index records follow it
    last_chunk_ = &(chunks_[r.pos] = std::move(c));
  }

  /// The records inside uncompressed chunk `r`: messages (whose offsets `c` keeps) and connections.
  void chunk_records(const BagRecord& r, Chunk& c) {
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

  /// An index data record: each entry's offset a message of the chunk before it.
  void index_data(const BagRecord& r) {
    if (number(r, "ver", 4) != kIndexVersion) fail(r.pos, "index data version is not 1");
    number(r, "conn", 4);
    const std::uint64_t count = number(r, "count", 4);
    if (count * kIndexEntryBytes != r.data_len)
      fail(r.pos, "index data of " + std::to_string(count) + " entries holds " + std::to_string(r.data_len) +
                      " bytes");
    if (!last_chunk_) fail(r.pos, "index data before any chunk");
    const std::string entries = read(r.data_pos, r.data_len);
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::uint64_t at = i * kIndexEntryBytes + 8;  // past the entry's time
      const std::uint64_t offset = little_endian(entries.substr(at, kLengthBytes));
      if (offset >= last_chunk_->size)
        fail(r.data_pos + at, "index offset " + std::to_string(offset) + " is past its chunk's " +
                                  std::to_string(last_chunk_->size) + " bytes");
      if (!last_chunk_->opaque && !last_chunk_->message_at.count(offset))
        fail(r.data_pos + at, "index offset " + std::to_string(offset) + " is not a message in its chunk");
    }
  }

  /// A chunk info record: its entries fill its data, and a chunk starts where it points.
  void chunk_info(const BagRecord& r) {
    if (number(r, "ver", 4) != kIndexVersion) fail(r.pos, "chunk info version is not 1");
    const std::uint64_t chunk_pos = number(r, "chunk_pos", 8);
    number(r, "start_time", 8);
    number(r, "end_time", 8);
    const std::uint64_t count = number(r, "count", 4);
    if (count * kChunkInfoEntryBytes != r.data_len)
      fail(r.pos, "chunk info of " + std::to_string(count) + " entries holds " + std::to_string(r.data_len) +
                      " bytes");
    if (!chunks_.count(chunk_pos))
      fail(r.pos, "chunk info points at byte " + std::to_string(chunk_pos) + ", where no chunk starts");
  }

  /// The first top-level record at or after `pos`.
  std::vector<BagRecord>::const_iterator record_at(std::uint64_t pos) const {
    return std::lower_bound(records_.begin(), records_.end(), pos,
                            [](const BagRecord& r, std::uint64_t p) { return r.pos < p; });
  }

  /// What rosbag reads at open: conn_count connections and chunk_count chunk infos from
  /// index_pos on, and after each chunk the index data records its chunk info counts.
  void check_index(const BagHead& head) {
    auto it = record_at(head.index_pos);
    if (it == records_.end() || it->pos != head.index_pos)
      fail(head.record.pos, "index_pos " + std::to_string(head.index_pos) + " is not the start of a record");
    for (std::uint64_t i = 0; i < head.conn_count + head.chunk_count; ++i, ++it) {
      const std::uint8_t wanted = i < head.conn_count ? kOpConnection : kOpChunkInfo;
      if (it == records_.end())
        fail(size_, "the index ends after " + std::to_string(i) + " of " + std::to_string(head.conn_count) +
                        " connections and " + std::to_string(head.chunk_count) + " chunk infos");
      if (it->op != wanted)
        fail(it->pos, op_name(it->op) + " record where the index has a " + op_name(wanted));
      if (wanted == kOpChunkInfo) chunk_indexes(it->pos);
    }
  }

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
  void chunk_indexes(std::uint64_t info_pos) {
    const BagRecord info = record(info_pos, size_, "the end of the file");
    const std::uint64_t chunk_pos = number(info, "chunk_pos", 8), count = number(info, "count", 4);
    auto it = record_at(chunk_pos);
    for (std::uint64_t i = 0; i < count; ++i) {
      if (++it == records_.end() || it->op != kOpIndexData)
        fail(info_pos, "chunk info counts " + std::to_string(count) + " connections, the chunk at byte " +
                           std::to_string(chunk_pos) + " is followed by " + std::to_string(i) +
                           " index records");
    }
  }

  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::string eof_;  ///< "the end of the file (N bytes)", for messages
  BagLimits limits_;
  std::vector<BagRecord> records_;         ///< the top-level ones, in file order (headers only kept)
  std::map<std::uint64_t, Chunk> chunks_;  ///< by their record's place
  Chunk* last_chunk_ = nullptr;
};

}  // namespace

std::uint64_t little_endian(const std::string& bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = bytes.size(); i-- > 0;) v = v << 8 | static_cast<std::uint8_t>(bytes[i]);
  return v;
}

BagLimits check_bag(const std::string& path) { return BagChecker(path).check(); }

bool is_bag_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && status.type() != fs::file_type::not_found)
    throw input_error(path, 0, "cannot read the bag: " + ec.message());
  return fs::is_regular_file(status);
}

}  // namespace tsgraphs::ros1_bag::ros_bag_internal
