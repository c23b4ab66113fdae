// KISS-ICP's adaptive threshold: the initial value, growth with the model deviation, rotations
// taken at the points' range, and the minimum motion below which a scan teaches nothing.
#include <gtest/gtest.h>

#include <stdexcept>

#include "tsgraphs/odometry/adaptive_threshold.hpp"

using namespace tsgraphs;
using tsgraphs::odometry::AdaptiveThreshold;
using tsgraphs::odometry::pose_displacement;

namespace {
constexpr double kInitial = 2.0;
constexpr double kMinMotion = 0.1;
constexpr double kMaxRange = 30.0;

Pose3 translation(double x) { return make_pose(Eigen::Vector3d(x, 0.0, 0.0), 0.0); }
}  // namespace

TEST(AdaptiveThreshold, StartsAtTheInitialValue) {
  const AdaptiveThreshold t(kInitial, kMinMotion, kMaxRange);
  EXPECT_DOUBLE_EQ(t.threshold(), kInitial);
  EXPECT_EQ(t.num_samples(), 0u);
}

TEST(AdaptiveThreshold, StandingStillTeachesNothing) {
  AdaptiveThreshold t(kInitial, kMinMotion, kMaxRange);
  t.update(translation(0.5), translation(0.01));  // large deviation, but the robot barely moved
  EXPECT_DOUBLE_EQ(t.threshold(), kInitial);
  EXPECT_EQ(t.num_samples(), 0u);
}

TEST(AdaptiveThreshold, GrowsWithLargerModelDeviations) {
  AdaptiveThreshold t(kInitial, kMinMotion, kMaxRange);
  const Pose3 motion = translation(1.0);
  t.update(translation(0.02), motion);
  const double small = t.threshold();
  EXPECT_NEAR(small, 0.02, 1e-12);  // the RMS of one sample
  t.update(translation(0.2), motion);
  const double larger = t.threshold();
  EXPECT_GT(larger, small);
  t.update(make_pose(Eigen::Vector3d::Zero(), 0.05), motion);  // a rotation error counts at max_range
  EXPECT_GT(t.threshold(), larger);
  EXPECT_EQ(t.num_samples(), 3u);
}

TEST(AdaptiveThreshold, ARotationCountsWhereTheScansPointsAre) {
  // A 5 degree sway, taken at the points' 4 m instead of max_range's 30 m: 0.35 m, not 2.6 m.
  const Pose3 motion = translation(0.6);
  const Pose3 sway = make_pose(Eigen::Vector3d::Zero(), 0.0, 5.0 * M_PI / 180.0);
  AdaptiveThreshold near(kInitial, kMinMotion, kMaxRange), far(kInitial, kMinMotion, kMaxRange);
  near.update(sway, motion, 4.0);
  far.update(sway, motion);
  EXPECT_NEAR(near.threshold(), pose_displacement(sway, 4.0), 1e-12);
  EXPECT_NEAR(far.threshold(), pose_displacement(sway, kMaxRange), 1e-12);
  EXPECT_LT(near.threshold(), 0.4);
  EXPECT_GT(far.threshold(), 2.5);
  // Whether the scan moved enough to teach is still judged at max_range.
  near.update(sway, translation(0.01), 4.0);
  EXPECT_EQ(near.num_samples(), 1u);
}

TEST(AdaptiveThreshold, DisplacementOfARotationIsItsChordAtMaxRange) {
  const double yaw = 0.1;
  EXPECT_NEAR(pose_displacement(make_pose(Eigen::Vector3d(0.3, 0.4, 0.0), yaw), kMaxRange),
              2.0 * kMaxRange * std::sin(yaw / 2.0) + 0.5, 1e-12);
}

TEST(AdaptiveThreshold, RejectsBadParameters) {
  EXPECT_THROW(AdaptiveThreshold(0.0, kMinMotion, kMaxRange), std::invalid_argument);
  EXPECT_THROW(AdaptiveThreshold(kInitial, -1.0, kMaxRange), std::invalid_argument);
  EXPECT_THROW(AdaptiveThreshold(kInitial, kMinMotion, 0.0), std::invalid_argument);
}
