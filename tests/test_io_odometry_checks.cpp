#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/odometry_checks.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

/// Scans 0.1 s apart walking along x at 1 m/s.
SequenceInfo walk(std::size_t n) {
  SequenceInfo info;
  for (std::size_t i = 0; i < n; ++i) {
    info.times.push_back(0.1 * static_cast<double>(i));
    Pose3 pose = Pose3::Identity();
    pose.translation() = Eigen::Vector3d(0.1 * static_cast<double>(i), 4.0e6, 0.5);  // a UTM-sized northing
    info.odometry.push_back(pose);
  }
  return info;
}

std::string error_of(const SequenceInfo& info) {
  return test::input_error_of([&] { check_odometry_motion(info, "seq"); });
}

}  // namespace

TEST(OdometryChecks, WalkingFarFromTheOriginAndNoOdometryPass) {
  EXPECT_NO_THROW(check_odometry_motion(walk(50), "seq"));
  EXPECT_NO_THROW(check_odometry_motion(SequenceInfo{}, "seq"));
  SequenceInfo repeated = walk(3);  // the same stamp twice, a short step: stamps from another clock
  repeated.times[2] = repeated.times[1];
  EXPECT_NO_THROW(check_odometry_motion(repeated, "seq"));
}

// Issue 18: an odometry line 5e7 m off (within the coordinate limit) ran into a bad_alloc of
// the ground's slope grid ("internal error", exit 1).
TEST(OdometryChecks, AJumpNoPlatformMakesIsAnInputErrorNamingTheScan) {
  SequenceInfo info = walk(10);
  info.odometry[4].translation().x() += 50.0;  // 50 m in 0.1 s
  EXPECT_EQ(error_of(info),
            "seq: odometry of scan 4 (t 0.4 s) is 50.1 m from the previous scan's, 0.1 s earlier: "
            "faster than any platform (100 m/s; corrupt pose?)");
  SequenceInfo slow = walk(10);
  slow.times[4] += 1.0;  // the same 50 m in 1.1 s: 45 m/s, a car park's car, allowed
  slow.odometry[4].translation().x() += 50.0;
  for (std::size_t i = 5; i < slow.times.size(); ++i) {
    slow.times[i] += 1.0;
    slow.odometry[i].translation().x() += 50.0;
  }
  EXPECT_NO_THROW(check_odometry_motion(slow, "seq"));
}

TEST(OdometryChecks, ARunWiderThanAnyBuildingIsAnInputError) {
  SequenceInfo info = walk(3);
  info.times[2] = 1000.0;  // slow enough, but 20 km away
  info.odometry[2].translation().x() = 2.0e4;
  EXPECT_THAT(
      error_of(info),
      StartsWith("seq: odometry of scan 2 (t 1000 s) is 20000 m from the first scan's: more than 10 km"));
}
