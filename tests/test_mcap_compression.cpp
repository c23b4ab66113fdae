// Compressed bytes (mcap/compression.hpp): zstd and lz4 round trips in memory and as files, and
// data that is cut, claims more than allowed, or is not compressed at all, each an InputError
// naming the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zstd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "test_support.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/mcap/compression.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

/// 3 MB that compress well but not to nothing: more than zstd's and lz4's block sizes.
std::string sample() {
  std::string s;
  for (int i = 0; s.size() < 3'000'000; ++i)
    s += "scan " + std::to_string(i % 977) + " point " + std::to_string(i) + "\n";
  s.resize(3'000'000);
  return s;
}

class Compression : public test::TempDirTest {};

}  // namespace

TEST_F(Compression, RoundTripsInMemory) {
  const std::string s = sample();
  const std::string z = mcap::compress_zstd(s, 1), l = mcap::compress_lz4(s);
  EXPECT_LT(z.size(), s.size() / 4);
  EXPECT_LT(l.size(), s.size() / 2);
  EXPECT_EQ(mcap::decompress("zstd", z.data(), z.size(), s.size(), "f", "chunk"), s);
  EXPECT_EQ(mcap::decompress("lz4", l.data(), l.size(), s.size(), "f", "chunk"), s);
  EXPECT_EQ(mcap::decompress("", s.data(), s.size(), s.size(), "f", "chunk"), s);
  EXPECT_EQ(mcap::decompress_zstd(z.data(), z.size(), s.size(), "f", "message"), s);
  EXPECT_EQ(mcap::decompress_zstd(z.data(), 0, s.size(), "f", "message"), "");
  // Two frames end to end, and frames with a content checksum (4 bytes after the last block
  // that hold no output: read with the output already full).
  EXPECT_EQ(mcap::decompress_zstd((z + z).data(), 2 * z.size(), 2 * s.size(), "f", "message"), s + s);
  std::string c(ZSTD_compressBound(s.size()), '\0');
  const std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> ctx(ZSTD_createCCtx(), ZSTD_freeCCtx);
  ZSTD_CCtx_setParameter(ctx.get(), ZSTD_c_checksumFlag, 1);
  c.resize(ZSTD_compress2(ctx.get(), c.data(), c.size(), s.data(), s.size()));
  EXPECT_EQ(mcap::decompress("zstd", c.data(), c.size(), s.size(), "f", "chunk"), s);
  EXPECT_EQ(mcap::decompress_zstd(c.data(), c.size(), s.size(), "f", "message"), s);
}

TEST_F(Compression, DataCutShortOrLargerThanAllowedIsNamed) {
  const std::string s = sample();
  const std::string z = mcap::compress_zstd(s, 1), l = mcap::compress_lz4(s);
  // A size word one byte short or long, data cut in half: the file and the place, with the size.
  EXPECT_THAT(
      test::input_error_of([&] {
        mcap::decompress("zstd", z.data(), z.size(), s.size() - 1, "f.mcap", "Chunk record at byte 9");
      }),
      StartsWith("f.mcap: Chunk record at byte 9: zstd data does not decompress to its 2999999 bytes"));
  EXPECT_THAT(test::input_error_of(
                  [&] { mcap::decompress("zstd", z.data(), z.size(), s.size() + 1, "f.mcap", "chunk"); }),
              HasSubstr("does not decompress to its 3000001 bytes"));
  EXPECT_THAT(test::input_error_of(
                  [&] { mcap::decompress("zstd", z.data(), z.size() / 2, s.size(), "f.mcap", "chunk"); }),
              HasSubstr("(the data ends inside a frame)"));
  EXPECT_THAT(test::input_error_of(
                  [&] { mcap::decompress("lz4", l.data(), l.size() / 2, s.size(), "f.mcap", "chunk"); }),
              HasSubstr("(the data ends inside a frame)"));
  EXPECT_THAT(test::input_error_of(
                  [&] { mcap::decompress("", s.data(), s.size(), s.size() + 1, "f.mcap", "chunk"); }),
              HasSubstr("uncompressed records of 3000000 bytes, its size field says 3000001"));
  EXPECT_THAT(
      test::input_error_of([&] { mcap::decompress("bz2", s.data(), s.size(), s.size(), "f.mcap", "chunk"); }),
      HasSubstr("unknown compression 'bz2'"));
  EXPECT_EQ(test::input_error_of(
                [&] { mcap::decompress_zstd(z.data(), z.size(), 1000, "bag_0.db3", "the message"); }),
            "bag_0.db3: the message: zstd data that does not decompress (more than 1000 bytes)");
  EXPECT_THAT(test::input_error_of(
                  [&] { mcap::decompress_zstd(s.data(), 100, s.size(), "bag_0.db3", "the message"); }),
              StartsWith("bag_0.db3: the message: zstd data that does not decompress ("));
}

TEST_F(Compression, FilesRoundTripAndDamagedOnesAreNamed) {
  const std::string s = sample();
  const fs::path raw = dir_ / "bag_0.db3", packed = dir_ / "bag_0.db3.zstd", back = dir_ / "back.db3";
  std::ofstream(raw, std::ios::binary) << s;
  mcap::compress_zstd_file(raw.string(), packed.string(), 1);
  EXPECT_LT(fs::file_size(packed), s.size() / 4);
  mcap::decompress_zstd_file(packed.string(), back.string());
  EXPECT_EQ(test::read_file(back), s);
  // The streamed file is an ordinary zstd frame: decompressed in memory too.
  const std::string z = test::read_file(packed);
  EXPECT_EQ(mcap::decompress_zstd(z.data(), z.size(), s.size(), "f", "file"), s);

  fs::resize_file(packed, fs::file_size(packed) / 2);
  EXPECT_EQ(test::input_error_of([&] { mcap::decompress_zstd_file(packed.string(), back.string()); }),
            packed.string() + ": zstd data that ends inside a frame (cut off?)");
  EXPECT_THAT(test::input_error_of([&] { mcap::decompress_zstd_file(raw.string(), back.string()); }),
              StartsWith(raw.string() + ": zstd data that does not decompress near byte "));
  std::ofstream(dir_ / "empty.zstd");
  EXPECT_EQ(test::input_error_of(
                [&] { mcap::decompress_zstd_file((dir_ / "empty.zstd").string(), back.string()); }),
            (dir_ / "empty.zstd").string() + ": an empty file, not zstd data");
  EXPECT_EQ(
      test::input_error_of([&] { mcap::decompress_zstd_file((dir_ / "none.zstd").string(), back.string()); }),
      (dir_ / "none.zstd").string() + ": cannot open file");
}
