// KISS-ICP's adaptive threshold: the initial value, growth with the model deviation, and the
// minimum motion below which a scan teaches nothing.
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
