// Planes in (n, d) form and pose helpers.
#include <gtest/gtest.h>

#include <cmath>

#include "tsgraphs/core/plane.hpp"
#include "tsgraphs/core/pose.hpp"

using namespace tsgraphs;

TEST(Plane, SignedDistanceAndTransform) {
  // The wall x = 4 facing -x (toward the origin).
  const Plane p = Plane::from_point_normal({4, 1, 2}, {-2, 0, 0});
  EXPECT_NEAR(p.n.norm(), 1.0, 1e-12);
  EXPECT_NEAR(p.signed_distance({0, 0, 0}), 4.0, 1e-12);
  EXPECT_NEAR(p.signed_distance({5, 3, 3}), -1.0, 1e-12);
  EXPECT_TRUE(p.closest_to_origin().isApprox(Eigen::Vector3d(4, 0, 0)));
  // Expressed in a frame A where B sits at (1, 2, 0) rotated 90 degrees: every point keeps its
  // distance.
  const Pose3 T_AB = make_pose({1, 2, 0}, M_PI / 2);
  const Plane q = p.transformed(T_AB);
  for (const Eigen::Vector3d& x :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(5, -3, 1), Eigen::Vector3d(4, 9, -2)}) {
    EXPECT_NEAR(q.signed_distance(T_AB * x), p.signed_distance(x), 1e-12);
  }
}

TEST(Pose, YawPitchAndWrap) {
  const Pose3 T = make_pose({1, 2, 3}, 0.7, 0.2);
  EXPECT_NEAR(yaw_of(T), 0.7, 1e-12);
  // Pitch about the body y axis tips the x axis down for a positive angle.
  EXPECT_LT(T.linear().col(0).z(), 0.0);
  EXPECT_NEAR(std::asin(-T.linear().col(0).z()), 0.2, 1e-12);
  EXPECT_NEAR(wrap_angle(3 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(wrap_angle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(wrap_angle(-0.5), -0.5, 1e-12);
  EXPECT_NEAR(wrap_angle(2 * M_PI + 0.25), 0.25, 1e-12);
}
