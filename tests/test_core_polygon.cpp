// 2-D polygon geometry: area, containment, segment tests, simplicity, clipping and the
// trapezoid triangulation of regions with holes, touching and overlapping polygons.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "tsgraphs/core/polygon.hpp"

using namespace tsgraphs;

namespace {

Polygon2 box(double x0, double y0, double x1, double y1) {
  return {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};  // counter-clockwise
}

Polygon2 reversed(Polygon2 p) { return Polygon2(p.rbegin(), p.rend()); }

// L shape: [0,2]x[0,2] without the top right quarter [1,2]x[1,2]; area 3.
Polygon2 l_shape() { return {Vec2(0, 0), Vec2(2, 0), Vec2(2, 1), Vec2(1, 1), Vec2(1, 2), Vec2(0, 2)}; }

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double triangle_signed_area(const Triangle2& t) { return 0.5 * cross2(t[1] - t[0], t[2] - t[0]); }

double total_area(const std::vector<Triangle2>& tris) {
  double s = 0.0;
  for (const Triangle2& t : tris) s += std::abs(triangle_signed_area(t));
  return s;
}

bool in_region(const std::vector<Polygon2>& include, const std::vector<Polygon2>& exclude, const Vec2& p) {
  bool in = false;
  for (const Polygon2& poly : include) in = in || contains(poly, p);
  for (const Polygon2& poly : exclude) in = in && !contains(poly, p);
  return in;
}

double distance_to_outline(const Polygon2& poly, const Vec2& p) {
  double d = INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    d = std::min(d, distance_to_segment(p, poly[i], poly[(i + 1) % poly.size()]));
  }
  return d;
}

// Checks the triangulation of a region: total area, orientation, and that random points of the
// bounding box lie in exactly one triangle when inside the region and in none otherwise.
void check_triangulation(const std::vector<Polygon2>& include, const std::vector<Polygon2>& exclude,
                         double expected_area) {
  const std::vector<Triangle2> tris = triangulate_region(include, exclude);
  ASSERT_FALSE(tris.empty());
  EXPECT_NEAR(total_area(tris), expected_area, 1e-9);
  for (const Triangle2& t : tris) {
    EXPECT_GT(triangle_signed_area(t), 0.0)
        << "clockwise or degenerate triangle (" << t[0].transpose() << "), (" << t[1].transpose() << "), ("
        << t[2].transpose() << ")";
  }

  Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto* set : {&include, &exclude}) {
    for (const Polygon2& poly : *set) {
      for (const Vec2& v : poly) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
    }
  }
  lo -= Vec2(0.5, 0.5);
  hi += Vec2(0.5, 0.5);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> ux(lo.x(), hi.x()), uy(lo.y(), hi.y());
  constexpr double kMargin = 1e-7;
  int checked = 0, inside = 0;
  for (int k = 0; k < 4000; ++k) {
    // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
    const double py = uy(rng), px = ux(rng);
    const Vec2 p(px, py);
    // Skip points on (or numerically next to) any outline or triangle edge.
    bool near_edge = false;
    for (const auto* set : {&include, &exclude}) {
      for (const Polygon2& poly : *set) near_edge = near_edge || distance_to_outline(poly, p) < kMargin;
    }
    for (const Triangle2& t : tris) {
      near_edge = near_edge || distance_to_outline(Polygon2(t.begin(), t.end()), p) < kMargin;
    }
    if (near_edge) continue;
    int hits = 0;
    for (const Triangle2& t : tris) {
      if (cross2(t[1] - t[0], p - t[0]) > 0 && cross2(t[2] - t[1], p - t[1]) > 0 &&
          cross2(t[0] - t[2], p - t[2]) > 0) {
        ++hits;
      }
    }
    const bool expected = in_region(include, exclude, p);
    EXPECT_EQ(hits, expected ? 1 : 0) << "point (" << p.transpose() << ")";
    ++checked;
    inside += expected;
  }
  EXPECT_GT(checked, 3900);
  EXPECT_GT(inside, 100);  // the sampling did reach the region
}

}  // namespace

// ---------------------------------------------------------------- area and containment

TEST(PolygonArea, SignedAreaIsPositiveForCounterClockwise) {
  EXPECT_DOUBLE_EQ(signed_area(box(0, 0, 1, 1)), 1.0);
  EXPECT_DOUBLE_EQ(signed_area(reversed(box(0, 0, 1, 1))), -1.0);
  EXPECT_DOUBLE_EQ(signed_area({Vec2(0, 0), Vec2(4, 0), Vec2(0, 3)}), 6.0);
  EXPECT_DOUBLE_EQ(signed_area({Vec2(0, 0), Vec2(0, 3), Vec2(4, 0)}), -6.0);
  EXPECT_DOUBLE_EQ(area(reversed(box(2, 3, 5, 7))), 12.0);
  EXPECT_DOUBLE_EQ(signed_area(l_shape()), 3.0);
}

TEST(PolygonArea, SignedAreaDoesNotDependOnPosition) {
  Polygon2 p = l_shape();
  for (Vec2& v : p) v += Vec2(1000.0, -250.0);
  EXPECT_NEAR(signed_area(p), 3.0, 1e-9);
}

TEST(PolygonArea, DegeneratePolygonsHaveZeroArea) {
  EXPECT_DOUBLE_EQ(signed_area({}), 0.0);
  EXPECT_DOUBLE_EQ(signed_area({Vec2(1, 1)}), 0.0);
  EXPECT_DOUBLE_EQ(signed_area({Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)}), 0.0);
}

TEST(PolygonContains, InsideAndOutsideASquare) {
  const Polygon2 sq = box(0, 0, 1, 1);
  EXPECT_TRUE(contains(sq, Vec2(0.5, 0.5)));
  EXPECT_TRUE(contains(sq, Vec2(0.01, 0.99)));
  EXPECT_FALSE(contains(sq, Vec2(1.5, 0.5)));
  EXPECT_FALSE(contains(sq, Vec2(-0.1, 0.5)));
  EXPECT_FALSE(contains(sq, Vec2(0.5, 1.01)));
  EXPECT_FALSE(contains(sq, Vec2(0.5, -3.0)));
  // Orientation does not matter.
  EXPECT_TRUE(contains(reversed(sq), Vec2(0.5, 0.5)));
  EXPECT_FALSE(contains(reversed(sq), Vec2(1.5, 0.5)));
}

TEST(PolygonContains, ConcaveLShape) {
  const Polygon2 l = l_shape();
  EXPECT_TRUE(contains(l, Vec2(0.5, 0.5)));
  EXPECT_TRUE(contains(l, Vec2(1.5, 0.5)));   // bottom arm
  EXPECT_TRUE(contains(l, Vec2(0.5, 1.5)));   // left arm
  EXPECT_FALSE(contains(l, Vec2(1.5, 1.5)));  // the notch
  EXPECT_FALSE(contains(l, Vec2(1.01, 1.01)));
  EXPECT_FALSE(contains(l, Vec2(2.5, 0.5)));
  EXPECT_FALSE(contains(l, Vec2(0.5, 2.5)));
}

TEST(PolygonContains, EmptyPolygonContainsNothing) { EXPECT_FALSE(contains({}, Vec2(0, 0))); }

// ---------------------------------------------------------------- segments

TEST(PolygonSegments, DistanceToSegment) {
  const Vec2 a(-1, 0), b(1, 0);
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec2(0, 1), a, b), 1.0);     // above the middle
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec2(0.3, -2), a, b), 2.0);  // below, projects inside
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec2(4, 4), a, b), 5.0);     // beyond b: distance to b (3-4-5)
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec2(-4, -4), a, b), 5.0);   // beyond a
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec2(0.5, 0), a, b), 0.0);   // on the segment
  EXPECT_DOUBLE_EQ(distance_to_segment(Vec2(4, 5), Vec2(1, 1), Vec2(1, 1)), 5.0);  // degenerate segment
  // Diagonal segment: distance from the origin to the line x + y = 2 is sqrt(2).
  EXPECT_NEAR(distance_to_segment(Vec2(0, 0), Vec2(2, 0), Vec2(0, 2)), std::sqrt(2.0), 1e-12);
}

TEST(PolygonSegments, CrossingSegmentsReportTheCrossing) {
  Vec2 at(-99, -99);
  EXPECT_TRUE(segments_intersect(Vec2(0, 0), Vec2(2, 2), Vec2(0, 2), Vec2(2, 0), &at));
  EXPECT_NEAR(at.x(), 1.0, 1e-12);
  EXPECT_NEAR(at.y(), 1.0, 1e-12);
  EXPECT_TRUE(segments_intersect(Vec2(0, 0), Vec2(4, 0), Vec2(1, -1), Vec2(1, 3), &at));
  EXPECT_NEAR(at.x(), 1.0, 1e-12);
  EXPECT_NEAR(at.y(), 0.0, 1e-12);
}

TEST(PolygonSegments, TouchingAtAnEndpointCounts) {
  Vec2 at(-99, -99);
  EXPECT_TRUE(segments_intersect(Vec2(0, 0), Vec2(1, 0), Vec2(1, 0), Vec2(1, 1), &at));
  EXPECT_NEAR((at - Vec2(1, 0)).norm(), 0.0, 1e-12);
  // T junction: an endpoint of one segment in the middle of the other.
  EXPECT_TRUE(segments_intersect(Vec2(0, 0), Vec2(2, 0), Vec2(1, 0), Vec2(1, 1), &at));
  EXPECT_NEAR((at - Vec2(1, 0)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(segments_intersect(Vec2(1, 5), Vec2(1, 1), Vec2(0, 1), Vec2(3, 1), &at));
  EXPECT_NEAR((at - Vec2(1, 1)).norm(), 0.0, 1e-12);
}

TEST(PolygonSegments, DisjointSegmentsDoNotIntersect) {
  // Parallel, apart.
  EXPECT_FALSE(segments_intersect(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 1)));
  // Collinear, apart.
  EXPECT_FALSE(segments_intersect(Vec2(0, 0), Vec2(1, 0), Vec2(2, 0), Vec2(3, 0)));
  // The lines cross, the segments do not.
  EXPECT_FALSE(segments_intersect(Vec2(0, 0), Vec2(1, 0), Vec2(2, -1), Vec2(2, 1)));
  EXPECT_FALSE(segments_intersect(Vec2(0, 0), Vec2(1, 1), Vec2(3, 0), Vec2(2, 1)));
  // Almost touching.
  EXPECT_FALSE(segments_intersect(Vec2(0, 0), Vec2(1, 0), Vec2(1.001, 0), Vec2(1.001, 1)));
}

TEST(PolygonSegments, CollinearOverlappingSegmentsIntersect) {
  Vec2 at(-99, -99);
  EXPECT_TRUE(segments_intersect(Vec2(0, 0), Vec2(2, 0), Vec2(1, 0), Vec2(3, 0), &at));
  EXPECT_NEAR(at.y(), 0.0, 1e-12);
  EXPECT_GE(at.x(), 1.0 - 1e-12);  // a point of the overlap [1, 2]
  EXPECT_LE(at.x(), 2.0 + 1e-12);
  // Reversed direction, one inside the other.
  EXPECT_TRUE(segments_intersect(Vec2(0, 0), Vec2(0, 4), Vec2(0, 3), Vec2(0, 1), &at));
  EXPECT_NEAR(at.x(), 0.0, 1e-12);
  EXPECT_GE(at.y(), 1.0 - 1e-12);
  EXPECT_LE(at.y(), 3.0 + 1e-12);
  // Collinear and meeting end to end.
  EXPECT_TRUE(segments_intersect(Vec2(0, 0), Vec2(1, 1), Vec2(1, 1), Vec2(2, 2), &at));
  EXPECT_NEAR((at - Vec2(1, 1)).norm(), 0.0, 1e-12);
}

TEST(PolygonSegments, DegenerateSegments) {
  // A point segment against a proper one.
  EXPECT_TRUE(segments_intersect(Vec2(1, 0), Vec2(1, 0), Vec2(0, 0), Vec2(2, 0)));
  EXPECT_TRUE(segments_intersect(Vec2(0, 0), Vec2(2, 2), Vec2(1, 1), Vec2(1, 1)));
  EXPECT_FALSE(segments_intersect(Vec2(1, 0.5), Vec2(1, 0.5), Vec2(0, 0), Vec2(2, 0)));
  EXPECT_FALSE(segments_intersect(Vec2(0, 0), Vec2(2, 0), Vec2(3, 0), Vec2(3, 0)));
  // Two point segments.
  EXPECT_TRUE(segments_intersect(Vec2(1, 1), Vec2(1, 1), Vec2(1, 1), Vec2(1, 1)));
  EXPECT_FALSE(segments_intersect(Vec2(1, 1), Vec2(1, 1), Vec2(1, 2), Vec2(1, 2)));
}

TEST(PolygonSegments, LargeCoordinates) {
  const Vec2 o(5.0e5, -3.0e5);
  Vec2 at;
  EXPECT_TRUE(segments_intersect(o + Vec2(0, 0), o + Vec2(2, 2), o + Vec2(0, 2), o + Vec2(2, 0), &at));
  EXPECT_NEAR((at - (o + Vec2(1, 1))).norm(), 0.0, 1e-6);
  EXPECT_FALSE(segments_intersect(o + Vec2(0, 0), o + Vec2(1, 0), o + Vec2(0, 0.01), o + Vec2(1, 0.01)));
}

// ---------------------------------------------------------------- simplicity

TEST(PolygonSimplicity, SimplePolygonsHaveNoSelfIntersection) {
  EXPECT_FALSE(find_self_intersection(box(0, 0, 1, 1)).has_value());
  EXPECT_FALSE(find_self_intersection(reversed(box(0, 0, 1, 1))).has_value());
  EXPECT_FALSE(find_self_intersection(l_shape()).has_value());
  EXPECT_FALSE(find_self_intersection({Vec2(0, 0), Vec2(4, 0), Vec2(0, 3)}).has_value());
  // Collinear consecutive vertices are fine (a straight angle, not a fold).
  EXPECT_FALSE(
      find_self_intersection({Vec2(0, 0), Vec2(1, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)}).has_value());
}

TEST(PolygonSimplicity, BowTieIsFound) {
  const auto hit = find_self_intersection({Vec2(0, 0), Vec2(1, 1), Vec2(1, 0), Vec2(0, 1)});
  ASSERT_TRUE(hit.has_value());
  // Edge 0 (0,0)-(1,1) crosses edge 2 (1,0)-(0,1).
  EXPECT_EQ(hit->first, 0u);
  EXPECT_EQ(hit->second, 2u);
}

TEST(PolygonSimplicity, RepeatedVertexIsFound) {
  // Consecutive duplicate.
  const auto dup = find_self_intersection({Vec2(0, 0), Vec2(1, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)});
  ASSERT_TRUE(dup.has_value());
  EXPECT_EQ(dup->first, 1u);
  EXPECT_EQ(dup->second, 1u);
  // First vertex repeated at the end (the closing repeat that polygons must not carry).
  const auto closing = find_self_intersection({Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0, 0)});
  ASSERT_TRUE(closing.has_value());
  // The same vertex visited twice: a figure of eight pinched at (1, 1).
  EXPECT_TRUE(find_self_intersection({Vec2(0, 0), Vec2(2, 0), Vec2(1, 1), Vec2(2, 2), Vec2(0, 2), Vec2(1, 1)})
                  .has_value());
}

TEST(PolygonSimplicity, SpikeFoldingBackIsFound) {
  // A square with a spike going up from (4,0) to (4,4) and back down to (4,2).
  EXPECT_TRUE(find_self_intersection({Vec2(0, 0), Vec2(4, 0), Vec2(4, 4), Vec2(4, 2)}).has_value());
  // A spike through the closing edge: (0,4) up to (0,6), back down to (0,0).
  EXPECT_TRUE(
      find_self_intersection({Vec2(0, 0), Vec2(4, 0), Vec2(4, 4), Vec2(0, 4), Vec2(0, 6)}).has_value());
  // Degenerate triangles: only adjacent edges, which fold back on each other.
  const auto fold_mid = find_self_intersection({Vec2(0, 0), Vec2(2, 0), Vec2(1, 0)});
  ASSERT_TRUE(fold_mid.has_value());
  const auto fold_closing = find_self_intersection({Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)});
  ASSERT_TRUE(fold_closing.has_value());
  EXPECT_EQ(fold_closing->first, 0u);
  EXPECT_EQ(fold_closing->second, 2u);
}

TEST(PolygonSimplicity, EdgeTouchingAnotherEdgeIsFound) {
  // Vertex (2,0) of the "inner" dent lies on edge 0.
  EXPECT_TRUE(
      find_self_intersection({Vec2(0, 0), Vec2(4, 0), Vec2(4, 4), Vec2(2, 0), Vec2(0, 4)}).has_value());
}

// ---------------------------------------------------------------- clipping

TEST(PolygonClip, OverlappingSquares) {
  const Polygon2 out = clip_to_convex(box(0, 0, 2, 2), box(1, 1, 3, 3));
  EXPECT_NEAR(area(out), 1.0, 1e-12);
  for (const Vec2& v : out) {
    EXPECT_GE(v.x(), 1.0 - 1e-12);
    EXPECT_LE(v.x(), 2.0 + 1e-12);
    EXPECT_GE(v.y(), 1.0 - 1e-12);
    EXPECT_LE(v.y(), 2.0 + 1e-12);
  }
  // Either orientation of the clip polygon.
  EXPECT_NEAR(area(clip_to_convex(box(0, 0, 2, 2), reversed(box(1, 1, 3, 3)))), 1.0, 1e-12);
  EXPECT_NEAR(area(clip_to_convex(box(0, 0, 2, 2), box(0.5, -1, 1.5, 5))), 2.0, 1e-12);
}

TEST(PolygonClip, ContainedAndDisjoint) {
  EXPECT_NEAR(area(clip_to_convex(box(1, 1, 2, 2), box(0, 0, 5, 5))), 1.0, 1e-12);
  EXPECT_NEAR(area(clip_to_convex(box(0, 0, 5, 5), box(1, 1, 2, 2))), 1.0, 1e-12);
  EXPECT_NEAR(area(clip_to_convex(box(0, 0, 1, 1), box(3, 3, 4, 4))), 0.0, 1e-12);
}

TEST(PolygonClip, ConcaveSubject) {
  // The L shape clipped to [0.5,1.5]^2: the unit square less the notch quarter [1,1.5]^2.
  EXPECT_NEAR(area(clip_to_convex(l_shape(), box(0.5, 0.5, 1.5, 1.5))), 0.75, 1e-12);
}

TEST(PolygonClip, SquareAndItsRotationBy45Degrees) {
  // A 2x2 square and the same square rotated by 45 deg about its centre meet in a regular
  // octagon of area 8 (sqrt 2 - 1).
  const double r = std::sqrt(2.0);
  const Polygon2 diamond = {Vec2(r, 0), Vec2(0, r), Vec2(-r, 0), Vec2(0, -r)};
  EXPECT_NEAR(area(clip_to_convex(box(-1, -1, 1, 1), diamond)), 8.0 * (std::sqrt(2.0) - 1.0), 1e-12);
}

// ---------------------------------------------------------------- triangulation

TEST(PolygonTriangulate, Square) { check_triangulation({box(0, 0, 4, 4)}, {}, 16.0); }

TEST(PolygonTriangulate, ClockwiseSquare) { check_triangulation({reversed(box(0, 0, 4, 4))}, {}, 16.0); }

TEST(PolygonTriangulate, LShape) { check_triangulation({l_shape()}, {}, 3.0); }

TEST(PolygonTriangulate, TriangleAndSlantedQuad) {
  check_triangulation({{Vec2(0, 0), Vec2(4, 0), Vec2(1, 3)}}, {}, 6.0);
  const Polygon2 quad = {Vec2(0, 0), Vec2(5, 1), Vec2(4, 4), Vec2(-1, 3)};
  check_triangulation({quad}, {}, signed_area(quad));
}

TEST(PolygonTriangulate, SquareWithASquareHole) {
  check_triangulation({box(0, 0, 4, 4)}, {box(1, 1, 3, 3)}, 16.0 - 4.0);
  check_triangulation({box(0, 0, 4, 4)}, {reversed(box(1, 1, 3, 3))}, 16.0 - 4.0);
}

TEST(PolygonTriangulate, HoleTouchingTheBorder) {
  check_triangulation({box(0, 0, 4, 4)}, {box(0, 1, 2, 3)}, 16.0 - 4.0);  // shares the left edge
  check_triangulation({box(0, 0, 4, 4)}, {box(1, 0, 3, 4)}, 16.0 - 8.0);  // cuts the square in two
  check_triangulation({box(0, 0, 4, 4)}, {box(2, 2, 4, 4)}, 16.0 - 4.0);  // a corner
}

TEST(PolygonTriangulate, HolePartlyOutside) {
  check_triangulation({box(0, 0, 4, 4)}, {box(3, 1, 5, 2)}, 15.0);
}

TEST(PolygonTriangulate, TwoOverlappingHoles) {
  // Holes of 4 each overlapping in a unit square: their union is 7.
  check_triangulation({box(0, 0, 6, 6)}, {box(1, 1, 3, 3), box(2, 2, 4, 4)}, 36.0 - 7.0);
}

TEST(PolygonTriangulate, OverlappingIncludesGiveTheirUnion) {
  check_triangulation({box(0, 0, 2, 2), box(1, 1, 3, 3)}, {}, 7.0);
  check_triangulation({box(0, 0, 2, 2), box(0, 0, 2, 2)}, {}, 4.0);  // the same polygon twice
  // A square and a diamond whose edges cross the square's at non-vertex heights.
  const Polygon2 sq = box(0, 0, 2, 2);
  const Polygon2 diamond = {Vec2(3.5, 1), Vec2(2, 2.5), Vec2(0.5, 1), Vec2(2, -0.5)};
  const double inter = area(clip_to_convex(sq, diamond));
  ASSERT_GT(inter, 0.5);
  check_triangulation({sq, diamond}, {}, 4.0 + 4.5 - inter);
}

TEST(PolygonTriangulate, TouchingIncludes) {
  check_triangulation({box(0, 0, 2, 2), box(2, 0, 4, 2)}, {}, 8.0);  // side by side
  check_triangulation({box(0, 0, 2, 2), box(2, 2, 4, 4)}, {}, 8.0);  // corner to corner
}

TEST(PolygonTriangulate, HoleInAnIncludeThatIsCoveredByAnother) {
  // The hole of polygon set "exclude" wins over every include.
  check_triangulation({box(0, 0, 4, 4), box(1, 1, 3, 3)}, {box(1.5, 1.5, 2.5, 2.5)}, 15.0);
}

TEST(PolygonTriangulate, SelfCrossingIncludeUsesEvenOdd) {
  // A bow-tie covers two triangles of area 1 each.
  check_triangulation({{Vec2(0, 0), Vec2(2, 2), Vec2(2, 0), Vec2(0, 2)}}, {}, 2.0);
}

TEST(PolygonTriangulate, RotatedAndShiftedLShapeWithAHole) {
  const double c = std::cos(0.5), sn = std::sin(0.5);
  auto move = [&](Polygon2 p) {
    for (Vec2& v : p) v = Vec2(c * v.x() - sn * v.y(), sn * v.x() + c * v.y()) * 3.0 + Vec2(1000.0, -500.0);
    return p;
  };
  // L of area 3 scaled by 3 (area 27), less a hole of 0.5 x 0.5 scaled (area 2.25).
  check_triangulation({move(l_shape())}, {move(box(0.25, 0.25, 0.75, 0.75))}, 27.0 - 2.25);
}

TEST(PolygonTriangulate, ConcaveStar) {
  Polygon2 star;
  for (int i = 0; i < 14; ++i) {
    const double a = 2.0 * M_PI * i / 14.0, r = (i % 2) ? 1.0 : 3.0;
    star.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  ASSERT_FALSE(find_self_intersection(star).has_value());
  check_triangulation({star}, {}, signed_area(star));
  check_triangulation({star}, {box(-0.5, -0.5, 0.5, 0.5)}, signed_area(star) - 1.0);
}

TEST(PolygonTriangulate, EmptyInputsGiveNoTriangles) {
  EXPECT_TRUE(triangulate_region({}).empty());
  EXPECT_TRUE(triangulate_region({}, {box(0, 0, 1, 1)}).empty());
  EXPECT_TRUE(triangulate_region({box(0, 0, 1, 1)}, {box(-1, -1, 2, 2)}).empty());  // all cut away
}
