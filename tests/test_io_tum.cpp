// TUM trajectory files: round trip, field order, skipped lines and every rejected line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/tum.hpp"

#include "test_support.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using tsgraphs::test::input_error_of;
using tsgraphs::test::TempDirTest;

namespace {

class Tum : public TempDirTest {
 protected:
  // The message of the InputError that reading `text` from the file bad_path() raises.
  std::string error_reading(const std::string& text) {
    SCOPED_TRACE("reading:\n" + text);
    const std::string path = write_file("bad.txt", text);
    return input_error_of([&] { read_tum(path); });
  }
  std::string bad_path() const { return (dir_ / "bad.txt").string(); }
};

Pose3 random_pose(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
  const double qz = n(rng), qy = n(rng), qx = n(rng), qw = n(rng);
  Eigen::Quaterniond q(qw, qx, qy, qz);
  q.normalize();
  Pose3 T = Pose3::Identity();
  T.linear() = q.toRotationMatrix();
  const double tz = u(rng), ty = u(rng), tx = u(rng);
  T.translation() = Eigen::Vector3d(tx, ty, tz);
  return T;
}

// x y z qx qy qz qw of the identity pose (a line without its timestamp).
const char* kIdentityLine = "0 0 0 0 0 0 1";

}  // namespace

std::vector<StampedPose> random_trajectory() {
  std::mt19937 rng(2024);
  std::vector<StampedPose> poses;
  double t = 1.7e9;  // Unix time, as real datasets use
  for (int i = 0; i < 200; ++i) {
    t += 0.1 * std::uniform_real_distribution<double>(0.0, 2.0)(rng);
    poses.push_back({t, random_pose(rng)});
  }
  return poses;
}

TEST_F(Tum, RoundTripOfRandomPoses) {
  const std::vector<StampedPose> poses = random_trajectory();
  const std::vector<StampedPose> back = read_tum(write_file("poses.txt", format_tum(poses)));
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(back[i].t, poses[i].t, 1e-9) << i;
    EXPECT_LT((back[i].pose.translation() - poses[i].pose.translation()).cwiseAbs().maxCoeff(), 1e-9) << i;
    // Rotations within a few 1e-9 (see RoundTripOfRotationsTo1e9 for the stricter bound).
    EXPECT_LT((back[i].pose.linear() - poses[i].pose.linear()).cwiseAbs().maxCoeff(), 1e-8) << i;
    // The rotation read back is a proper rotation.
    EXPECT_NEAR(
        (back[i].pose.linear() * back[i].pose.linear().transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0,
        1e-12);
    EXPECT_NEAR(back[i].pose.linear().determinant(), 1.0, 1e-12);
  }
}

// format_tum promises "full double precision, so files round-trip", but prints the quaternion
// with 9 decimals (%.9f): rotation matrix entries come back up to ~1.3e-9 off.
TEST_F(Tum, RoundTripOfRotationsTo1e9) {
  const std::vector<StampedPose> poses = random_trajectory();
  const std::vector<StampedPose> back = read_tum(write_file("poses.txt", format_tum(poses)));
  ASSERT_EQ(back.size(), poses.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    worst = std::max(worst, (back[i].pose.linear() - poses[i].pose.linear()).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-9);
}

TEST_F(Tum, FieldOrderIsTxyzQxQyQzQw) {
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1, 2, 3);
  const std::string text = format_tum({{12.5, T}});
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  std::istringstream s(text);
  double v[8];
  for (double& x : v) ASSERT_TRUE(s >> x) << text;
  double extra;
  EXPECT_FALSE(s >> extra) << text;
  EXPECT_DOUBLE_EQ(v[0], 12.5);
  EXPECT_DOUBLE_EQ(v[1], 1.0);
  EXPECT_DOUBLE_EQ(v[2], 2.0);
  EXPECT_DOUBLE_EQ(v[3], 3.0);
  // q = (qx, qy, qz, qw) = +-(0, 0, sin 45, cos 45).
  const double sign = v[7] < 0 ? -1.0 : 1.0;
  EXPECT_NEAR(sign * v[4], 0.0, 1e-9);
  EXPECT_NEAR(sign * v[5], 0.0, 1e-9);
  EXPECT_NEAR(sign * v[6], std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(sign * v[7], std::sqrt(0.5), 1e-9);
}

TEST_F(Tum, ReadsKnownValues) {
  // 90 deg about x, given with qw last.
  const auto poses =
      read_tum(write_file("poses.txt", "5.25 -1 2.5 3 0.7071067811865476 0 0 0.7071067811865476\n"));
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_DOUBLE_EQ(poses[0].t, 5.25);
  EXPECT_DOUBLE_EQ(poses[0].pose.translation().x(), -1.0);
  EXPECT_DOUBLE_EQ(poses[0].pose.translation().y(), 2.5);
  EXPECT_DOUBLE_EQ(poses[0].pose.translation().z(), 3.0);
  const Eigen::Vector3d y_mapped = poses[0].pose.linear() * Eigen::Vector3d::UnitY();
  EXPECT_NEAR((y_mapped - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);  // y -> z
}

TEST_F(Tum, SlightlyNonUnitQuaternionIsNormalised) {
  const auto poses = read_tum(write_file("poses.txt", "1 0 0 0 0 0 0 1.0004\n"));
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_NEAR((poses[0].pose.linear() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
}

TEST_F(Tum, CommentsAndBlankLinesAreSkipped) {
  const std::string text = std::string("# timestamp tx ty tz qx qy qz qw\n") + "\n" + "1.0 " + kIdentityLine +
                           "\n" + "   \n" + "\t\r\n" + "# another comment\n" + "2.0 1 2 3 0 0 0 1\r\n" + "\n";
  const auto poses = read_tum(write_file("poses.txt", text));
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_DOUBLE_EQ(poses[0].t, 1.0);
  EXPECT_DOUBLE_EQ(poses[1].t, 2.0);
  EXPECT_DOUBLE_EQ(poses[1].pose.translation().z(), 3.0);
}

TEST_F(Tum, EmptyFileHasNoPoses) { EXPECT_TRUE(read_tum(write_file("poses.txt", "")).empty()); }

TEST_F(Tum, SevenNumbersNameFileAndLine) {
  const std::string msg = error_reading("# header\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
  EXPECT_THAT(msg, StartsWith(bad_path() + ":3: "));
}

TEST_F(Tum, NonNumbersAreRejected) {
  EXPECT_THAT(error_reading("1 0 0 0 0 0 0 1\n2 0 0 zero 0 0 0 1\n"), StartsWith(bad_path() + ":2: "));
  EXPECT_THAT(error_reading("t x y z qx qy qz qw\n"), StartsWith(bad_path() + ":1: "));
}

TEST_F(Tum, NonFiniteValuesAreRejected) {
  EXPECT_THAT(error_reading("1 0 0 0 0 0 0 1\n2 nan 0 0 0 0 0 1\n"), StartsWith(bad_path() + ":2: "));
  EXPECT_THAT(error_reading("1 0 0 inf 0 0 0 1\n"), StartsWith(bad_path() + ":1: "));
  EXPECT_THAT(error_reading("1 0 0 1e999 0 0 0 1\n"), StartsWith(bad_path() + ":1: "));
}

TEST_F(Tum, NonUnitQuaternionIsRejected) {
  const std::string msg = error_reading("1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 2\n");
  EXPECT_THAT(msg, StartsWith(bad_path() + ":2: "));
  EXPECT_THAT(msg, HasSubstr("quaternion"));
  EXPECT_THAT(error_reading("1 0 0 0 0 0 0 0\n"), StartsWith(bad_path() + ":1: "));
  // Rotation matrix entries instead of a quaternion (a KITTI-style line cut short).
  EXPECT_THAT(error_reading("1 1 0 0 0 0 1 0.5\n"), StartsWith(bad_path() + ":1: "));
}

TEST_F(Tum, BackwardsTimestampsAreRejected) {
  const std::string msg = error_reading("1 0 0 0 0 0 0 1\n3 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1\n");
  EXPECT_THAT(msg, StartsWith(bad_path() + ":3: "));
  EXPECT_THAT(msg, HasSubstr("backwards"));
  // Equal timestamps are allowed.
  EXPECT_EQ(read_tum(write_file("poses.txt", "1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n")).size(), 2u);
}

// A line with more than 8 fields is not a TUM line ("a malformed line ... is an InputError"),
// but read_tum reads the first 8 numbers and silently ignores the rest of the line.
TEST_F(Tum, ExtraFieldsAreRejected) {
  EXPECT_THAT(error_reading("1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1 5\n"), StartsWith(bad_path() + ":2: "));
  EXPECT_THAT(error_reading("1 0 0 0 0 0 0 1 garbage\n"), StartsWith(bad_path() + ":1: "));
}

// Issue 52: a word of the file was quoted raw and whole. Quoted printable: other bytes as \xNN,
// at most 40 bytes.
TEST_F(Tum, MessagesQuoteTheFilePrintable) {
  EXPECT_EQ(error_reading("1 0 0 \x1b[2J 0 0 0 1\n"),
            bad_path() + ":1: expected 8 numbers: t x y z qx qy qz qw, z is '\\x1b[2J'");
  EXPECT_EQ(error_reading("1 0 0 0 0 0 0 1 \xff\x01\n"),
            bad_path() + ":1: expected 8 numbers: t x y z qx qy qz qw, found more: '\\xff\\x01'");
  EXPECT_EQ(error_reading("1 0 0 0 0 0 0 1 " + std::string(100, 'x') + "\n"),
            bad_path() + ":1: expected 8 numbers: t x y z qx qy qz qw, found more: '" + std::string(40, 'x') +
                "...'");
}

TEST_F(Tum, MissingFileNamesTheFile) {
  const std::string path = (dir_ / "nope.txt").string();
  try {
    read_tum(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), StartsWith(path + ": "));
  }
}

// A number beyond a double names its field (a stream read it as "not 8 numbers").
TEST_F(Tum, NumbersBeyondADoubleNameTheirField) {
  EXPECT_EQ(error_reading("1 0 0 0 0 0 0 1\n2 1e400 0 0 0 0 0 1\n"),
            bad_path() + ":2: x is 1e400: out of the range of a double");
  EXPECT_EQ(error_reading("-1e999 0 0 0 0 0 0 1\n"),
            bad_path() + ":1: t is -1e999: out of the range of a double");
}

// Positions no place on Earth has (1e308 made eval divide by zero drawing the bird's-eye) are
// refused; UTM-sized positions, Unix stamps and a '+' sign are read.
TEST_F(Tum, PositionsBeyondAnyPlaceAreRefused) {
  EXPECT_EQ(error_reading("1 0 0 0 0 0 0 1\n2 0 1e308 0 0 0 0 1\n"),
            bad_path() + ":2: y is 1e308: not a coordinate within 1e8 m");
  EXPECT_EQ(error_reading("1 0 0 -2e8 0 0 0 1\n"),
            bad_path() + ":1: z is -2e8: not a coordinate within 1e8 m");
  const std::vector<StampedPose> utm = read_tum(write_file("poses.txt", "1.7e9 4.5e5 5.8e6 +12.5 0 0 0 1\n"));
  ASSERT_EQ(utm.size(), 1u);
  EXPECT_EQ(utm[0].t, 1.7e9);
  EXPECT_EQ(utm[0].pose.translation(), Eigen::Vector3d(4.5e5, 5.8e6, 12.5));
}

// A folder where the file should be says so (a stream opened it and read no poses).
TEST_F(Tum, AFolderIsNotAFile) {
  std::filesystem::create_directories(dir_ / "poses.txt");
  const std::string path = (dir_ / "poses.txt").string();
  try {
    read_tum(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": is a folder, not a file");
  }
}
