// Odometry drift: zero noise gives truth; the spread over many seeds matches the model.
#include <gtest/gtest.h>

#include <cmath>

#include "tsgraphs/sim/odometry_drift.hpp"

using namespace tsgraphs;
using namespace tsgraphs::sim;
using namespace tsgraphs::scene;

namespace {

// Truth for a straight run of `length` m in steps of `step`, then a turn in place of `turn`.
std::vector<Pose3> straight_then_turn(double length, double step, double turn, int turn_steps) {
  std::vector<Pose3> truth;
  for (int k = 0; k * step <= length + 1e-9; ++k) truth.push_back(make_pose({k * step, 0.0, 0.5}, 0.0));
  for (int k = 1; k <= turn_steps; ++k) truth.push_back(make_pose({length, 0.0, 0.5}, turn * k / turn_steps));
  return truth;
}

struct Spread {
  Eigen::Vector3d pos_std;
  double yaw_std;
};

Spread spread(const std::vector<Pose3>& truth, const OdometryNoise& noise, int seeds) {
  Eigen::Vector3d s1 = Eigen::Vector3d::Zero(), s2 = Eigen::Vector3d::Zero();
  double y1 = 0, y2 = 0;
  for (int seed = 0; seed < seeds; ++seed) {
    const std::vector<Pose3> odom = drift_odometry(truth, noise, static_cast<std::uint64_t>(seed));
    const Pose3 err = truth.back().inverse() * odom.back();
    s1 += err.translation();
    s2 += err.translation().cwiseProduct(err.translation());
    const double ey = yaw_of(err);
    y1 += ey;
    y2 += ey * ey;
  }
  Spread s;
  s.pos_std = (s2 / seeds - (s1 / seeds).cwiseProduct(s1 / seeds)).cwiseSqrt();
  s.yaw_std = std::sqrt(y2 / seeds - (y1 / seeds) * (y1 / seeds));
  return s;
}

}  // namespace

TEST(OdometryDrift, NoNoiseIsTruth) {
  const auto truth = straight_then_turn(10.0, 0.1, M_PI, 20);
  const auto odom = drift_odometry(truth, {0.0, 0.0, 0.0}, 1);
  ASSERT_EQ(odom.size(), truth.size());
  for (std::size_t k = 0; k < truth.size(); ++k) EXPECT_TRUE(odom[k].isApprox(truth[k], 1e-9));
}

TEST(OdometryDrift, TranslationErrorGrowsWithTheSquareRootOfDistance) {
  // Only translation noise: after L metres each axis has std sigma * sqrt(L), whatever the
  // step; the along-track axis over a straight run is x.
  const double sigma = 0.05, length = 20.0;
  const int seeds = 400;
  for (const double step : {0.1, 0.5}) {
    const Spread s = spread(straight_then_turn(length, step, 0.0, 0), {sigma, 0.0, 0.0}, seeds);
    const double expected = sigma * std::sqrt(length);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(s.pos_std[a], expected, 0.12 * expected) << "axis " << a << " step " << step;
    EXPECT_NEAR(s.yaw_std, 0.0, 1e-12);
  }
}

TEST(OdometryDrift, YawErrorPerMetreAndPerRadian) {
  const int seeds = 400;
  const double length = 20.0, turn = 2 * M_PI;
  {
    const Spread s = spread(straight_then_turn(length, 0.1, 0.0, 0), {0.0, 0.0, 0.004}, seeds);
    EXPECT_NEAR(s.yaw_std, 0.004 * std::sqrt(length), 0.12 * 0.004 * std::sqrt(length));
    // The yaw error swings the position sideways (y), never along the track (x).
    EXPECT_GT(s.pos_std.y(), 0.0);
    EXPECT_LT(s.pos_std.x(), 0.2 * s.pos_std.y());
  }
  {
    // Per radian: a full turn in place, the straight part carrying no yaw noise per metre.
    const Spread s = spread(straight_then_turn(1.0, 0.1, turn, 40), {0.0, 0.02, 0.0}, seeds);
    EXPECT_NEAR(s.yaw_std, 0.02 * std::sqrt(turn), 0.12 * 0.02 * std::sqrt(turn));
  }
}

TEST(OdometryDrift, SeedDecidesTheDrift) {
  const auto truth = straight_then_turn(10.0, 0.1, 1.0, 10);
  const OdometryNoise noise{0.01, 0.01, 0.002};
  const auto a = drift_odometry(truth, noise, 7);
  const auto b = drift_odometry(truth, noise, 7);
  const auto c = drift_odometry(truth, noise, 8);
  EXPECT_TRUE(a.back().isApprox(b.back(), 0.0));
  EXPECT_FALSE(a.back().isApprox(c.back(), 1e-9));
  EXPECT_TRUE(a.front().isApprox(truth.front(), 0.0));
}
