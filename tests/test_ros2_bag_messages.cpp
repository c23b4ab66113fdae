// ROS 2 messages in CDR (ros2_bag/cdr.hpp, ros2_bag/ros2_messages.hpp): written and read back, a
// big-endian message built byte by byte with its alignment padding, messages cut short or
// claiming more than they hold, and definitions checked field by field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/ros2_bag/cdr.hpp"
#include "tsgraphs/io/point_cloud2.hpp"
#include "tsgraphs/ros2_bag/ros2_messages.hpp"

using namespace tsgraphs;
namespace ros2 = tsgraphs::ros2_bag::ros2;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

Pose3 some_pose(double yaw, const Eigen::Vector3d& t) {
  Pose3 p = Pose3::Identity();
  p.linear() =
      (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  p.translation() = t;
  return p;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Ros2Messages, PointCloud2ReadsBackItsPoints) {
  PointCloud cloud;
  for (int i = 0; i < 50; ++i) {
    cloud.points.emplace_back(0.5f * i, -0.25f * i, 0.125f * (i % 7));
    cloud.intensity.push_back(static_cast<float>(i));
  }
  const std::string cdr = ros2::encode_point_cloud2(1700000000.123456789, "lidar", cloud);
  const io::PointCloud2Message m = ros2::parse_point_cloud2(cdr, "bag: /points, message 0");
  EXPECT_NEAR(m.stamp, 1700000000.123456789, 1e-6);
  EXPECT_EQ(m.frame_id, "lidar");
  EXPECT_EQ(m.layout.width, 50u);
  ASSERT_EQ(m.layout.fields.size(), 4u);
  EXPECT_EQ(m.layout.fields[3].name, "intensity");
  const PointCloud back = io::decode_point_cloud2(
      m.layout, reinterpret_cast<const std::uint8_t*>(cdr.data()) + m.data_offset, m.data_size, "here");
  ASSERT_EQ(back.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(back.points[i], cloud.points[i]);
    EXPECT_EQ(back.intensity[i], cloud.intensity[i]);
  }
}

TEST(Ros2Messages, PosesAndTransformsReadBack) {
  ros2::StampedPoseMessage odom{12.25, "odom", "base_link", some_pose(0.7, {1, -2, 0.5})};
  const ros2::StampedPoseMessage o = ros2::parse_odometry(ros2::encode_odometry(odom), "x");
  EXPECT_EQ(o.stamp, 12.25);
  EXPECT_EQ(o.frame_id, "odom");
  EXPECT_EQ(o.child_frame_id, "base_link");
  EXPECT_TRUE(o.pose.isApprox(odom.pose, 1e-12));
  const ros2::StampedPoseMessage p = ros2::parse_pose_stamped(ros2::encode_pose_stamped(odom), "x");
  EXPECT_TRUE(p.pose.isApprox(odom.pose, 1e-12));
  EXPECT_EQ(p.frame_id, "odom");
  const std::vector<ros2::TransformMessage> tf = {{0.0, "base_link", "lidar", some_pose(0.0, {0.1, 0, 1.2})},
                                                  {0.0, "map", "odom", some_pose(-1.0, {5, 5, 0})}};
  const auto back = ros2::parse_tf_message(ros2::encode_tf_message(tf), "x");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].parent, "map");
  EXPECT_EQ(back[1].child, "odom");
  EXPECT_TRUE(back[0].transform.isApprox(tf[0].transform, 1e-12));
}

// A geometry_msgs/PoseStamped in big-endian CDR, built from the rules: the frame id "odom"
// (length 5 with its NUL) ends at byte 17 of the body, so 7 bytes of padding align the first
// double to 8.
TEST(Ros2Messages, BigEndianWithAlignmentPadding) {
  std::string body;
  const auto be = [&](std::uint64_t v, int bytes) {
    for (int i = bytes - 1; i >= 0; --i) body.push_back(static_cast<char>(v >> (8 * i)));
  };
  const auto be_double = [&](double d) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, 8);
    be(bits, 8);
  };
  be(12, 4), be(500000000, 4), be(5, 4);
  body += std::string("odom\0", 5);
  body += std::string(7, '\x55');  // padding (any value)
  for (double v : {1.0, 2.0, 3.0}) be_double(v);
  for (double v : {0.0, 0.0, std::sin(0.25), std::cos(0.25)}) be_double(v);  // 0.5 rad about z
  const std::string cdr = std::string("\x00\x00\x00\x00", 4) + body;
  const ros2::StampedPoseMessage m = ros2::parse_pose_stamped(cdr, "x");
  EXPECT_EQ(m.stamp, 12.5);
  EXPECT_EQ(m.frame_id, "odom");
  EXPECT_TRUE(m.pose.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_NEAR(std::atan2(m.pose.linear()(1, 0), m.pose.linear()(0, 0)), 0.5, 1e-12);
}

TEST(Ros2Messages, MessagesCutShortOrClaimingTooMuchAreInputErrorsNamingTheMessage) {
  const std::string odom = ros2::encode_odometry({1.0, "odom", "base", some_pose(0.2, {1, 2, 3})});
  for (std::size_t n = 0; n < odom.size(); ++n) {
    EXPECT_THAT(error_of([&] { ros2::parse_odometry(odom.substr(0, n), "run.db3: /odom, message 3"); }),
                StartsWith("run.db3: /odom, message 3: "))
        << n;
  }
  PointCloud cloud;
  cloud.points.emplace_back(1, 2, 3);
  std::string points = ros2::encode_point_cloud2(1.0, "lidar", cloud);
  for (std::size_t n = 0; n < points.size(); ++n) {
    EXPECT_NE(error_of([&] { ros2::parse_point_cloud2(points.substr(0, n), "m"); }), "") << n;
  }
  // A field count of 2^32 - 1 in a short message.
  std::string many = points;
  const std::size_t fields_at = 4 + 4 + 4 + 4 + 6 + 2 + 4 + 4;  // stamp, frame "lidar" + pad, height, width
  for (int i = 0; i < 4; ++i) many[fields_at + i] = '\xff';
  EXPECT_THAT(error_of([&] { ros2::parse_point_cloud2(many, "m"); }),
              HasSubstr("CDR sequence fields of 4294967295 elements"));
  EXPECT_THAT(
      error_of([&] { ros2::parse_odometry(std::string("\x01\x00\x00\x00", 4) + odom.substr(4), "m"); }),
      HasSubstr("not plain CDR"));
  // A zero quaternion is no orientation.
  const std::string zero = ros2::encode_pose_stamped({1.0, "map", "", Pose3::Identity()});
  std::string bad = zero;
  bad.replace(bad.size() - 8, 8, std::string(8, '\0'));  // w = 0 with x = y = z = 0
  EXPECT_THAT(error_of([&] { ros2::parse_pose_stamped(bad, "m"); }), HasSubstr("not a rotation"));
}

TEST(Ros2Messages, DefinitionsAreCheckedFieldByField) {
  const std::string& pc2 = ros2::definition(ros2::kPointCloud2);
  EXPECT_THAT(pc2, StartsWith("std_msgs/Header header\n"));
  EXPECT_THAT(pc2, HasSubstr("\n" + std::string(80, '=') + "\nMSG: std_msgs/Header\n"));
  EXPECT_THAT(pc2, HasSubstr("MSG: builtin_interfaces/Time\n"));
  EXPECT_THAT(pc2, HasSubstr("MSG: sensor_msgs/PointField\n"));
  for (const char* type : {ros2::kPointCloud2, ros2::kOdometry, ros2::kPoseStamped, ros2::kTfMessage}) {
    EXPECT_EQ(ros2::definition_mismatch(type, ros2::definition(type)), "") << type;
    EXPECT_EQ(ros2::definition_mismatch(type, ""), "") << type;
  }
  // Comments, constants and package-relative types, as ROS's own files have them.
  const std::string written_by_hand =
      "# A cloud\nuint8 INT8    = 1\nuint8 FLOAT32 = 7\nHeader header # the stamp\n\nuint32 height\nuint32 "
      "width\n"
      "PointField[] fields\nbool    is_bigendian\nuint32  point_step\nuint32  row_step\nuint8[] data\nbool "
      "is_dense\n";
  EXPECT_EQ(ros2::definition_mismatch(ros2::kPointCloud2, written_by_hand), "");
  EXPECT_THAT(
      ros2::definition_mismatch(ros2::kOdometry, ros2::definition(ros2::kPoseStamped)),
      HasSubstr(
          "its definition declares (Header header, Pose pose), not the fields of nav_msgs/msg/Odometry"));
  EXPECT_THROW(ros2::definition("std_msgs/msg/String"), std::invalid_argument);
}
