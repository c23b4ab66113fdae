// MCAP files read: the summary's index when it is usable, else the data section from the start.
#include "tsgraphs/mcap/mcap.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <tuple>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/mcap/compression.hpp"
#include "tsgraphs/mcap/mcap_internal.hpp"

namespace tsgraphs::mcap {

using namespace internal;

namespace {

constexpr std::uint64_t kPrefixBytes = 9;  // opcode (1) and content length (8)
// A chunk's uncompressed records at most (as ROS1 bag chunks): a larger size word is corrupt,
// and decompressing it would allocate what the file does not hold.
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 30;

std::string op_name(std::uint8_t op) {
  static const char* const kNames[] = {
      "opcode 0", "Header",         "Footer",         "Schema",     "Channel",          "Message",
      "Chunk",    "Message Index",  "Chunk Index",    "Attachment", "Attachment Index", "Statistics",
      "Metadata", "Metadata Index", "Summary Offset", "Data End"};
  return op < sizeof kNames / sizeof kNames[0] ? kNames[op] : "opcode " + std::to_string(op);
}

template <class T>
T little(const char* p) {  // little-endian, whatever the host
  T v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(static_cast<std::uint8_t>(p[i])) << (8 * i);
  return v;
}

/// One record's content read field by field; a field past the content's end is an InputError
/// naming the file, the record and the field.
class Fields {
 public:
  Fields(const char* p, std::uint64_t n, const std::string& path, std::string where)
      : p_(p), n_(n), path_(path), where_(std::move(where)) {}
  template <class T>
  T num(const char* what) {
    need(sizeof(T), what);
    const T v = little<T>(p_ + at_);
    at_ += sizeof(T);
    return v;
  }
  std::string str(const char* what) { return take(num<std::uint32_t>(what), what); }
  /// A uint64 length-prefixed field: where its bytes start in the content, and how many.
  std::pair<std::uint64_t, std::uint64_t> span64(const char* what) {
    const std::uint64_t n = num<std::uint64_t>(what);
    need(n, what);
    const std::uint64_t start = at_;
    at_ += n;
    return {start, n};
  }
  std::map<std::string, std::string> string_map(const char* what) {
    const std::uint32_t bytes = num<std::uint32_t>(what);
    need(bytes, what);
    Fields m(p_ + at_, bytes, path_, where_);
    at_ += bytes;
    std::map<std::string, std::string> out;
    while (m.at_ < m.n_) {
      std::string key = m.str(what);
      out[key] = m.str(what);
    }
    return out;
  }
  /// An Array or Map of fixed-size entries: the start of its entries and their count.
  std::pair<std::uint64_t, std::uint64_t> fixed_entries(std::uint64_t entry_bytes, const char* what) {
    const std::uint32_t bytes = num<std::uint32_t>(what);
    need(bytes, what);
    if (bytes % entry_bytes != 0)
      fail(std::string(what) + " holds " + std::to_string(bytes) + " bytes, not whole entries");
    const std::uint64_t start = at_;
    at_ += bytes;
    return {start, bytes / entry_bytes};
  }
  std::uint64_t at() const { return at_; }
  std::uint64_t left() const { return n_ - at_; }
  [[noreturn]] void fail(const std::string& what) const { throw input_error(path_, 0, where_ + ": " + what); }

 private:
  void need(std::uint64_t n, const char* what) const {
    if (n > n_ - at_) {
      fail(std::string("field ") + what + " (" + std::to_string(n) + " bytes at byte " + std::to_string(at_) +
           " of the record) runs past its end (" + std::to_string(n_) + " bytes)");
    }
  }
  std::string take(std::uint64_t n, const char* what) {
    need(n, what);
    std::string s(p_ + at_, n);
    at_ += n;
    return s;
  }
  const char* p_;
  std::uint64_t n_;
  std::uint64_t at_ = 0;
  const std::string& path_;
  std::string where_;
};

std::string record_at(std::uint8_t op, std::uint64_t offset, const std::string& in = "") {
  return op_name(op) + " record at byte " + std::to_string(offset) + in;
}

/// A chunk's records: `src` decompressed to exactly `size` bytes, a size beyond kMaxChunkBytes refused first.
std::string unpack(const std::string& compression, const char* src, std::uint64_t n, std::uint64_t size,
                   const std::string& path, const std::string& where) {
  if (size > kMaxChunkBytes) {
    throw input_error(path, 0,
                      where + ": uncompressed size " + std::to_string(size) + " is beyond " +
                          std::to_string(kMaxChunkBytes) + " bytes (corrupt?)");
  }
  return mcap::decompress(compression, src, n, size, path, where);
}

}  // namespace

/// The file, read at offsets from any thread (pread).
struct Reader::File {
  int fd = -1;
  std::uint64_t size = 0;
  std::string path;
  mutable std::mutex cache_mutex;
  mutable std::uint64_t cached_chunk = MessageRef::kNoChunk;
  mutable std::shared_ptr<const std::string> cached;

  ~File() {
    if (fd >= 0) ::close(fd);
  }
  /// n bytes at `offset`, or an InputError saying what ran past the end.
  std::string read(std::uint64_t offset, std::uint64_t n, const std::string& what) const {
    if (offset > size || n > size - offset) {
      throw input_error(
          path, 0, what + " runs past the end of the file (" + std::to_string(size) + " bytes; cut short?)");
    }
    std::string out(n, '\0');
    for (std::uint64_t done = 0; done < n;) {
      const ssize_t got = ::pread(fd, out.data() + done, n - done, static_cast<off_t>(offset + done));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0)
        throw input_error(path, 0, "cannot read " + what + ": " + std::strerror(got < 0 ? errno : EIO));
      done += static_cast<std::uint64_t>(got);
    }
    return out;
  }
  /// The record at `offset`: its opcode and content.
  std::pair<std::uint8_t, std::string> record(std::uint64_t offset, const std::string& what) const {
    const std::string prefix = read(offset, kPrefixBytes, what + " at byte " + std::to_string(offset));
    const auto op = static_cast<std::uint8_t>(prefix[0]);
    const auto n = little<std::uint64_t>(prefix.data() + 1);
    return {op, read(offset + kPrefixBytes, n, record_at(op, offset, " (" + std::to_string(n) + " bytes)"))};
  }
};

Reader::Reader(const std::string& path) : Reader(path, path) {}

Reader::Reader(const std::string& path, const std::string& shown)
    : path_(shown), file_(std::make_unique<File>()) {
  file_->path = shown;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw input_error(shown, 0, "is a folder, not an MCAP file");
  file_->fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (file_->fd < 0) throw input_error(shown, 0, std::string("cannot open file: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(file_->fd, &st) != 0)
    throw input_error(shown, 0, std::string("cannot read file: ") + std::strerror(errno));
  file_->size = static_cast<std::uint64_t>(st.st_size);
  if (file_->read(0, std::min<std::uint64_t>(kMagicBytes, file_->size), "the magic") !=
      std::string(kMagic, kMagicBytes)) {
    throw input_error(shown, 0, "not an MCAP file (no MCAP magic at its start)");
  }
  const auto [op, content] = file_->record(kMagicBytes, "the Header record");
  if (op != kHeader) throw input_error(shown, 0, "byte 8: expected the Header record, found " + op_name(op));
  Fields h(content.data(), content.size(), path_, record_at(op, kMagicBytes));
  profile_ = h.str("profile");
  read_summary_or_scan();
}

Reader::~Reader() = default;

void Reader::read_summary_or_scan() {
  std::string why;
  if (read_index(&why)) {
    indexed_ = true;
  } else {
    if (!why.empty())
      warnings_.push_back(path_ + ": " + why + "; its messages are found by reading it from the start");
    schemas_.clear(), channels_.clear(), messages_.clear();
    scan();
  }
  // By log time; among equal times, in file order.
  const auto position = [](const MessageRef& m) {
    return m.chunk != MessageRef::kNoChunk ? std::make_tuple(m.log_time, m.chunk, m.offset)
                                           : std::make_tuple(m.log_time, m.offset, std::uint64_t{0});
  };
  std::stable_sort(messages_.begin(), messages_.end(),
                   [&](const MessageRef& a, const MessageRef& b) { return position(a) < position(b); });
}

namespace {

Schema read_schema(Fields& r) {
  Schema s;
  s.id = r.num<std::uint16_t>("id");
  s.name = r.str("name"), s.encoding = r.str("encoding"), s.data = r.str("data");
  return s;
}

Channel read_channel(Fields& r) {
  Channel c;
  c.id = r.num<std::uint16_t>("id"), c.schema_id = r.num<std::uint16_t>("schema_id");
  c.topic = r.str("topic"), c.message_encoding = r.str("message_encoding"),
  c.metadata = r.string_map("metadata");
  return c;
}

/// A Chunk Index record: its chunk, and where each channel's Message Index is.
struct ChunkIndex {
  std::uint64_t offset = 0, length = 0;
  std::map<std::uint16_t, std::uint64_t> message_indexes;
};

/// The Chunk Index record `r`, whose content starts at `content`; its chunk must lie in the data
/// section (before `summary_start`).
ChunkIndex read_chunk_index(Fields& r, const char* content, std::uint64_t summary_start) {
  ChunkIndex c;
  r.num<std::uint64_t>("message_start_time"), r.num<std::uint64_t>("message_end_time");
  c.offset = r.num<std::uint64_t>("chunk_start_offset"), c.length = r.num<std::uint64_t>("chunk_length");
  const auto [start, count] = r.fixed_entries(10, "message_index_offsets");
  for (std::uint64_t i = 0; i < count; ++i) {
    const char* e = content + start + 10 * i;
    c.message_indexes[little<std::uint16_t>(e)] = little<std::uint64_t>(e + 2);
  }
  if (c.offset < kMagicBytes || c.length > summary_start || c.offset > summary_start - c.length)
    r.fail("its chunk is outside the data section");
  return c;
}

/// What the summary section's records say of the messages.
struct SummaryRecords {
  std::vector<ChunkIndex> chunks;
  std::optional<std::uint64_t> message_count;  // the Statistics record's, when there is one
};

/// The records of the summary section `summary` (at byte `summary_start`): its schemas and
/// channels into `schemas` and `channels`, its chunk indexes and statistics returned.
SummaryRecords read_summary_records(const std::string& summary, std::uint64_t summary_start,
                                    const std::string& path, std::map<std::uint16_t, Schema>& schemas,
                                    std::map<std::uint16_t, Channel>& channels) {
  SummaryRecords out;
  for (std::uint64_t at = 0; at < summary.size();) {
    const std::uint64_t abs = summary_start + at;
    if (summary.size() - at < kPrefixBytes)
      throw input_error(path, 0, "a record at byte " + std::to_string(abs) + " is cut short");
    const auto op = static_cast<std::uint8_t>(summary[at]);
    const auto n = little<std::uint64_t>(summary.data() + at + 1);
    if (n > summary.size() - at - kPrefixBytes) {
      throw input_error(path, 0, record_at(op, abs) + " runs past the summary section");
    }
    Fields r(summary.data() + at + kPrefixBytes, n, path, record_at(op, abs));
    if (op == kSchema) {
      const Schema s = read_schema(r);
      if (s.id != 0) schemas.emplace(s.id, s);
    } else if (op == kChannel) {
      const Channel c = read_channel(r);
      channels.emplace(c.id, c);
    } else if (op == kChunkIndex) {
      out.chunks.push_back(read_chunk_index(r, summary.data() + at + kPrefixBytes, summary_start));
    } else if (op == kStatistics) {
      out.message_count = r.num<std::uint64_t>("message_count");
    }
    at += kPrefixBytes + n;
  }
  return out;
}

}  // namespace

bool Reader::read_summary(std::uint64_t* summary_start, std::string* summary, std::string* why) const {
  const File& f = *file_;
  const std::uint64_t tail = kPrefixBytes + kFooterContentBytes + kMagicBytes;
  if (f.size < kMagicBytes + kPrefixBytes + tail) {
    *why = "the file is too short for a footer (cut short?)";
    return false;
  }
  const std::uint64_t footer_at = f.size - tail;
  const std::string end = f.read(footer_at, tail, "the footer");
  if (end.compare(kPrefixBytes + kFooterContentBytes, kMagicBytes, kMagic, kMagicBytes) != 0 ||
      end[0] != kFooter || little<std::uint64_t>(end.data() + 1) != kFooterContentBytes) {
    *why = "it does not end in an MCAP footer (cut short?)";
    return false;
  }
  *summary_start = little<std::uint64_t>(end.data() + kPrefixBytes);
  const auto summary_crc = little<std::uint32_t>(end.data() + kPrefixBytes + 16);
  if (*summary_start == 0) return false;  // no summary: nothing to warn about
  if (*summary_start < kMagicBytes || *summary_start > footer_at) {
    throw input_error(path_, 0,
                      "Footer: summary_start " + std::to_string(*summary_start) + " is outside the file");
  }
  *summary = f.read(*summary_start, footer_at - *summary_start, "the summary section");
  if (summary_crc != 0) {
    const std::uint32_t crc = crc_of(end.data(), kPrefixBytes + 16, crc_of(summary->data(), summary->size()));
    if (crc != summary_crc) {
      throw input_error(path_, 0,
                        "the summary section at byte " + std::to_string(*summary_start) +
                            " does not match its CRC (corrupt)");
    }
  }
  return true;
}

bool Reader::read_message_indexes(std::uint64_t chunk_offset,
                                  const std::map<std::uint16_t, std::uint64_t>& message_indexes,
                                  std::string* why) {
  if (message_indexes.empty()) {
    *why = "the chunk at byte " + std::to_string(chunk_offset) + " has no message index";
    return false;
  }
  for (const auto& [channel, offset] : message_indexes) {
    if (!channels_.count(channel)) {
      *why = "the summary lacks channel " + std::to_string(channel) + " of the chunk at byte " +
             std::to_string(chunk_offset);
      return false;
    }
    const auto [op, content] =
        file_->record(offset, "the Message Index of channel " + std::to_string(channel));
    if (op != kMessageIndex) {
      throw input_error(path_, 0,
                        "byte " + std::to_string(offset) + ": a Chunk Index points at a " + op_name(op) +
                            " record, not a Message Index");
    }
    Fields r(content.data(), content.size(), path_, record_at(op, offset));
    if (r.num<std::uint16_t>("channel_id") != channel)
      r.fail("its channel is not the one the Chunk Index names");
    const auto [start, count] = r.fixed_entries(16, "records");
    for (std::uint64_t i = 0; i < count; ++i) {
      const char* e = content.data() + start + 16 * i;
      messages_.push_back({channel, little<std::uint64_t>(e), chunk_offset, little<std::uint64_t>(e + 8)});
    }
  }
  return true;
}

bool Reader::read_index(std::string* why) {
  std::uint64_t summary_start = 0;
  std::string summary;
  if (!read_summary(&summary_start, &summary, why)) return false;
  const SummaryRecords records = read_summary_records(summary, summary_start, path_, schemas_, channels_);
  if (records.chunks.empty()) return false;  // unchunked (or empty): the messages are found by a scan
  for (const ChunkIndex& c : records.chunks)
    if (!read_message_indexes(c.offset, c.message_indexes, why)) return false;
  // Messages outside chunks have no index: the statistics tell whether there are any.
  if (records.message_count && *records.message_count != messages_.size()) {
    *why = "its index holds " + std::to_string(messages_.size()) + " of the " +
           std::to_string(*records.message_count) + " messages its statistics count";
    return false;
  }
  return true;
}

void Reader::scan() {
  const File& f = *file_;
  std::uint64_t pos = kMagicBytes;
  std::uint32_t crc = crc_of(kMagic, kMagicBytes);
  const auto define = [&](std::uint8_t op, Fields& r) {
    if (op == kSchema) {
      const Schema s = read_schema(r);
      if (s.id != 0) schemas_.emplace(s.id, s);
    } else {
      const Channel c = read_channel(r);
      channels_.emplace(c.id, c);
    }
  };
  const auto message = [&](Fields& r, std::uint64_t chunk, std::uint64_t offset) {
    const auto channel = r.num<std::uint16_t>("channel_id");
    r.num<std::uint32_t>("sequence");
    const auto log_time = r.num<std::uint64_t>("log_time");
    if (!channels_.count(channel))
      r.fail("a message on channel " + std::to_string(channel) + " before its Channel record");
    messages_.push_back({channel, log_time, chunk, offset});
  };
  for (bool first = true;; first = false) {
    if (pos + kPrefixBytes > f.size) {
      throw input_error(path_, 0,
                        "the data section ends at byte " + std::to_string(f.size) +
                            " without a Data End or Footer record (cut short?)");
    }
    const std::string prefix = f.read(pos, kPrefixBytes, "record prefix");
    const auto op = static_cast<std::uint8_t>(prefix[0]);
    const auto n = little<std::uint64_t>(prefix.data() + 1);
    const std::string content =
        f.read(pos + kPrefixBytes, n, record_at(op, pos, " (" + std::to_string(n) + " bytes)"));
    Fields r(content.data(), content.size(), path_, record_at(op, pos));
    if (op == kDataEnd) {
      const auto expected = r.num<std::uint32_t>("data_section_crc");
      if (expected != 0 && expected != crc) {
        throw input_error(
            path_, 0,
            "the data section (bytes 0 to " + std::to_string(pos) + ") does not match its CRC (corrupt)");
      }
      return;
    }
    if (op == kFooter) return;  // a file without Data End
    crc = crc_of(content.data(), content.size(), crc_of(prefix.data(), prefix.size(), crc));
    if (first && op == kHeader) {
      pos += kPrefixBytes + n;
      continue;
    }
    if (op == kSchema || op == kChannel) define(op, r);
    if (op == kMessage) message(r, MessageRef::kNoChunk, pos);
    if (op == kChunk) {
      const std::shared_ptr<const std::string> records = unpack_chunk(content, pos);
      for (std::uint64_t at = 0; at < records->size();) {
        const std::string where = record_at(kChunk, pos, ", its record at byte " + std::to_string(at));
        if (records->size() - at < kPrefixBytes) throw input_error(path_, 0, where + ": cut short");
        const auto inner = static_cast<std::uint8_t>((*records)[at]);
        const auto m = little<std::uint64_t>(records->data() + at + 1);
        if (m > records->size() - at - kPrefixBytes)
          throw input_error(path_, 0, where + ": runs past the chunk's records");
        Fields ir(records->data() + at + kPrefixBytes, m, path_, where + " (" + op_name(inner) + ")");
        if (inner == kSchema || inner == kChannel) define(inner, ir);
        if (inner == kMessage) message(ir, pos, at);
        at += kPrefixBytes + m;
      }
    }
    pos += kPrefixBytes + n;
  }
}

std::shared_ptr<const std::string> Reader::chunk_records(std::uint64_t chunk_offset) const {
  {
    std::lock_guard<std::mutex> lock(file_->cache_mutex);
    if (file_->cached_chunk == chunk_offset) return file_->cached;
  }
  const auto [op, content] = file_->record(chunk_offset, "a Chunk record");
  if (op != kChunk)
    throw input_error(
        path_, 0, "byte " + std::to_string(chunk_offset) + ": expected a Chunk record, found " + op_name(op));
  auto records = unpack_chunk(content, chunk_offset);
  std::lock_guard<std::mutex> lock(file_->cache_mutex);
  file_->cached_chunk = chunk_offset;
  file_->cached = records;
  return records;
}

std::shared_ptr<const std::string> Reader::unpack_chunk(const std::string& content,
                                                        std::uint64_t chunk_offset) const {
  const std::string where = record_at(kChunk, chunk_offset);
  Fields r(content.data(), content.size(), path_, where);
  r.num<std::uint64_t>("message_start_time"), r.num<std::uint64_t>("message_end_time");
  const auto size = r.num<std::uint64_t>("uncompressed_size");
  const auto crc = r.num<std::uint32_t>("uncompressed_crc");
  const std::string compression = r.str("compression");
  const auto [start, n] = r.span64("records");
  auto records =
      std::make_shared<const std::string>(unpack(compression, content.data() + start, n, size, path_, where));
  if (crc != 0 && crc_of(records->data(), records->size()) != crc) {
    throw input_error(path_, 0, where + ": its records do not match their CRC (corrupt)");
  }
  return records;
}

Message Reader::message_at(const std::string& bytes, std::uint64_t offset, const std::string& where) const {
  if (offset > bytes.size() || bytes.size() - offset < kPrefixBytes)
    throw input_error(path_, 0, where + ": outside its chunk");
  const auto op = static_cast<std::uint8_t>(bytes[offset]);
  const auto n = little<std::uint64_t>(bytes.data() + offset + 1);
  if (op != kMessage) throw input_error(path_, 0, where + ": a " + op_name(op) + " record, not a Message");
  if (n > bytes.size() - offset - kPrefixBytes)
    throw input_error(path_, 0, where + ": runs past its chunk's records");
  Fields r(bytes.data() + offset + kPrefixBytes, n, path_, where);
  Message m;
  m.channel_id = r.num<std::uint16_t>("channel_id");
  m.sequence = r.num<std::uint32_t>("sequence");
  m.log_time = r.num<std::uint64_t>("log_time");
  m.publish_time = r.num<std::uint64_t>("publish_time");
  m.data.assign(bytes.data() + offset + kPrefixBytes + r.at(), r.left());
  return m;
}

Message Reader::read(const MessageRef& ref) const {
  if (ref.chunk == MessageRef::kNoChunk) {
    const auto [op, content] = file_->record(ref.offset, "a Message record");
    std::string whole(kPrefixBytes, '\0');
    whole[0] = static_cast<char>(op);
    for (int i = 0; i < 8; ++i) whole[1 + i] = static_cast<char>(content.size() >> (8 * i));
    return message_at(whole + content, 0, record_at(op, ref.offset));
  }
  return message_at(*chunk_records(ref.chunk), ref.offset,
                    record_at(kChunk, ref.chunk, ", the message at byte " + std::to_string(ref.offset)));
}

void Reader::read_each(const std::vector<MessageRef>& refs,
                       const std::function<void(const MessageRef&, const Message&)>& f) const {
  for (const MessageRef& ref : refs)
    f(ref, read(ref));  // the one-chunk cache keeps each chunk's decompression to one per run
}

}  // namespace tsgraphs::mcap
