// MCAP files written: chunks, message indexes, the summary and every CRC.
#include "tsgraphs/mcap/mcap.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/mcap/compression.hpp"
#include "tsgraphs/mcap/mcap_internal.hpp"

namespace tsgraphs::mcap {

using namespace internal;

namespace {

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

}  // namespace tsgraphs::mcap
