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
  l.fields = {{"x", 0, kF64, 1}, {"y", 8, kF64, 1}, {"z", 16, kF64, 1}, {"intensity", 28, kU16, 1}, {"ring", 30, kU16, 1}};
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
  EXPECT_NE(test::input_error_of([&] { decode_point_cloud2(no_z, data.data(), data.size(), "a.bag: /points, scan 3"); })
                .find("a.bag: /points, scan 3"),
            std::string::npos);
  PointCloud2Layout int_x = padded_layout();
  int_x.fields[0].datatype = kI16;
  EXPECT_NE(test::input_error_of([&] { decode_point_cloud2(int_x, data.data(), data.size(), "m"); }).find("neither float32"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([&] { decode_point_cloud2(padded_layout(), data.data(), 100, "m"); }).find("bytes"),
            std::string::npos);
  PointCloud2Layout past = padded_layout();
  past.fields[3].offset = 35;
  EXPECT_NE(test::input_error_of([&] { decode_point_cloud2(past, data.data(), data.size(), "m"); }).find("past point_step"),
            std::string::npos);
  PointCloud2Layout big = padded_layout();
  big.is_bigendian = true;
  EXPECT_NE(test::input_error_of([&] { decode_point_cloud2(big, data.data(), data.size(), "m"); }).find("big-endian"),
            std::string::npos);
}
