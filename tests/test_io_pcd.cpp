// PCD reading: the real HDL-32 scans against an independent parse, NaN points dropped, and
// errors naming the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/io/pcd.hpp"

#include "test_support.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using tsgraphs::test::input_error_of;
using tsgraphs::test::read_file;
using tsgraphs::test::TempDirTest;

namespace {

const std::string kDataDir = std::string(TSGRAPHS_TEST_DATA_DIR) + "/hdl32_pair";

std::uint32_t bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// A minimal reader for exactly the layout of the test scans ("x y z intensity", 4 float32,
// DATA binary), written independently of PCL to check read_pcd against.
std::vector<std::array<float, 4>> parse_binary_xyzi(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t points = 0;
  bool data = false;
  while (std::getline(in, line)) {
    if (line.rfind("FIELDS", 0) == 0) {
      EXPECT_EQ(line, "FIELDS x y z intensity");
    }
    if (line.rfind("SIZE", 0) == 0) {
      EXPECT_EQ(line, "SIZE 4 4 4 4");
    }
    if (line.rfind("TYPE", 0) == 0) {
      EXPECT_EQ(line, "TYPE F F F F");
    }
    if (line.rfind("POINTS", 0) == 0) points = std::stoul(line.substr(7));
    if (line.rfind("DATA", 0) == 0) {
      EXPECT_EQ(line, "DATA binary");
      data = true;
      break;
    }
  }
  EXPECT_TRUE(data);
  std::vector<std::array<float, 4>> out(points);
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(points * 16));
  EXPECT_EQ(static_cast<std::size_t>(in.gcount()), points * 16);
  return out;
}

std::string header(const std::string& fields, const std::string& size, const std::string& type,
                   const std::string& count, unsigned long long width, unsigned long long height,
                   const std::string& data) {
  std::ostringstream s;
  s << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " << fields << "\nSIZE " << size
    << "\nTYPE " << type << "\nCOUNT " << count << "\nWIDTH " << width << "\nHEIGHT " << height
    << "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << width * height << "\nDATA " << data << "\n";
  return s.str();
}

// The message of the InputError that reading the PCD file at `path` raises.
std::string read_error(const std::string& path) {
  SCOPED_TRACE("reading " + path);
  return input_error_of([&] { read_pcd(path); });
}

using Pcd = TempDirTest;

}  // namespace

TEST(PcdRealScans, MatchAnIndependentParse) {
  for (const char* name : {"251370668.pcd", "251371071.pcd"}) {
    SCOPED_TRACE(name);
    const std::string path = kDataDir + "/" + name;
    const PointCloud cloud = read_pcd(path);
    EXPECT_GT(cloud.size(), 10000u);
    ASSERT_TRUE(cloud.has_intensity());
    ASSERT_EQ(cloud.intensity.size(), cloud.size());
    EXPECT_FALSE(cloud.has_labels());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      ASSERT_TRUE(cloud.points[i].allFinite()) << i;
      ASSERT_TRUE(std::isfinite(cloud.intensity[i])) << i;
    }
    // The files hold no NaN points: every point is read, bit for bit, in file order.
    const auto raw = parse_binary_xyzi(path);
    ASSERT_EQ(cloud.size(), raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
      for (int k = 0; k < 3; ++k) ASSERT_EQ(bits(cloud.points[i][k]), bits(raw[i][k])) << i;
      ASSERT_EQ(bits(cloud.intensity[i]), bits(raw[i][3])) << i;
    }
  }
  EXPECT_EQ(read_pcd(kDataDir + "/251370668.pcd").size(), 69088u);
  EXPECT_EQ(read_pcd(kDataDir + "/251371071.pcd").size(), 69792u);
}

TEST(PcdRealScans, LookLikeAnHdl32Scan) {
  const PointCloud cloud = read_pcd(kDataDir + "/251370668.pcd");
  double max_range = 0.0, min_z = 1e9, max_z = -1e9;
  for (const auto& p : cloud.points) {
    max_range = std::max(max_range, static_cast<double>(p.head<2>().norm()));
    min_z = std::min(min_z, static_cast<double>(p.z()));
    max_z = std::max(max_z, static_cast<double>(p.z()));
  }
  EXPECT_GT(max_range, 20.0);   // an outdoor campus scan reaches tens of metres
  EXPECT_LT(max_range, 120.0);  // HDL-32E range is about 100 m
  EXPECT_LT(min_z, -1.0);       // the ground below the sensor
  EXPECT_GT(max_z, min_z + 2.0);
}

TEST_F(Pcd, MissingFileNamesTheFile) {
  const std::string path = (dir_ / "nope.pcd").string();
  EXPECT_THAT(read_error(path), StartsWith(path + ":"));
  EXPECT_THAT(read_error(dir_.string()), StartsWith(dir_.string() + ":"));  // a folder
}

TEST_F(Pcd, TextFileThatIsNotAPcdNamesTheFile) {
  const std::string path = write_file("notes.pcd", "this is not a point cloud\njust some text\n");
  EXPECT_THAT(read_error(path), StartsWith(path + ":"));
  const std::string empty = write_file("empty.pcd", "");
  EXPECT_THAT(read_error(empty), StartsWith(empty + ":"));
}

TEST_F(Pcd, TruncatedBinaryFileNamesTheFile) {
  std::string content = header("x y z", "4 4 4", "F F F", "1 1 1", 100, 1, "binary");
  content += std::string(5 * 12, '\0');  // 5 of 100 points
  const std::string path = write_file("short.pcd", content);
  EXPECT_THAT(read_error(path), StartsWith(path + ":"));
}

TEST_F(Pcd, AsciiWithNaNPointsDropsThem) {
  const std::string path =
      write_file("nan.pcd", header("x y z intensity", "4 4 4 4", "F F F F", "1 1 1 1", 5, 1, "ascii") +
                                "1 2 3 10\n"
                                "nan nan nan 0\n"
                                "4.5 -5 6 20\n"
                                "7 8 nan 30\n"
                                "-1 -2 -3 nan\n");
  const PointCloud cloud = read_pcd(path);
  ASSERT_EQ(cloud.size(), 3u);
  ASSERT_TRUE(cloud.has_intensity());
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(cloud.intensity[0], 10.0f);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4.5f, -5, 6));
  EXPECT_EQ(cloud.intensity[1], 20.0f);
  EXPECT_EQ(cloud.points[2], Eigen::Vector3f(-1, -2, -3));
  EXPECT_EQ(cloud.intensity[2], 0.0f);  // a point with a NaN intensity is kept, its intensity 0
}

TEST_F(Pcd, OrganisedBinaryCloudWithNaNs) {
  std::string content = header("x y z", "4 4 4", "F F F", "1 1 1", 2, 2, "binary");
  const float nan = std::nanf("");
  const float values[12] = {1, 1, 1, nan, nan, nan, 2, 2, 2, 3, nan, 3};
  content.append(reinterpret_cast<const char*>(values), sizeof values);
  const PointCloud cloud = read_pcd(write_file("organised.pcd", content));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_FALSE(cloud.has_intensity());
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1, 1, 1));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(2, 2, 2));
}

TEST_F(Pcd, XyzOnlyHasNoIntensity) {
  const PointCloud cloud = read_pcd(write_file(
      "xyz.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "ascii") + "0.5 0.25 -8\n100 200 300\n"));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_FALSE(cloud.has_intensity());
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(0.5f, 0.25f, -8.0f));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(100, 200, 300));
}

TEST_F(Pcd, ExtraFieldsAreIgnored) {
  const PointCloud cloud =
      read_pcd(write_file("rich.pcd", header("x y z intensity ring time", "4 4 4 4 2 4", "F F F F U F",
                                             "1 1 1 1 1 1", 2, 1, "ascii") +
                                          "1 2 3 40 7 0.01\n4 5 6 50 8 0.02\n"));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4, 5, 6));
  ASSERT_TRUE(cloud.has_intensity());
  EXPECT_EQ(cloud.intensity[1], 50.0f);
}

TEST_F(Pcd, NoCoordinatesIsAnInputError) {
  const std::string path =
      write_file("noxyz.pcd", header("a b c", "4 4 4", "F F F", "1 1 1", 1, 1, "ascii") + "1 2 3\n");
  EXPECT_THAT(read_error(path), StartsWith(path + ":"));
}

// A file with x but no y and z must not be read as points on the x axis. read_pcd only checks
// for "x", and PCL fills the missing y and z with 0.
TEST_F(Pcd, OnlySomeCoordinatesIsAnInputError) {
  const std::string path =
      write_file("xonly.pcd", header("x intensity", "4 4", "F F", "1 1", 2, 1, "ascii") + "1 5\n2 6\n");
  EXPECT_THAT(read_error(path), StartsWith(path + ":"));
}

// Double-precision coordinates (TYPE F, SIZE 8) are valid PCD, written e.g. by georeferenced
// map exports; they must read as their values. pcl::fromPCLPointCloud2 matches fields by name
// AND datatype, finds no float32 x y z and leaves every point at (0, 0, 0), silently.
TEST_F(Pcd, DoublePrecisionCoordinates) {
  const std::string path = write_file(
      "double.pcd", header("x y z", "8 8 8", "F F F", "1 1 1", 2, 1, "ascii") + "1.5 2.5 3.5\n-4 5 6\n");
  const PointCloud cloud = read_pcd(path);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1.5f, 2.5f, 3.5f));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(-4, 5, 6));
}

// Integer intensities (TYPE U, as some drivers write them) must keep their values; for the
// same reason as above they all read as 0.
TEST_F(Pcd, IntegerIntensity) {
  const std::string path = write_file(
      "uint_intensity.pcd",
      header("x y z intensity", "4 4 4 2", "F F F U", "1 1 1 1", 2, 1, "ascii") + "1 2 3 40\n4 5 6 300\n");
  const PointCloud cloud = read_pcd(path);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4, 5, 6));
  ASSERT_TRUE(cloud.has_intensity());
  EXPECT_EQ(cloud.intensity[0], 40.0f);
  EXPECT_EQ(cloud.intensity[1], 300.0f);
}

TEST_F(Pcd, ShortOrTruncatedFilesNameTheFile) {
  const std::string ascii =
      write_file("short.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 5, 1, "ascii") + "1 2 3\n4 5 6\n");
  EXPECT_THAT(read_error(ascii), StartsWith(ascii + ":"));
  std::string compressed = header("x y z", "4 4 4", "F F F", "1 1 1", 100, 1, "binary_compressed");
  compressed += std::string(
      "\x10\x00\x00\x00\xb0\x04\x00\x00"
      "abcd",
      12);
  const std::string path = write_file("compressed.pcd", compressed);
  EXPECT_THAT(read_error(path), StartsWith(path + ":"));
}

// Issue 52: a binary body longer than POINTS was cut silently where its ASCII twin is refused.
TEST_F(Pcd, BinaryBodyLongerThanPointsIsRefusedAsItsAsciiTwinIs) {
  const std::string head = header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "binary");
  const std::string two_points(2 * 12, '\0');
  ASSERT_EQ(read_pcd(write_file("exact.pcd", head + two_points)).size(), 2u);
  const std::string path = write_file("long.pcd", head + two_points + std::string(12, '\0'));
  EXPECT_EQ(read_error(path),
            path + ": PCD body has more points than POINTS (2): 12 bytes after the last point, from byte " +
                std::to_string(head.size() + two_points.size()));
  const std::string one = write_file("one_byte.pcd", head + two_points + "\n");
  EXPECT_THAT(read_error(one), HasSubstr(": 1 bytes after the last point, from byte "));
}

// Issue 52: a header line of binary bytes was quoted raw. Text from a file reaches a message
// printable (other bytes as \xNN) and cut to 40 bytes.
TEST_F(Pcd, MessagesQuoteNoRawBytes) {
  const auto is_printable = [](const std::string& s) {
    return std::all_of(s.begin(), s.end(), [](char c) { return c >= 0x20 && c <= 0x7e; });
  };
  std::string binary = "VERSION 0.7\n\x01\xff\x1b[2J";
  binary += std::string(100, '\x80') + "\n";
  std::string path = write_file("binary.pcd", binary);
  std::string error = read_error(path);
  std::string quoted = "\\x01\\xff\\x1b[2J";  // 6 bytes of the line, then as many 0x80 as the cap leaves
  for (std::size_t i = 6; i < kMaxQuotedBytes; ++i) quoted += "\\x80";
  EXPECT_EQ(error, path + ":2: not a PCD header line: '" + quoted + "...'");
  EXPECT_TRUE(is_printable(error)) << error;
  // A field name, a count and an ascii body's token, each quoted.
  path = write_file("field.pcd", header("x y z\x07", "4 4 1", "F F F", "1 1 1", 1, 1, "ascii") + "1 2 3\n");
  error = read_error(path);
  EXPECT_THAT(error, HasSubstr("field z\\x07 of TYPE F"));
  EXPECT_TRUE(is_printable(error)) << error;
  path = write_file("count.pcd", header("x y z", "4 4 4", "F F F", "1 1 \x7f", 1, 1, "ascii") + "1 2 3\n");
  error = read_error(path);
  EXPECT_THAT(error, HasSubstr("COUNT '\\x7f' is not a whole number (field z)"));
  EXPECT_TRUE(is_printable(error)) << error;
  path =
      write_file("token.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 1, 1, "ascii") + "1 2 \x1b\x9b\n");
  error = read_error(path);
  EXPECT_THAT(error, HasSubstr("not a number: '\\x1b\\x9b'"));
  EXPECT_TRUE(is_printable(error)) << error;
}

// "A missing or malformed file is an InputError", but PCL reads a word in an ASCII body as 0:
// the second point below comes back as (4, 0, 6).
TEST_F(Pcd, AsciiBodyWithAWordIsAnInputError) {
  const std::string path =
      write_file("word.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "ascii") + "1 2 3\n4 abc 6\n");
  EXPECT_THAT(read_error(path), StartsWith(path + ":"));
}

TEST_F(Pcd, EncodedCloudsReadBackExactly) {
  PointCloud xyz;
  xyz.points = {{0.025f, -3.5f, 2.575f}, {1e4f, 0.0f, -7.25f}};
  const std::string bytes = encode_pcd(xyz);
  EXPECT_THAT(bytes, HasSubstr("FIELDS x y z\n"));
  EXPECT_THAT(bytes, HasSubstr("DATA binary\n"));
  const PointCloud back = read_pcd(write_file("xyz.pcd", bytes));
  EXPECT_EQ(back.points, xyz.points);
  EXPECT_FALSE(back.has_intensity());
  PointCloud with_i = xyz;
  with_i.intensity = {0.5f, 0.75f};
  const PointCloud back_i = read_pcd(write_file("xyzi.pcd", encode_pcd(with_i)));
  EXPECT_EQ(back_i.points, with_i.points);
  EXPECT_EQ(back_i.intensity, with_i.intensity);
  EXPECT_TRUE(read_pcd(write_file("empty.pcd", encode_pcd(PointCloud{}))).empty());
}

namespace {

// A DATA binary_compressed body: the two little-endian size words, then `lzf` as written.
std::string compressed_body(std::uint32_t compressed, std::uint32_t uncompressed, const std::string& lzf) {
  std::string body(8, '\0');
  std::memcpy(body.data(), &compressed, 4);
  std::memcpy(body.data() + 4, &uncompressed, 4);
  return body + lzf;
}

// Two x y z float points as binary_compressed stores them (field by field: x0 x1 y0 y1 z0 z1)
// in LZF made of one literal run (a control byte below 32 is "copy the next byte + 1 bytes").
std::string two_points_lzf() {
  const float soa[6] = {1.0f, 4.0f, 2.0f, 5.0f, 3.0f, 6.0f};
  std::string lzf(1, static_cast<char>(sizeof soa - 1));
  lzf.append(reinterpret_cast<const char*>(soa), sizeof soa);
  return lzf;
}

}  // namespace

TEST_F(Pcd, CompressedBlockThatAgreesWithItsHeaderReads) {
  const std::string path =
      write_file("good.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "binary_compressed") +
                                 compressed_body(25, 24, two_points_lzf()));
  const PointCloud cloud = read_pcd(path);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4, 5, 6));
}

// Issue 18: an uncompressed size word of 0 made PCL write the points into an empty buffer
// (SIGSEGV in run, convert and simulate).
TEST_F(Pcd, CompressedBlockWithUncompressedSizeZeroIsAnInputError) {
  const std::string path =
      write_file("zero.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "binary_compressed") +
                                 compressed_body(25, 0, two_points_lzf()));
  const std::string message = read_error(path);
  EXPECT_THAT(message, StartsWith(path + ": "));
  EXPECT_THAT(message, HasSubstr("uncompressed size 0, expected 24 bytes for POINTS x SIZE"));
}

TEST_F(Pcd, CompressedBlockSizesThatDisagreeWithTheFileAreInputErrors) {
  const std::string head = header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "binary_compressed");
  const std::string larger = write_file("larger.pcd", head + compressed_body(25, 4096, two_points_lzf()));
  EXPECT_THAT(read_error(larger), HasSubstr("uncompressed size 4096, expected 24 bytes"));
  const std::string past = write_file("past.pcd", head + compressed_body(0xFFFFFFF0u, 24, two_points_lzf()));
  EXPECT_THAT(read_error(past),
              AllOf(StartsWith(past + ": "), HasSubstr("compressed size 4294967280 runs past the end")));
  const std::string empty = write_file("empty_block.pcd", head + compressed_body(0, 24, ""));
  EXPECT_THAT(read_error(empty), HasSubstr("compressed size 0"));
  const std::string no_words = write_file("no_words.pcd", head + "abc");
  EXPECT_THAT(read_error(no_words), AllOf(StartsWith(no_words + ": "), HasSubstr("size words")));
  // Issue 52: bytes after the block were ignored (a binary body's are refused).
  const std::string trailing =
      write_file("trailing.pcd", head + compressed_body(25, 24, two_points_lzf()) + "xyz");
  EXPECT_EQ(read_error(trailing),
            trailing + ": binary_compressed block at byte " + std::to_string(head.size()) +
                ": 3 bytes after the compressed block, from byte " + std::to_string(head.size() + 8 + 25));
}

// Issue 18: "SIZE four" was skipped as "stoll: scan skipped", without the file's name.
TEST_F(Pcd, NonNumericSizeOrCountNamesTheFileLineAndField) {
  std::string text = header("x y z", "4 four 4", "F F F", "1 1 1", 1, 1, "ascii") + "1 2 3\n";
  const std::string size = write_file("size.pcd", text);
  EXPECT_THAT(read_error(size),
              StartsWith(size + ":4: PCD header: SIZE 'four' is not a whole number (field y)"));
  const std::string count =
      write_file("count.pcd", header("x y z", "4 4 4", "F F F", "1 -1 1", 1, 1, "ascii") + "1 2 3\n");
  EXPECT_THAT(read_error(count),
              StartsWith(count + ":6: PCD header: COUNT '-1' is not a whole number (field y)"));
  const std::string width =
      write_file("width.pcd", header("x y z", "4 4 4", "F F F", "1 1 1", 1, 1, "ascii") + "1 2 3\n");
  std::string wide = read_file(width);
  wide.replace(wide.find("WIDTH 1"), 7, "WIDTH 99999999999999999999999");
  const std::string overflow = write_file("overflow.pcd", wide);
  EXPECT_THAT(read_error(overflow), StartsWith(overflow + ":7: PCD header: WIDTH"));
}

// Issue 18: a symlink loop ended in "internal error" (std::filesystem's exception).
TEST_F(Pcd, SymlinkLoopIsAnInputErrorNamingTheFile) {
  const std::filesystem::path a = dir_ / "a.pcd", b = dir_ / "b.pcd";
  std::filesystem::create_symlink(b, a);
  std::filesystem::create_symlink(a, b);
  EXPECT_THAT(read_error(a.string()), StartsWith(a.string() + ": "));
}

// Issue 18: PCL printed its own lines ("[pcl::PCDReader::readHeader] ...") before ours. The
// reader is ours now: a malformed header or body is one line naming the file and the line (or
// the block's byte), and nothing else is printed.
TEST_F(Pcd, MalformedFilesAreOneLineErrorsAndNothingElseIsPrinted) {
  const std::string good = header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "ascii");
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string h = good;
    h.replace(h.find(from), from.size(), to);
    return h + "1 2 3\n4 5 6\n";
  };
  const std::string compressed = header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "binary_compressed");
  struct Case {
    std::string name, text, error;
  };
  const std::vector<Case> cases = {
      {"viewpoint.pcd", replaced("VIEWPOINT 0 0 0 1 0 0 0", "VIEWPOINT 0 0 0"),
       ":9: PCD header: VIEWPOINT needs 7 numbers (tx ty tz qw qx qy qz)"},
      {"type_first.pcd", replaced("SIZE 4 4 4\nTYPE F F F", "TYPE F F F\nSIZE 4 4 4"),
       ":4: PCD header: TYPE comes before SIZE"},
      {"count_first.pcd",
       replaced("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1",
                "COUNT 1 1 1\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F"),
       ":3: PCD header: COUNT comes before FIELDS"},
      {"points.pcd", replaced("POINTS 2", "POINTS 3"),
       ":10: PCD header: POINTS 3 is not WIDTH * HEIGHT (2 x 1)"},
      {"data.pcd", replaced("DATA ascii", "DATA text"),
       ":11: PCD header: DATA must be ascii, binary or binary_compressed"},
      {"no_data.pcd", good.substr(0, good.find("DATA")), ":10: PCD header has no DATA line"},
      {"few_rows.pcd", good + "1 2 3\n", ":12: PCD body has 1 points, POINTS says 2"},
      {"many_rows.pcd", good + "1 2 3\n4 5 6\n7 8 9\n", ":14: PCD body has more points than POINTS (2)"},
      {"short_row.pcd", good + "1 2 3\n4 5\n", ":13: expected 3 values, found 2"},
      {"bad_lzf.pcd", compressed + compressed_body(25, 24, std::string(1, '\x1f') + std::string(24, '\0')),
       ": binary_compressed block at byte 175: corrupt LZF data: it decompresses to 0 of 24 bytes"},
      // A back-reference before the start of the block (liblzf checks it).
      {"back_ref.pcd", compressed + compressed_body(3, 24, std::string("\xe0\x10\x20", 3)),
       ": binary_compressed block at byte 175: corrupt LZF data: it decompresses to 0 of 24 bytes"},
  };
  for (const Case& c : cases) {
    const std::string path = write_file(c.name, c.text);
    testing::internal::CaptureStderr();
    const std::string error = read_error(path);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << c.name;
    EXPECT_EQ(error, path + c.error);
  }
}

// Found by fuzzing (issue 18): PCL's reader took a binary body's lines that began with a header
// word ("DATA", "FIELDS", "COLUMNS", also after lines it did not know) for more header, and threw
// or wrote out of bounds. A binary body is bytes: whatever they spell, they are read as points.
TEST_F(Pcd, BinaryBodiesAreReadAsBytesWhateverTheySpell) {
  const std::string head = header("x y z", "4 4 4", "F F F", "1 1 1", 2, 1, "binary");
  for (const std::string word : {"DATA", "FIELDS", "COLUMNS", "VERSION x\n\n# c\n  FIELDS a\nDATA b"}) {
    std::string body = word.substr(0, 24);
    body.resize(24, '\0');
    const PointCloud cloud = read_pcd(write_file("words.pcd", head + body));
    float first[6];  // ASCII bytes are finite floats (exponent bits below 0xff)
    std::memcpy(first, body.data(), sizeof first);
    ASSERT_EQ(cloud.size(), 2u) << word;
    EXPECT_EQ(cloud.points[0], Eigen::Vector3f(first[0], first[1], first[2])) << word;
    EXPECT_EQ(cloud.points[1], Eigen::Vector3f(first[3], first[4], first[5])) << word;
  }
}

// Found by fuzzing (issue 18): a 2-byte float field was read as 4 bytes, past the end of the
// last point (heap-buffer-overflow under ASan). Types outside the specification are refused.
TEST_F(Pcd, FieldTypesOutsideTheSpecificationAreRefusedAtTheSizeLine) {
  for (const auto& [size, type] : std::vector<std::pair<std::string, std::string>>{
           {"4 4 2", "F F F"}, {"4 4 1", "F F F"}, {"4 4 3", "F F I"}}) {
    const std::string path =
        write_file("types.pcd", header("x y z", size, type, "1 1 1", 1, 1, "binary") + std::string(16, '\0'));
    EXPECT_THAT(read_error(path), StartsWith(path + ":4: PCD header: field z of TYPE "));
  }
}

// Every type of the specification, in a binary body: 8-byte integers too.
TEST_F(Pcd, EveryFieldTypeReads) {
  std::string body;
  const auto put = [&](auto v) { body.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(std::int64_t{-3}), put(std::uint64_t{7}), put(std::int16_t{-2}), put(std::uint8_t{200});
  const PointCloud cloud = read_pcd(write_file(
      "types.pcd", header("x y z intensity", "8 8 2 1", "I U I U", "1 1 1 1", 1, 1, "binary") + body));
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(-3, 7, -2));
  EXPECT_EQ(cloud.intensity[0], 200.0f);
}

// binary_compressed stores field after field (all x, then all y, ...); with fields of other
// sizes and a COUNT above 1 each block starts after the ones before it, for all points.
TEST_F(Pcd, CompressedFieldsOfMixedSizesAndCounts) {
  std::string soa;
  const auto put = [&](auto v) { soa.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(std::uint16_t{40}), put(std::uint16_t{50}), put(std::uint16_t{60});  // intensity, 3 points
  for (float v : {1.f, 4.f, 7.f}) put(v);                                  // x
  for (int k = 0; k < 3 * 2; ++k) put(std::uint8_t(k));                    // pad, COUNT 2
  for (float v : {2.f, 5.f, 8.f}) put(v);                                  // y
  for (double v : {3.0, 6.0, 9.0}) put(v);                                 // z
  std::string lzf;                                                         // literal runs of at most 32 bytes
  for (std::size_t at = 0; at < soa.size(); at += 32) {
    const std::size_t n = std::min<std::size_t>(32, soa.size() - at);
    lzf += static_cast<char>(n - 1);
    lzf += soa.substr(at, n);
  }
  const std::string path = write_file(
      "mixed.pcd",
      header("intensity x pad y z", "2 4 1 4 8", "U F U F F", "1 1 2 1 1", 3, 1, "binary_compressed") +
          compressed_body(static_cast<std::uint32_t>(lzf.size()), static_cast<std::uint32_t>(soa.size()),
                          lzf));
  const PointCloud cloud = read_pcd(path);
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4, 5, 6));
  EXPECT_EQ(cloud.points[2], Eigen::Vector3f(7, 8, 9));
  EXPECT_EQ(cloud.intensity[2], 60.0f);
}

// POINTS x point size beyond 64 bits (8,200 fields of COUNT 65536 and 2^32 - 1 points) is
// refused at the POINTS line, not wrapped round into a small size.
TEST_F(Pcd, PointsTimesPointSizeOverflowIsRefused) {
  std::string fields, sizes, types, counts;
  for (int i = 0; i < 8200; ++i) {
    fields += (i < 3 ? std::string(1, "xyz"[i]) : "f" + std::to_string(i)) + " ";
    sizes += "8 ", types += "F ", counts += "65536 ";
  }
  const std::string path =
      write_file("overflow.pcd", header(fields, sizes, types, counts, 4294967295u, 1, "binary"));
  EXPECT_EQ(read_error(path), path + ":10: PCD header: POINTS x point size overflows");
}

// A size word no LZF block of this length can reach is refused before its buffer is made.
TEST_F(Pcd, CompressedSizeWordLzfCannotReachIsRefused) {
  const std::string head = header("x y z", "4 4 4", "F F F", "1 1 1", 1000, 1000, "binary_compressed");
  const std::string path = write_file("ratio.pcd", head + compressed_body(4, 12000000, "abcd"));
  EXPECT_EQ(read_error(path), path + ": binary_compressed block at byte " + std::to_string(head.size()) +
                                  ": 4 compressed bytes cannot hold 12000000 (LZF expands at most 88 times)");
}

// Found by fuzzing (issue 18): a header with a second POINTS line (and the rest again) passed
// this check with one and made PCL size the cloud by the other (an allocation of 1e18 bytes).
TEST_F(Pcd, AHeaderKeyGivenTwiceIsRefused) {
  std::string text = header("x y z", "4 4 4", "F F F", "1 1 1", 1, 1, "binary");
  text.insert(text.find("POINTS"), "POINTS 99999999999\n");
  const std::string path = write_file("twice.pcd", text + std::string(12, '\0'));
  EXPECT_EQ(read_error(path), path + ":11: PCD header: POINTS given twice (first on line 10)");
}
