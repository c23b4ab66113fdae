// Oriented rectangles: corners, containment, overlap area, Dice and IoU with known values.
#include <gtest/gtest.h>

#include <cmath>

#include "tsgraphs/core/rect.hpp"

using namespace tsgraphs;

namespace {

OrientedRect rect(double cx, double cy, double sx, double sy, double yaw = 0.0) {
  OrientedRect r;
  r.center = Vec2(cx, cy);
  r.size = Vec2(sx, sy);
  r.yaw = yaw;
  return r;
}

void expect_vec_near(const Vec2& a, const Vec2& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x(), b.x(), tol) << "got (" << a.transpose() << ") expected (" << b.transpose() << ")";
  EXPECT_NEAR(a.y(), b.y(), tol) << "got (" << a.transpose() << ") expected (" << b.transpose() << ")";
}

}  // namespace

TEST(OrientedRect, Area) {
  EXPECT_DOUBLE_EQ(rect(1, 2, 4, 2).area(), 8.0);
  EXPECT_DOUBLE_EQ(rect(1, 2, 4, 2, 0.7).area(), 8.0);
  EXPECT_DOUBLE_EQ(OrientedRect().area(), 0.0);
}

TEST(OrientedRect, CornersAxisAligned) {
  const Polygon2 c = rect(1, 2, 4, 2).corners();
  ASSERT_EQ(c.size(), 4u);
  expect_vec_near(c[0], Vec2(-1, 1));
  expect_vec_near(c[1], Vec2(3, 1));
  expect_vec_near(c[2], Vec2(3, 3));
  expect_vec_near(c[3], Vec2(-1, 3));
  EXPECT_NEAR(signed_area(c), 8.0, 1e-12);  // counter-clockwise
}

TEST(OrientedRect, CornersRotated) {
  // Yaw 90 deg: the rectangle's x axis (length 4) points along the map y axis.
  const Polygon2 c = rect(0, 0, 4, 2, M_PI / 2).corners();
  ASSERT_EQ(c.size(), 4u);
  expect_vec_near(c[0], Vec2(1, -2));
  expect_vec_near(c[1], Vec2(1, 2));
  expect_vec_near(c[2], Vec2(-1, 2));
  expect_vec_near(c[3], Vec2(-1, -2));
  EXPECT_NEAR(signed_area(c), 8.0, 1e-12);
  // Any yaw keeps them counter-clockwise, with the given area, around the centre.
  for (double yaw : {-3.0, -1.2, 0.3, 2.0, 3.1}) {
    const OrientedRect r = rect(5, -7, 3, 0.5, yaw);
    const Polygon2 k = r.corners();
    EXPECT_NEAR(signed_area(k), 1.5, 1e-12) << yaw;
    expect_vec_near(0.25 * (k[0] + k[1] + k[2] + k[3]), r.center);
    EXPECT_NEAR((k[1] - k[0]).norm(), 3.0, 1e-12);  // the first edge runs along the rect's x axis
    EXPECT_NEAR(std::atan2((k[1] - k[0]).y(), (k[1] - k[0]).x()), yaw, 1e-12);
  }
}

TEST(OrientedRect, Contains) {
  const OrientedRect r = rect(1, 2, 4, 2);
  EXPECT_TRUE(r.contains(Vec2(1, 2)));
  EXPECT_TRUE(r.contains(Vec2(2.9, 2.9)));
  EXPECT_TRUE(r.contains(Vec2(-0.9, 1.1)));
  EXPECT_FALSE(r.contains(Vec2(3.1, 2)));
  EXPECT_FALSE(r.contains(Vec2(1, 3.1)));
  EXPECT_FALSE(r.contains(Vec2(1, 0.9)));

  const OrientedRect rot = rect(0, 0, 4, 2, M_PI / 2);
  EXPECT_TRUE(rot.contains(Vec2(0, 1.9)));  // along its long axis (map y)
  EXPECT_TRUE(rot.contains(Vec2(0.9, -1.9)));
  EXPECT_FALSE(rot.contains(Vec2(1.9, 0)));  // outside its short axis (map x)
  EXPECT_FALSE(rot.contains(Vec2(0, 2.1)));

  const OrientedRect diag = rect(0, 0, 2, 2, M_PI / 4);  // a diamond with corners at distance sqrt 2
  EXPECT_TRUE(diag.contains(Vec2(1.4, 0)));
  EXPECT_FALSE(diag.contains(Vec2(0.9, 0.9)));
}

TEST(OrientedRectOverlap, IdenticalRectsOverlapFully) {
  const OrientedRect r = rect(1, 2, 4, 2, 0.3);
  EXPECT_NEAR(intersection_area(r, r), 8.0, 1e-9);
  EXPECT_NEAR(iou(r, r), 1.0, 1e-12);
  EXPECT_NEAR(dice(r, r), 1.0, 1e-12);
}

TEST(OrientedRectOverlap, DisjointRectsDoNotOverlap) {
  const OrientedRect a = rect(0, 0, 1, 1), b = rect(5, 0, 1, 1, 0.4);
  EXPECT_DOUBLE_EQ(intersection_area(a, b), 0.0);
  EXPECT_DOUBLE_EQ(iou(a, b), 0.0);
  EXPECT_DOUBLE_EQ(dice(a, b), 0.0);
}

TEST(OrientedRectOverlap, RectAndItselfRotatedByNinetyDegrees) {
  // A 4x2 rect and its 90 deg rotation about the centre overlap in the central 2x2 square.
  const OrientedRect a = rect(3, -1, 4, 2), b = rect(3, -1, 4, 2, M_PI / 2);
  EXPECT_NEAR(intersection_area(a, b), 4.0, 1e-9);
  EXPECT_NEAR(intersection_area(b, a), 4.0, 1e-9);
  EXPECT_NEAR(iou(a, b), 4.0 / 12.0, 1e-9);
  EXPECT_NEAR(dice(a, b), 2.0 * 4.0 / 16.0, 1e-9);
}

TEST(OrientedRectOverlap, SquareAndItsRotationBy45Degrees) {
  const OrientedRect a = rect(0, 0, 2, 2), b = rect(0, 0, 2, 2, M_PI / 4);
  EXPECT_NEAR(intersection_area(a, b), 8.0 * (std::sqrt(2.0) - 1.0), 1e-9);
}

TEST(OrientedRectOverlap, HalfOverlappingUnitSquares) {
  const OrientedRect a = rect(0, 0, 1, 1), b = rect(0.5, 0, 1, 1);
  EXPECT_NEAR(intersection_area(a, b), 0.5, 1e-12);
  EXPECT_NEAR(iou(a, b), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(dice(a, b), 0.5, 1e-12);
  // Symmetric.
  EXPECT_NEAR(iou(b, a), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(dice(b, a), 0.5, 1e-12);
}

TEST(OrientedRectOverlap, ContainedRect) {
  const OrientedRect small = rect(0, 0, 1, 1), big = rect(0.2, -0.1, 4, 4, 0.3);
  EXPECT_NEAR(intersection_area(small, big), 1.0, 1e-9);
  EXPECT_NEAR(intersection_area(big, small), 1.0, 1e-9);
  EXPECT_NEAR(iou(small, big), 1.0 / 16.0, 1e-9);
  EXPECT_NEAR(dice(small, big), 2.0 / 17.0, 1e-9);
}

TEST(OrientedRectOverlap, EmptyRectsGiveZeroNotNaN) {
  const OrientedRect empty = rect(0, 0, 0, 0), line = rect(0, 0, 3, 0), unit = rect(0, 0, 1, 1);
  for (const OrientedRect* a : {&empty, &line}) {
    for (const OrientedRect* b : {&empty, &line, &unit}) {
      EXPECT_EQ(intersection_area(*a, *b), 0.0);
      EXPECT_EQ(intersection_area(*b, *a), 0.0);
      const double i = iou(*a, *b), d = dice(*a, *b);
      EXPECT_FALSE(std::isnan(i));
      EXPECT_FALSE(std::isnan(d));
      EXPECT_EQ(i, 0.0);
      EXPECT_EQ(d, 0.0);
    }
  }
}

TEST(OrientedRect, Distances) {
  OrientedRect a;
  a.center = Vec2(0, 0);
  a.size = Vec2(2, 1);
  a.yaw = 0.0;
  EXPECT_DOUBLE_EQ(distance(a, Vec2(0.5, 0.2)), 0.0);  // inside
  EXPECT_DOUBLE_EQ(distance(a, Vec2(3, 0)), 2.0);
  EXPECT_NEAR(distance(a, Vec2(4, 4.5)), 5.0, 1e-12);  // from the corner (1, 0.5)
  EXPECT_NEAR(distance(a, Vec2(-3, 2), Vec2(3, 2)), 1.5, 1e-12);
  EXPECT_DOUBLE_EQ(distance(a, Vec2(-3, 0), Vec2(3, 0.1)), 0.0);  // crosses it
  OrientedRect b = a;
  b.center = Vec2(4, 0);
  b.yaw = M_PI / 4;  // a corner points at a: sqrt(1.25) from b's centre along -x
  EXPECT_NEAR(distance(a, b), 3.0 - std::sqrt(1.25) * std::cos(M_PI / 4 - std::atan2(0.5, 1.0)), 1e-9);
  b.center = Vec2(0.2, 0.1);  // inside a, crossing no side of it
  b.size = Vec2(0.2, 0.2);
  EXPECT_DOUBLE_EQ(distance(a, b), 0.0);
  EXPECT_DOUBLE_EQ(distance(b, a), 0.0);
}
