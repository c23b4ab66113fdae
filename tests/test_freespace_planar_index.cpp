// The planar index (a bucket grid of x-y projections): its answers are those of a search over
// every point, for radii below, at and above its cell, for queries inside and far outside the
// points, with points spread so far that the grid is coarsened, and with non-finite points.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "tsgraphs/freespace/planar_index.hpp"

namespace tsgraphs::freespace {
namespace {

std::vector<int> brute_force(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p,
                             double radius) {
  std::vector<int> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double dx = p.x() - points[i].x(), dy = p.y() - points[i].y();
    if (points[i].head<2>().allFinite() && dx * dx + dy * dy < radius * radius)
      out.push_back(static_cast<int>(i));
  }
  return out;
}

TEST(PlanarIndex, FindsWhatASearchOverEveryPointFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-8.0, 8.0), z(-3.0, 3.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i) {
    // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
    const double pz = z(rng), py = xy(rng), px = xy(rng);
    points.emplace_back(px, py, pz);
  }
  points.emplace_back(1.0, 1.0, 0.0);  // twice the same place: both are found
  points.emplace_back(1.0, 1.0, 2.0);
  points.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);  // never found
  const PlanarIndex index(points, 0.75);
  std::vector<int> found;
  std::size_t total = 0;
  for (const double radius : {0.1, 0.5, 0.75, 1.3, 3.0}) {
    for (int q = 0; q < 200; ++q) {
      const double py = 1.2 * xy(rng), px = 1.2 * xy(rng);  // the last argument first, as gcc drew them
      const Eigen::Vector3d p(px, py, 0.0);                 // some outside the points' box
      index.within(p, radius, found);
      EXPECT_EQ(found, brute_force(points, p, radius)) << "radius " << radius << " at " << p.transpose();
      total += found.size();
    }
  }
  EXPECT_GT(total, 1000u);  // the queries did find points
  index.within({1.0, 1.0, 0.0}, 0.01, found);
  EXPECT_EQ(found.size(), 2u);
  // Far away, at a radius of 0 or NaN, at a NaN place: nothing.
  index.within({1e300, -1e300, 0.0}, 1.0, found);
  EXPECT_TRUE(found.empty());
  index.within({1.0, 1.0, 0.0}, 0.0, found);
  EXPECT_TRUE(found.empty());
  index.within({1.0, 1.0, 0.0}, std::numeric_limits<double>::quiet_NaN(), found);
  EXPECT_TRUE(found.empty());
  index.within({std::numeric_limits<double>::quiet_NaN(), 1.0, 0.0}, 1.0, found);
  EXPECT_TRUE(found.empty());
}

TEST(PlanarIndex, PointsSpreadFarStillAnswerRightly) {
  // Two clusters 1e6 m apart: a grid of 0.5 m cells would have 4e12 cells; it is coarsened.
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 50; ++i) {
    points.emplace_back(0.1 * i, 0.0, 0.0);
    points.emplace_back(1e6 + 0.1 * i, 1e6, 0.0);
  }
  const PlanarIndex index(points, 0.5);
  std::vector<int> found;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d(1e6 + 2.5, 1e6 + 0.1, 0.0)}) {
    index.within(p, 0.5, found);
    EXPECT_EQ(found, brute_force(points, p, 0.5));
    EXPECT_FALSE(found.empty());
  }
}

TEST(PlanarIndex, VisitingStopsWhenAsked) {
  std::vector<Eigen::Vector3d> points(10, Eigen::Vector3d::Zero());
  const PlanarIndex index(points, 1.0);
  int calls = 0;
  index.visit_within(Eigen::Vector3d::Zero(), 1.0, [&](int) { return ++calls < 3; });
  EXPECT_EQ(calls, 3);
  EXPECT_THROW(PlanarIndex(points, 0.0), std::invalid_argument);
  EXPECT_TRUE([] {
    std::vector<int> found{1};
    PlanarIndex({}, 1.0).within(Eigen::Vector3d::Zero(), 1.0, found);
    return found.empty();
  }());
}

}  // namespace
}  // namespace tsgraphs::freespace
