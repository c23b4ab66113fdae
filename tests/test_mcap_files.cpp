// MCAP files (mcap/mcap.hpp): written and read back in each compression, files built here byte
// by byte from the specification (mcap.dev/spec) in the layouts of its conformance suite
// (chunked or not, with or without chunk and message indexes, padded records, summaries with
// repeated schemas and channels, statistics and summary offsets), and damaged files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/mcap/mcap.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

class Mcap : public test::TempDirTest {
 protected:
  std::string write_bytes(const std::string& name, const std::string& bytes) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  static std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  static std::string error_of(const std::string& path) {
    try {
      mcap::Reader r(path);
      for (const mcap::MessageRef& m : r.messages()) r.read(m);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

// What the writer is given: messages on two channels, times out of order and repeated.
struct Written {
  std::uint16_t channel;
  std::uint64_t log_time;
  std::string data;
};

std::vector<Written> some_messages() {
  std::vector<Written> out;
  for (int i = 0; i < 300; ++i) {
    const std::uint16_t channel = i % 3 == 0 ? 2 : 1;
    const std::uint64_t t = 1000000000ull + static_cast<std::uint64_t>((i * 7919) % 250) * 1000;  // repeats
    out.push_back(
        {channel, t,
         std::string(static_cast<std::size_t>(17 + (i * 31) % 900), static_cast<char>('a' + i % 26))});
  }
  return out;
}

// ---- a file written by hand, after the specification ---------------------------------------

// CRC-32 (IEEE 802.3, reflected, as zlib's), bit by bit: independent of the reader's.
std::uint32_t crc32_of(const std::string& bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const char c : bytes) {
    crc ^= static_cast<std::uint8_t>(c);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void u16(std::string& s, std::uint16_t v) { s.append({static_cast<char>(v), static_cast<char>(v >> 8)}); }
void u32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>(v >> (8 * i)));
}
void u64(std::string& s, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) s.push_back(static_cast<char>(v >> (8 * i)));
}
void str(std::string& s, const std::string& v) {
  u32(s, static_cast<std::uint32_t>(v.size()));
  s += v;
}
const std::string kMagic("\x89MCAP0\r\n", 8);

struct Layout {
  bool chunked = false, chunk_index = false, message_index = false, padded = false;
  bool repeated = false;  // schemas and channels repeated in the summary
  bool statistics = false, summary_offsets = false;
  std::string name() const {
    std::string n = "OneMessage";
    for (const auto& [on, tag] : std::vector<std::pair<bool, const char*>>{{chunked, "ch"},
                                                                           {chunk_index, "chx"},
                                                                           {message_index, "mx"},
                                                                           {padded, "pad"},
                                                                           {repeated, "rch-rsh"},
                                                                           {statistics, "st"},
                                                                           {summary_offsets, "sum"}})
      if (on) n += std::string("-") + tag;
    return n;
  }
};

// The conformance suite's OneMessage: schema 1 "Example" (encoding "c", data 4 5 6), channel 1
// "example" (encoding "a", metadata foo: bar), one message (sequence 10, log time 2, publish
// time 1, data 1 2 3). Padded records carry bytes after their fields, which readers skip.
std::string one_message(const Layout& l) {
  const std::string pad = l.padded ? std::string("\x01\x02\x03\x04", 4) : "";
  const auto rec = [&](std::uint8_t op, std::string content) {
    content += pad;
    std::string r(1, static_cast<char>(op));
    u64(r, content.size());
    return r + content;
  };
  std::string schema, channel, message, meta;
  u16(schema, 1), str(schema, "Example"), str(schema, "c"), str(schema, std::string("\x04\x05\x06", 3));
  str(meta, "foo"), str(meta, "bar");
  u16(channel, 1), u16(channel, 1), str(channel, "example"), str(channel, "a"), str(channel, meta);
  u16(message, 1), u32(message, 10), u64(message, 2), u64(message, 1),
      message += std::string("\x01\x02\x03", 3);
  // Message is not extended by padding (its data runs to the record's end).
  const std::string schema_r = rec(0x03, schema), channel_r = rec(0x04, channel);
  std::string message_r(1, '\x05');
  u64(message_r, message.size());
  message_r += message;

  std::string header;
  str(header, ""), str(header, "");
  std::string file = kMagic + rec(0x01, header);
  std::string chunk_index;
  if (l.chunked) {
    const std::string records = schema_r + channel_r + message_r;
    std::string c;
    u64(c, 2), u64(c, 2), u64(c, records.size()), u32(c, crc32_of(records));
    str(c, ""), u64(c, records.size()), c += records;
    const std::uint64_t chunk_at = file.size();
    const std::string chunk_r = rec(0x06, c);
    file += chunk_r;
    std::string offsets;
    const std::uint64_t index_at = file.size();
    if (l.message_index) {
      std::string mi, entries;
      u64(entries, 2), u64(entries, schema_r.size() + channel_r.size());
      u16(mi, 1), str(mi, entries);
      u16(offsets, 1), u64(offsets, file.size());
      file += rec(0x07, mi);
    }
    std::string ci;
    u64(ci, 2), u64(ci, 2), u64(ci, chunk_at), u64(ci, chunk_r.size()), str(ci, offsets),
        u64(ci, file.size() - index_at);
    str(ci, ""), u64(ci, records.size()), u64(ci, records.size());
    chunk_index = rec(0x08, ci);
  } else {
    file += schema_r + channel_r + message_r;
  }
  std::string data_end;
  u32(data_end, 0);
  file += rec(0x0F, data_end);
  const std::uint64_t summary_start = file.size();
  std::string offsets;
  const auto group = [&](std::uint8_t op, const std::string& records) {
    if (records.empty()) return;
    std::string o(1, static_cast<char>(op));
    u64(o, file.size()), u64(o, records.size());
    file += records;
    offsets += rec(0x0E, o);
  };
  if (l.repeated) group(0x03, schema_r), group(0x04, channel_r);
  if (l.chunk_index) group(0x08, chunk_index);
  if (l.statistics) {
    std::string st, counts;
    u16(counts, 1), u64(counts, 1);
    u64(st, 1), u16(st, 1), u32(st, 1), u32(st, 0), u32(st, 0), u32(st, l.chunked ? 1 : 0), u64(st, 2),
        u64(st, 2);
    str(st, counts);
    group(0x0B, rec(0x0B, st));
  }
  const bool has_summary = file.size() > summary_start;
  const std::uint64_t offsets_start = file.size();
  if (l.summary_offsets && has_summary) file += offsets;
  std::string footer;
  u64(footer, has_summary ? summary_start : 0),
      u64(footer, l.summary_offsets && has_summary ? offsets_start : 0), u32(footer, 0);
  std::string footer_r(1, '\x02');
  u64(footer_r, footer.size());
  return file + footer_r + footer + kMagic;
}

}  // namespace

TEST_F(Mcap, EveryCompressionReadsBackWhatWasWritten) {
  const std::vector<Written> written = some_messages();
  for (const mcap::Compression c :
       {mcap::Compression::none, mcap::Compression::lz4, mcap::Compression::zstd}) {
    SCOPED_TRACE(mcap::compression_name(c));
    const std::string path = (dir_ / "out.mcap").string();
    {
      mcap::Writer w(path, {"ros2", "tsgraphs-test", c, 4096});  // many chunks
      const auto schema = w.add_schema("pkg/msg/A", "ros2msg", "int32 a\n");
      ASSERT_EQ(w.add_channel(schema, "/a", "cdr", {{"offered_qos_profiles", ""}}), 1);
      ASSERT_EQ(w.add_channel(schema, "/b", "cdr"), 2);
      for (const Written& m : written) w.write(m.channel, m.log_time, m.log_time + 5, m.data);
      w.add_metadata("rosbag2", {{"serialized_metadata", "x"}});
      w.finish();
    }
    const mcap::Reader r(path);
    EXPECT_TRUE(r.indexed());
    EXPECT_TRUE(r.warnings().empty());
    EXPECT_EQ(r.profile(), "ros2");
    ASSERT_EQ(r.schemas().size(), 1u);
    EXPECT_EQ(r.schemas().at(1).name, "pkg/msg/A");
    EXPECT_EQ(r.schemas().at(1).data, "int32 a\n");
    ASSERT_EQ(r.channels().size(), 2u);
    EXPECT_EQ(r.channels().at(2).topic, "/b");
    EXPECT_EQ(r.channels().at(1).metadata.at("offered_qos_profiles"), "");
    ASSERT_EQ(r.messages().size(), written.size());
    // By log time, and in the order written among equal times.
    std::vector<std::size_t> order(written.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return written[a].log_time < written[b].log_time; });
    std::size_t k = 0;
    r.read_each(r.messages(), [&](const mcap::MessageRef& ref, const mcap::Message& m) {
      const Written& w = written[order[k++]];
      EXPECT_EQ(ref.channel_id, w.channel);
      EXPECT_EQ(m.channel_id, w.channel);
      EXPECT_EQ(m.log_time, w.log_time);
      EXPECT_EQ(m.publish_time, w.log_time + 5);
      EXPECT_EQ(m.data, w.data);
    });
    EXPECT_EQ(k, written.size());
    EXPECT_EQ(r.read(r.messages().back()).data, written[order.back()].data);
  }
}

TEST_F(Mcap, ASummaryCutOffIsReadFromTheStart) {
  const std::string path = (dir_ / "whole.mcap").string();
  {
    mcap::Writer w(path, {"", "t", mcap::Compression::zstd, 2048});
    w.add_channel(0, "/x", "raw");
    for (int i = 0; i < 50; ++i) w.write(1, 100 + i, 100 + i, std::string(100, static_cast<char>(i)));
    w.finish();
  }
  const std::string bytes = read_bytes(path);
  const mcap::Reader whole(path);
  ASSERT_TRUE(whole.indexed());
  // Cut inside the summary: the Data End record is whole, the footer is gone.
  const std::size_t data_end = bytes.find(std::string("\x0f\x04\x00\x00\x00\x00\x00\x00\x00", 9));
  ASSERT_NE(data_end, std::string::npos);
  for (const std::size_t cut : {data_end + 13, data_end + 40, bytes.size() - 10}) {
    const mcap::Reader r(write_bytes("cut.mcap", bytes.substr(0, cut)));
    EXPECT_FALSE(r.indexed());
    ASSERT_EQ(r.warnings().size(), 1u);
    EXPECT_THAT(r.warnings()[0], HasSubstr("does not end in an MCAP footer"));
    ASSERT_EQ(r.messages().size(), 50u);
    for (std::size_t i = 0; i < 50; ++i)
      EXPECT_EQ(r.read(r.messages()[i]).data, whole.read(whole.messages()[i]).data);
  }
}

TEST_F(Mcap, TheSpecificationsOneMessageInEveryLayout) {
  int layouts = 0;
  for (int bits = 0; bits < 128; ++bits) {
    Layout l;
    l.chunked = bits & 1, l.chunk_index = bits & 2, l.message_index = bits & 4, l.padded = bits & 8;
    l.repeated = bits & 16, l.statistics = bits & 32, l.summary_offsets = bits & 64;
    if (!l.chunked && (l.chunk_index || l.message_index)) continue;
    ++layouts;
    SCOPED_TRACE(l.name());
    const mcap::Reader r(write_bytes(l.name() + ".mcap", one_message(l)));
    // The index is used when it is whole: chunk and message indexes, and the channels in the summary.
    EXPECT_EQ(r.indexed(), l.chunk_index && l.message_index && l.repeated);
    ASSERT_EQ(r.schemas().size(), 1u);
    EXPECT_EQ(r.schemas().at(1).name, "Example");
    EXPECT_EQ(r.schemas().at(1).encoding, "c");
    EXPECT_EQ(r.schemas().at(1).data, std::string("\x04\x05\x06", 3));
    ASSERT_EQ(r.channels().size(), 1u);
    EXPECT_EQ(r.channels().at(1).topic, "example");
    EXPECT_EQ(r.channels().at(1).message_encoding, "a");
    EXPECT_EQ(r.channels().at(1).metadata, (std::map<std::string, std::string>{{"foo", "bar"}}));
    ASSERT_EQ(r.messages().size(), 1u);
    const mcap::Message m = r.read(r.messages()[0]);
    EXPECT_EQ(m.channel_id, 1);
    EXPECT_EQ(m.sequence, 10u);
    EXPECT_EQ(m.log_time, 2u);
    EXPECT_EQ(m.publish_time, 1u);
    EXPECT_EQ(m.data, std::string("\x01\x02\x03", 3));
  }
  EXPECT_EQ(layouts, 80);
}

// Messages outside chunks have no index entry: when the statistics count more messages than
// the index holds, the file is read from the start instead.
TEST_F(Mcap, AnIndexShortOfTheStatisticsCountIsNotUsed) {
  Layout l;
  l.chunked = l.chunk_index = l.message_index = l.repeated = l.statistics = true;
  std::string bytes = one_message(l);
  const std::size_t stats =
      bytes.find(std::string("\x0b", 1) + std::string("\x38\x00\x00\x00\x00\x00\x00\x00", 8));
  ASSERT_NE(stats, std::string::npos);
  bytes[stats + 9] = '\x02';  // message_count 2
  const mcap::Reader r(write_bytes("short_index.mcap", bytes));
  EXPECT_FALSE(r.indexed());
  ASSERT_EQ(r.warnings().size(), 1u);
  EXPECT_THAT(r.warnings()[0], HasSubstr("its index holds 1 of the 2 messages its statistics count"));
  EXPECT_EQ(r.messages().size(), 1u);
}

TEST_F(Mcap, DamagedFilesAreInputErrorsNamingTheFileAndTheRecord) {
  const std::string path = (dir_ / "good.mcap").string();
  {
    mcap::Writer w(path, {"", "t", mcap::Compression::none, 1024});
    w.add_channel(0, "/x", "raw");
    for (int i = 0; i < 20; ++i) w.write(1, i, i, std::string(200, 'm'));
    w.finish();
  }
  const std::string good = read_bytes(path);
  ASSERT_EQ(error_of(path), "");
  const auto damaged = [&](const std::string& name, std::string bytes) {
    return write_bytes(name, std::move(bytes));
  };
  // Cut inside the data section.
  const std::string cut = damaged("cut.mcap", good.substr(0, good.size() / 2));
  EXPECT_THAT(error_of(cut),
              AllOf(StartsWith(cut + ": "), HasSubstr("past the end of the file"), HasSubstr("cut short")));
  // A byte of a chunk's records changed: its CRC (read through the index, and by a scan).
  std::string flipped = good;
  flipped[good.find(std::string(200, 'm')) + 10] = 'x';
  const std::string crc = damaged("crc.mcap", flipped);
  EXPECT_THAT(error_of(crc),
              AllOf(StartsWith(crc + ": Chunk record at byte "), HasSubstr("do not match their CRC")));
  const std::string crc_cut = damaged("crc_cut.mcap", flipped.substr(0, flipped.size() - 20));
  EXPECT_THAT(error_of(crc_cut), HasSubstr("do not match their CRC"));
  // The summary changed: its CRC.
  std::string summary = good;
  summary[good.size() - 60] ^= 1;
  const std::string sum = damaged("summary.mcap", summary);
  EXPECT_THAT(error_of(sum), HasSubstr("does not match its CRC"));
  // No magic; a folder; a missing file.
  const std::string text = damaged("text.mcap", "hello, this is no MCAP file at all");
  EXPECT_EQ(error_of(text), text + ": not an MCAP file (no MCAP magic at its start)");
  EXPECT_THAT(error_of(dir_.string()), StartsWith(dir_.string() + ": is a folder"));
  EXPECT_THAT(error_of((dir_ / "none.mcap").string()), HasSubstr("cannot open file"));
  // A chunk claiming 2^40 uncompressed bytes.
  std::string huge = good;
  const std::size_t chunk_at = good.find('\x06', 8 + 9 + 8);  // the first Chunk record after the Header
  ASSERT_EQ(good[chunk_at], '\x06');
  for (int i = 0; i < 8; ++i) huge[chunk_at + 9 + 16 + i] = i == 5 ? '\x01' : '\0';
  const std::string big = damaged("big.mcap", huge);
  EXPECT_THAT(error_of(big), HasSubstr("uncompressed size 1099511627776 is beyond"));
}

// Found by fuzzing (issue 19): a chunk claiming 512 MiB was given a zero-filled buffer of that
// size before its data was found wanting (seconds, and a 10 s timeout under ASan). Output now
// grows with what the data decompresses to.
TEST_F(Mcap, AChunkClaimingMoreThanItsDataHoldsIsRefusedAsItDecompresses) {
  for (const mcap::Compression c :
       {mcap::Compression::none, mcap::Compression::zstd, mcap::Compression::lz4}) {
    SCOPED_TRACE(mcap::compression_name(c));
    const std::string path = (dir_ / "claim.mcap").string();
    {
      mcap::Writer w(path, {"", "t", c, 1 << 20});
      w.add_channel(0, "/x", "raw");
      w.write(1, 1, 1, std::string(300, 'q'));
      w.finish();
    }
    std::string bytes = read_bytes(path);
    const std::size_t chunk_at = 8 + 9 + 9;  // after the magic and the Header ("" and "t")
    ASSERT_EQ(bytes[chunk_at], '\x06');
    const std::uint64_t claim = 512ull << 20;
    for (int i = 0; i < 8; ++i) bytes[chunk_at + 9 + 16 + i] = static_cast<char>(claim >> (8 * i));
    const std::string damaged = write_bytes("claim_damaged.mcap", bytes);
    EXPECT_THAT(error_of(damaged),
                AllOf(StartsWith(damaged + ": Chunk record at byte 26: "), HasSubstr("536870912")));
  }
}

TEST_F(Mcap, AWriterDestroyedUnfinishedLeavesNothing) {
  const fs::path path = dir_ / "half.mcap";
  {
    mcap::Writer w(path.string(), {});
    w.add_channel(0, "/x", "raw");
    w.write(1, 1, 1, "abc");
  }
  EXPECT_TRUE(fs::is_empty(dir_));
  EXPECT_THROW(mcap::Writer((dir_ / "no" / "such" / "folder.mcap").string(), {}), InputError);
}
