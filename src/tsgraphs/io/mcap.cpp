#include "tsgraphs/io/mcap.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <tuple>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/compression.hpp"

namespace tsgraphs::io::mcap {
namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";
constexpr std::uint64_t kMagicBytes = 8;
constexpr std::uint64_t kPrefixBytes = 9;          // opcode (1) and content length (8)
constexpr std::uint64_t kFooterContentBytes = 20;  // summary_start, summary_offset_start, summary_crc
// A chunk's uncompressed records at most (as ROS1 bag chunks): a larger size word is corrupt,
// and decompressing it would allocate what the file does not hold.
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 30;

enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

std::string op_name(std::uint8_t op) {
  static const char* const kNames[] = {
      "opcode 0", "Header",         "Footer",         "Schema",     "Channel",          "Message",
      "Chunk",    "Message Index",  "Chunk Index",    "Attachment", "Attachment Index", "Statistics",
      "Metadata", "Metadata Index", "Summary Offset", "Data End"};
  return op < sizeof kNames / sizeof kNames[0] ? kNames[op] : "opcode " + std::to_string(op);
}

std::uint32_t crc_of(const char* p, std::size_t n, std::uint32_t crc = 0) {
  return static_cast<std::uint32_t>(::crc32_z(crc, reinterpret_cast<const Bytef*>(p), n));
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
  return io::decompress(compression, src, n, size, path, where);
}

// ---- writing -------------------------------------------------------------------------------

void put_u16(std::string& s, std::uint16_t v) { s.append({static_cast<char>(v), static_cast<char>(v >> 8)}); }
void put_u32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>(v >> (8 * i)));
}
void put_u64(std::string& s, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) s.push_back(static_cast<char>(v >> (8 * i)));
}
void put_str(std::string& s, const std::string& v) {
  put_u32(s, static_cast<std::uint32_t>(v.size()));
  s += v;
}
void put_map(std::string& s, const std::map<std::string, std::string>& m) {
  std::string entries;
  for (const auto& [k, v] : m) put_str(entries, k), put_str(entries, v);
  put_str(s, entries);
}
std::string record(std::uint8_t op, const std::string& content) {
  std::string r(1, static_cast<char>(op));
  put_u64(r, content.size());
  return r + content;
}

std::string compress(Compression c, const std::string& in) {
  if (c == Compression::zstd) return compress_zstd(in);
  if (c == Compression::lz4) return compress_lz4(in);
  return in;
}

}  // namespace

const char* compression_name(Compression c) {
  switch (c) {
    case Compression::lz4:
      return "lz4";
    case Compression::zstd:
      return "zstd";
    default:
      return "";
  }
}

// ---- reading -------------------------------------------------------------------------------

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

bool Reader::read_index(std::string* why) {
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
  const auto summary_start = little<std::uint64_t>(end.data() + kPrefixBytes);
  const auto summary_crc = little<std::uint32_t>(end.data() + kPrefixBytes + 16);
  if (summary_start == 0) return false;  // no summary: nothing to warn about
  if (summary_start < kMagicBytes || summary_start > footer_at) {
    throw input_error(path_, 0,
                      "Footer: summary_start " + std::to_string(summary_start) + " is outside the file");
  }
  const std::string summary = f.read(summary_start, footer_at - summary_start, "the summary section");
  if (summary_crc != 0) {
    const std::uint32_t crc = crc_of(end.data(), kPrefixBytes + 16, crc_of(summary.data(), summary.size()));
    if (crc != summary_crc) {
      throw input_error(path_, 0,
                        "the summary section at byte " + std::to_string(summary_start) +
                            " does not match its CRC (corrupt)");
    }
  }
  struct ChunkIndex {
    std::uint64_t offset = 0, length = 0;
    std::map<std::uint16_t, std::uint64_t> message_indexes;
  };
  std::vector<ChunkIndex> chunks;
  std::optional<std::uint64_t> message_count;  // the Statistics record's, when there is one
  for (std::uint64_t at = 0; at < summary.size();) {
    const std::uint64_t abs = summary_start + at;
    if (summary.size() - at < kPrefixBytes)
      throw input_error(path_, 0, "a record at byte " + std::to_string(abs) + " is cut short");
    const auto op = static_cast<std::uint8_t>(summary[at]);
    const auto n = little<std::uint64_t>(summary.data() + at + 1);
    if (n > summary.size() - at - kPrefixBytes) {
      throw input_error(path_, 0, record_at(op, abs) + " runs past the summary section");
    }
    Fields r(summary.data() + at + kPrefixBytes, n, path_, record_at(op, abs));
    if (op == kSchema) {
      Schema s;
      s.id = r.num<std::uint16_t>("id");
      s.name = r.str("name"), s.encoding = r.str("encoding"), s.data = r.str("data");
      if (s.id != 0) schemas_.emplace(s.id, s);
    } else if (op == kChannel) {
      Channel c;
      c.id = r.num<std::uint16_t>("id"), c.schema_id = r.num<std::uint16_t>("schema_id");
      c.topic = r.str("topic"), c.message_encoding = r.str("message_encoding"),
      c.metadata = r.string_map("metadata");
      channels_.emplace(c.id, c);
    } else if (op == kChunkIndex) {
      ChunkIndex c;
      r.num<std::uint64_t>("message_start_time"), r.num<std::uint64_t>("message_end_time");
      c.offset = r.num<std::uint64_t>("chunk_start_offset"), c.length = r.num<std::uint64_t>("chunk_length");
      const auto [start, count] = r.fixed_entries(10, "message_index_offsets");
      for (std::uint64_t i = 0; i < count; ++i) {
        const char* e = summary.data() + at + kPrefixBytes + start + 10 * i;
        c.message_indexes[little<std::uint16_t>(e)] = little<std::uint64_t>(e + 2);
      }
      if (c.offset < kMagicBytes || c.length > summary_start || c.offset > summary_start - c.length) {
        throw input_error(path_, 0, record_at(op, abs) + ": its chunk is outside the data section");
      }
      chunks.push_back(std::move(c));
    } else if (op == kStatistics) {
      message_count = r.num<std::uint64_t>("message_count");
    }
    at += kPrefixBytes + n;
  }
  if (chunks.empty()) return false;  // unchunked (or empty): the messages are found by a scan
  for (const ChunkIndex& c : chunks) {
    if (c.message_indexes.empty()) {
      *why = "the chunk at byte " + std::to_string(c.offset) + " has no message index";
      return false;
    }
    for (const auto& [channel, offset] : c.message_indexes) {
      if (!channels_.count(channel)) {
        *why = "the summary lacks channel " + std::to_string(channel) + " of the chunk at byte " +
               std::to_string(c.offset);
        return false;
      }
      const auto [op, content] = f.record(offset, "the Message Index of channel " + std::to_string(channel));
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
        messages_.push_back({channel, little<std::uint64_t>(e), c.offset, little<std::uint64_t>(e + 8)});
      }
    }
  }
  // Messages outside chunks have no index: the statistics tell whether there are any.
  if (message_count && *message_count != messages_.size()) {
    *why = "its index holds " + std::to_string(messages_.size()) + " of the " +
           std::to_string(*message_count) + " messages its statistics count";
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
      Schema s;
      s.id = r.num<std::uint16_t>("id");
      s.name = r.str("name"), s.encoding = r.str("encoding"), s.data = r.str("data");
      if (s.id != 0) schemas_.emplace(s.id, s);
    } else {
      Channel c;
      c.id = r.num<std::uint16_t>("id"), c.schema_id = r.num<std::uint16_t>("schema_id");
      c.topic = r.str("topic"), c.message_encoding = r.str("message_encoding"),
      c.metadata = r.string_map("metadata");
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

// ---- writing -------------------------------------------------------------------------------

struct Writer::State {
  std::string path, tmp;
  WriterOptions options;
  std::ofstream out;
  std::uint64_t pos = 0;
  std::uint32_t data_crc = 0;
  bool finished = false;
  std::vector<std::string> schema_records, channel_records;  // for the summary
  std::map<std::uint16_t, std::uint32_t> sequences;
  std::map<std::uint16_t, std::uint64_t> channel_counts;
  std::uint64_t message_count = 0, start_time = 0, end_time = 0;
  std::uint32_t chunk_count = 0, metadata_count = 0;
  // The open chunk.
  std::string chunk;
  std::uint64_t chunk_start = 0, chunk_end = 0;
  bool chunk_has_messages = false;
  std::map<std::uint16_t, std::string> chunk_message_index;  // per channel: (log_time, offset) entries
  std::vector<std::string> chunk_indexes, metadata_indexes;

  void put(const std::string& bytes) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error(tmp + ": write failed (disk full?)");
    pos += bytes.size();
  }
  void put_data(const std::string& bytes) {
    data_crc = crc_of(bytes.data(), bytes.size(), data_crc);
    put(bytes);
  }
  void flush_chunk() {
    if (chunk.empty()) return;
    const std::string packed = compress(options.compression, chunk);
    std::string content;
    put_u64(content, chunk_has_messages ? chunk_start : 0),
        put_u64(content, chunk_has_messages ? chunk_end : 0);
    put_u64(content, chunk.size());
    put_u32(content, crc_of(chunk.data(), chunk.size()));
    put_str(content, compression_name(options.compression));
    put_u64(content, packed.size());
    content += packed;
    const std::uint64_t chunk_at = pos;
    const std::string chunk_record = record(kChunk, content);
    put_data(chunk_record);
    const std::uint64_t indexes_at = pos;
    std::string offsets;
    for (const auto& [channel, entries] : chunk_message_index) {
      put_u16(offsets, channel), put_u64(offsets, pos);
      std::string mi;
      put_u16(mi, channel);
      put_str(mi, entries);
      put_data(record(kMessageIndex, mi));
    }
    std::string ci;
    put_u64(ci, chunk_has_messages ? chunk_start : 0), put_u64(ci, chunk_has_messages ? chunk_end : 0);
    put_u64(ci, chunk_at), put_u64(ci, chunk_record.size());
    put_str(ci, offsets);
    put_u64(ci, pos - indexes_at);
    put_str(ci, compression_name(options.compression));
    put_u64(ci, packed.size()), put_u64(ci, chunk.size());
    chunk_indexes.push_back(record(kChunkIndex, ci));
    ++chunk_count;
    chunk.clear(), chunk_message_index.clear();
    chunk_has_messages = false;
  }
};

Writer::Writer(const std::string& path, WriterOptions options) : s_(std::make_unique<State>()) {
  s_->path = path;
  s_->tmp = path + ".tmp-" + std::to_string(::getpid());
  s_->options = std::move(options);
  s_->out.open(s_->tmp, std::ios::binary | std::ios::trunc);
  if (!s_->out) throw input_error(path, 0, "cannot create the file (no folder, or no permission?)");
  s_->put_data(std::string(kMagic, kMagicBytes));
  std::string header;
  put_str(header, s_->options.profile), put_str(header, s_->options.library);
  s_->put_data(record(kHeader, header));
}

Writer::~Writer() {
  if (!s_->finished) {
    s_->out.close();
    std::error_code ec;
    std::filesystem::remove(s_->tmp, ec);
  }
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding,
                                 const std::string& data) {
  const auto id = static_cast<std::uint16_t>(s_->schema_records.size() + 1);
  std::string c;
  put_u16(c, id), put_str(c, name), put_str(c, encoding), put_str(c, data);
  s_->schema_records.push_back(record(kSchema, c));
  s_->chunk += s_->schema_records.back();  // before any message that needs it
  return id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, const std::string& topic,
                                  const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  const auto id = static_cast<std::uint16_t>(s_->channel_records.size() + 1);
  std::string c;
  put_u16(c, id), put_u16(c, schema_id), put_str(c, topic), put_str(c, message_encoding),
      put_map(c, metadata);
  s_->channel_records.push_back(record(kChannel, c));
  s_->chunk += s_->channel_records.back();
  s_->channel_counts[id] = 0;
  return id;
}

void Writer::write(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time,
                   const std::string& data) {
  if (channel_id == 0 || channel_id > s_->channel_records.size())
    throw std::invalid_argument("mcap::Writer::write: no channel " + std::to_string(channel_id));
  State& s = *s_;
  std::string m;
  put_u16(m, channel_id), put_u32(m, s.sequences[channel_id]++), put_u64(m, log_time),
      put_u64(m, publish_time);
  m += data;
  std::string& index = s.chunk_message_index[channel_id];
  put_u64(index, log_time), put_u64(index, s.chunk.size());
  s.chunk += record(kMessage, m);
  s.chunk_start = s.chunk_has_messages ? std::min(s.chunk_start, log_time) : log_time;
  s.chunk_end = s.chunk_has_messages ? std::max(s.chunk_end, log_time) : log_time;
  s.chunk_has_messages = true;
  s.start_time = s.message_count ? std::min(s.start_time, log_time) : log_time;
  s.end_time = s.message_count ? std::max(s.end_time, log_time) : log_time;
  ++s.message_count;
  ++s.channel_counts[channel_id];
  if (s.chunk.size() >= s.options.chunk_size) s.flush_chunk();
}

void Writer::add_metadata(const std::string& name, const std::map<std::string, std::string>& metadata) {
  std::string c;
  put_str(c, name), put_map(c, metadata);
  const std::string r = record(kMetadata, c);
  std::string index;
  put_u64(index, s_->pos), put_u64(index, r.size()), put_str(index, name);
  s_->metadata_indexes.push_back(record(kMetadataIndex, index));
  s_->put_data(r);
  ++s_->metadata_count;
}

void Writer::finish() {
  State& s = *s_;
  s.flush_chunk();
  std::string data_end;
  put_u32(data_end, s.data_crc);
  s.put(record(kDataEnd, data_end));
  // Summary: each group of one opcode together, then where each group is.
  const std::uint64_t summary_start = s.pos;
  std::uint32_t crc = 0;
  std::string offsets;
  const auto group = [&](std::uint8_t op, const std::vector<std::string>& records) {
    if (records.empty()) return;
    const std::uint64_t start = s.pos;
    for (const std::string& r : records) {
      crc = crc_of(r.data(), r.size(), crc);
      s.put(r);
    }
    std::string o(1, static_cast<char>(op));
    put_u64(o, start), put_u64(o, s.pos - start);
    offsets += record(kSummaryOffset, o);
  };
  std::string stats;
  put_u64(stats, s.message_count);
  put_u16(stats, static_cast<std::uint16_t>(s.schema_records.size()));
  put_u32(stats, static_cast<std::uint32_t>(s.channel_records.size()));
  put_u32(stats, 0), put_u32(stats, s.metadata_count), put_u32(stats, s.chunk_count);
  put_u64(stats, s.start_time), put_u64(stats, s.end_time);
  std::string counts;
  for (const auto& [id, n] : s.channel_counts) put_u16(counts, id), put_u64(counts, n);
  put_str(stats, counts);
  group(kSchema, s.schema_records);
  group(kChannel, s.channel_records);
  group(kChunkIndex, s.chunk_indexes);
  group(kStatistics, {record(kStatistics, stats)});
  group(kMetadataIndex, s.metadata_indexes);
  const std::uint64_t offsets_start = s.pos;
  crc = crc_of(offsets.data(), offsets.size(), crc);
  s.put(offsets);
  std::string footer(1, static_cast<char>(kFooter));
  put_u64(footer, kFooterContentBytes), put_u64(footer, summary_start), put_u64(footer, offsets_start);
  put_u32(footer, crc_of(footer.data(), footer.size(), crc));
  s.put(footer);
  s.put(std::string(kMagic, kMagicBytes));
  s.out.close();
  if (!s.out) throw std::runtime_error(s.tmp + ": write failed (disk full?)");
  std::error_code ec;
  std::filesystem::rename(s.tmp, s.path, ec);
  if (ec) throw input_error(s.path, 0, "cannot rename into place: " + ec.message());
  s.finished = true;
}

}  // namespace tsgraphs::io::mcap
