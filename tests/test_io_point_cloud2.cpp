// sensor_msgs/PointCloud2 data decoded without ROS (io/point_cloud2.hpp): float64 coordinates,
// padding, organised clouds with NaN returns, and layouts that cannot be read.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "test_support.hpp"
#include "tsgraphs/io/point_cloud2.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;

namespace {

constexpr std::uint8_t kF32 = 7, kF64 = 8, kU16 = 4, kI16 = 3;

template <class T>
void put(std::vector<std::uint8_t>& data, std::size_t at, T v) {
  std::memcpy(data.data() + at, &v, sizeof(T));
}

/// An organised 2 x 3 cloud: x y z float64 at 0 / 8 / 16, 4 bytes of padding, intensity uint16
/// at 28, 36-byte points, rows padded to 120 bytes; point (1, 1) is a missing return (NaN).
PointCloud2Layout padded_layout() {
  PointCloud2Layout l;
  l.height = 2;
  l.width = 3;
  l.point_step = 36;
  l.row_step = 120;
  l.fields = {{"x", 0, kF64, 1},
              {"y", 8, kF64, 1},
              {"z", 16, kF64, 1},
              {"intensity", 28, kU16, 1},
              {"ring", 30, kU16, 1}};
  return l;
}

std::vector<std::uint8_t> padded_data() {
  std::vector<std::uint8_t> data(240, 0xAB);
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c) {
      const std::size_t at = r * 120 + c * 36;
      const double x = r == 1 && c == 1 ? std::numeric_limits<double>::quiet_NaN() : 10.0 * r + c + 0.125;
      put(data, at, x);
      put(data, at + 8, -1.0 * c);
      put(data, at + 16, 0.5 * r);
      put<std::uint16_t>(data, at + 28, static_cast<std::uint16_t>(100 * r + c));
    }
  }
  return data;
}

}  // namespace

TEST(PointCloud2, Float64FieldsPaddingAndNaNReturnsDecodeRight) {
  const std::vector<std::uint8_t> data = padded_data();
  const PointCloud cloud = decode_point_cloud2(padded_layout(), data.data(), data.size(), "test");
  ASSERT_EQ(cloud.size(), 5u);  // 6 points, one NaN
  ASSERT_TRUE(cloud.has_intensity());
  EXPECT_FLOAT_EQ(cloud.points[1].x(), 1.125f);
  EXPECT_FLOAT_EQ(cloud.points[1].y(), -1.0f);
  EXPECT_FLOAT_EQ(cloud.points[3].x(), 10.125f);  // row 1, column 0
  EXPECT_FLOAT_EQ(cloud.points[4].x(), 12.125f);  // row 1, column 2 (column 1 was NaN)
  EXPECT_FLOAT_EQ(cloud.points[4].z(), 0.5f);
  EXPECT_FLOAT_EQ(cloud.intensity[4], 102.0f);
}

TEST(PointCloud2, Float32WithoutIntensity) {
  PointCloud2Layout l;
  l.width = 2;
  l.point_step = 16;  // x y z and 4 bytes of padding
  l.row_step = 32;
  l.fields = {{"x", 0, kF32, 1}, {"y", 4, kF32, 1}, {"z", 8, kF32, 1}};
  std::vector<std::uint8_t> data(32, 0);
  put(data, 0, 1.5f);
  put(data, 16 + 8, -2.0f);
  const PointCloud cloud = decode_point_cloud2(l, data.data(), data.size(), "test");
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_FALSE(cloud.has_intensity());
  EXPECT_FLOAT_EQ(cloud.points[0].x(), 1.5f);
  EXPECT_FLOAT_EQ(cloud.points[1].z(), -2.0f);
}

TEST(PointCloud2, LayoutsThatCannotBeReadAreErrorsNamingTheMessage) {
  const std::vector<std::uint8_t> data = padded_data();
  PointCloud2Layout no_z = padded_layout();
  no_z.fields.erase(no_z.fields.begin() + 2);
  EXPECT_NE(test::input_error_of([&] {
              decode_point_cloud2(no_z, data.data(), data.size(), "a.bag: /points, scan 3");
            }).find("a.bag: /points, scan 3"),
            std::string::npos);
  PointCloud2Layout int_x = padded_layout();
  int_x.fields[0].datatype = kI16;
  EXPECT_NE(test::input_error_of([&] {
              decode_point_cloud2(int_x, data.data(), data.size(), "m");
            }).find("neither float32"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([&] {
              decode_point_cloud2(padded_layout(), data.data(), 100, "m");
            }).find("bytes"),
            std::string::npos);
  PointCloud2Layout past = padded_layout();
  past.fields[3].offset = 35;
  EXPECT_NE(test::input_error_of([&] {
              decode_point_cloud2(past, data.data(), data.size(), "m");
            }).find("past point_step"),
            std::string::npos);
  PointCloud2Layout big = padded_layout();
  big.is_bigendian = true;
  EXPECT_NE(test::input_error_of([&] {
              decode_point_cloud2(big, data.data(), data.size(), "m");
            }).find("big-endian"),
            std::string::npos);
}

// Issue 52: x a float64 at 0 with y at 4 decoded y from half of x, as garbage. Fields sharing
// bytes are refused naming the message and both fields.
TEST(PointCloud2, FieldsThatOverlapAreRefusedNamingTheField) {
  const std::vector<std::uint8_t> data = padded_data();
  PointCloud2Layout y_in_x = padded_layout();
  y_in_x.fields[1].offset = 4;
  EXPECT_EQ(test::input_error_of(
                [&] { decode_point_cloud2(y_in_x, data.data(), data.size(), "a.bag: /points, message 3"); }),
            "a.bag: /points, message 3: field 'y' (bytes 4 to 11) overlaps field 'x' (bytes 0 to 7)");
  // Any field, wherever it is listed: ring (listed last) over the intensity's second byte.
  PointCloud2Layout ring = padded_layout();
  ring.fields[4].offset = 29;
  EXPECT_EQ(test::input_error_of([&] { decode_point_cloud2(ring, data.data(), data.size(), "m"); }),
            "m: field 'ring' (bytes 29 to 30) overlaps field 'intensity' (bytes 28 to 29)");
  // A field's count is its extent: x of 2 values reaches over y.
  PointCloud2Layout counted = padded_layout();
  counted.fields[0].count = 2;
  EXPECT_EQ(test::input_error_of([&] { decode_point_cloud2(counted, data.data(), data.size(), "m"); }),
            "m: field 'y' (bytes 8 to 15) overlaps field 'x' (bytes 0 to 15)");
  // The same field twice at one place is an overlap too; fields that only touch are not.
  PointCloud2Layout twice = padded_layout();
  twice.fields.push_back({"x", 0, kF64, 1});
  EXPECT_NE(test::input_error_of([&] {
              decode_point_cloud2(twice, data.data(), data.size(), "m");
            }).find("overlaps field 'x'"),
            std::string::npos);
  EXPECT_EQ(decode_point_cloud2(padded_layout(), data.data(), data.size(), "m").size(), 5u);
}

namespace {

void append_word(std::vector<std::uint8_t>& out, std::uint32_t v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + 4);
}

void append_string(std::vector<std::uint8_t>& out, const std::string& s) {
  append_word(out, static_cast<std::uint32_t>(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}

/// The padded cloud as a bag stores a sensor_msgs/PointCloud2 (ROS1 serialization), stamped
/// 12.5 s in frame "lidar". `fields_at` and `data_at` receive where the field count and the
/// data length words are.
std::vector<std::uint8_t> serialized_message(std::size_t* fields_at = nullptr,
                                             std::size_t* data_at = nullptr) {
  const PointCloud2Layout l = padded_layout();
  const std::vector<std::uint8_t> data = padded_data();
  std::vector<std::uint8_t> out;
  append_word(out, 7);          // header.seq
  append_word(out, 12);         // header.stamp.sec
  append_word(out, 500000000);  // header.stamp.nsec
  append_string(out, "lidar");
  append_word(out, l.height);
  append_word(out, l.width);
  if (fields_at) *fields_at = out.size();
  append_word(out, static_cast<std::uint32_t>(l.fields.size()));
  for (const PointField2& f : l.fields) {
    append_string(out, f.name);
    append_word(out, f.offset);
    out.push_back(f.datatype);
    append_word(out, f.count);
  }
  out.push_back(0);  // is_bigendian
  append_word(out, l.point_step);
  append_word(out, l.row_step);
  if (data_at) *data_at = out.size();
  append_word(out, static_cast<std::uint32_t>(data.size()));
  out.insert(out.end(), data.begin(), data.end());
  out.push_back(1);  // is_dense
  return out;
}

void set_word(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t v) {
  std::memcpy(bytes.data() + at, &v, 4);
}

}  // namespace

TEST(PointCloud2Message, SerializedMessageParsesAndDecodes) {
  const std::vector<std::uint8_t> bytes = serialized_message();
  const PointCloud2Message m = parse_point_cloud2_message(bytes.data(), bytes.size(), "test");
  EXPECT_DOUBLE_EQ(m.stamp, 12.5);
  EXPECT_EQ(m.frame_id, "lidar");
  ASSERT_EQ(m.layout.fields.size(), 5u);
  EXPECT_EQ(m.layout.fields[3].name, "intensity");
  EXPECT_EQ(m.layout.fields[3].offset, 28u);
  EXPECT_EQ(m.layout.row_step, 120u);
  EXPECT_EQ(m.data_size, 240u);
  const PointCloud cloud = decode_point_cloud2(m.layout, bytes.data() + m.data_offset, m.data_size, "test");
  ASSERT_EQ(cloud.size(), 5u);
  EXPECT_FLOAT_EQ(cloud.points[4].x(), 12.125f);
  EXPECT_FLOAT_EQ(cloud.intensity[4], 102.0f);
}

// Issue 18: a field count or data length near 2^31 was a bad_alloc or a stream overrun
// ("internal error") in rosbag's deserializer; checked against the message's bytes, before
// anything is allocated.
TEST(PointCloud2Message, LengthsNear2To31AreInputErrorsNamingTheByte) {
  std::size_t fields_at = 0, data_at = 0;
  const std::vector<std::uint8_t> good = serialized_message(&fields_at, &data_at);
  std::vector<std::uint8_t> fields = good;
  set_word(fields, fields_at, 0x7FFFFFFFu);
  EXPECT_EQ(test::input_error_of(
                [&] { parse_point_cloud2_message(fields.data(), fields.size(), "a.bag: /points, scan 3"); }),
            "a.bag: /points, scan 3: field count 2147483647 at byte " + std::to_string(fields_at) +
                " is more than the message's " + std::to_string(good.size() - fields_at - 4) +
                " bytes can hold");
  std::vector<std::uint8_t> data = good;
  set_word(data, data_at, 0x7FFFFFF0u);
  EXPECT_EQ(
      test::input_error_of([&] { parse_point_cloud2_message(data.data(), data.size(), "m"); }),
      "m: data at byte " + std::to_string(data_at + 4) + " needs 2147483632 bytes, the message has 241 left");
  std::vector<std::uint8_t> name = good;
  set_word(name, fields_at + 4, 0xFFFFFFF0u);  // the first field's name length
  EXPECT_NE(test::input_error_of([&] {
              parse_point_cloud2_message(name.data(), name.size(), "m");
            }).find("field name"),
            std::string::npos);
}

TEST(PointCloud2Message, EveryTruncationIsAnInputError) {
  const std::vector<std::uint8_t> good = serialized_message();
  for (std::size_t keep = 0; keep < good.size(); ++keep) {
    SCOPED_TRACE(keep);
    EXPECT_NE(test::input_error_of([&] { parse_point_cloud2_message(good.data(), keep, "m"); }).find("m: "),
              std::string::npos);
  }
}

// A field count (COUNT, not the number of fields) near 2^32 is a field past point_step, with
// no overflow; and many empty rows are no work.
TEST(PointCloud2, HugeFieldCountOrEmptyRowsAreHandled) {
  const std::vector<std::uint8_t> data = padded_data();
  PointCloud2Layout counted = padded_layout();
  counted.fields[3].count = 0xFFFFFFFFu;
  EXPECT_NE(test::input_error_of([&] {
              decode_point_cloud2(counted, data.data(), data.size(), "m");
            }).find("past point_step"),
            std::string::npos);
  PointCloud2Layout empty_rows = padded_layout();
  empty_rows.height = 0xFFFFFFFFu;
  empty_rows.width = 0;
  empty_rows.row_step = 0;
  EXPECT_TRUE(decode_point_cloud2(empty_rows, data.data(), data.size(), "m").empty());
}
