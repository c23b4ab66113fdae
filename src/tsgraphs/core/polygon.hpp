#pragma once
/// 2-D polygon geometry: area, containment, simplicity, clipping and triangulation of
/// regions with holes. Polygons are vertex lists without the closing repeat.
#include <cmath>
#include <Eigen/Core>
#include <array>
#include <optional>
#include <utility>
#include <vector>

namespace tsgraphs {

using Vec2 = Eigen::Vector2d;
using Polygon2 = std::vector<Vec2>;
using Triangle2 = std::array<Vec2, 3>;

/// Shoelace area, positive for counter-clockwise vertex order.
double signed_area(const Polygon2& poly);
inline double area(const Polygon2& poly) { return std::abs(signed_area(poly)); }

/// The area centroid of a simple polygon (its first vertex when the area is zero).
Vec2 centroid(const Polygon2& poly);

/// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
Polygon2 convex_hull(std::vector<Vec2> points);

/// Even-odd point-in-polygon test (points on the boundary may go either way).
bool contains(const Polygon2& poly, const Vec2& p);

/// Distance from p to the segment [a, b].
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b);

/// True when the closed segments [a, b] and [c, d] share a point; `at` gets one of them.
bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2* at = nullptr);

/// A pair of edge indices (edge i joins vertex i and i+1) of a polygon that is not simple:
/// two non-adjacent edges that touch, adjacent edges that fold back, or a repeated vertex.
/// std::nullopt when the polygon is simple.
std::optional<std::pair<std::size_t, std::size_t>> find_self_intersection(const Polygon2& poly);

/// Intersection of `subject` with a convex polygon `clip` (Sutherland-Hodgman).
Polygon2 clip_to_convex(const Polygon2& subject, const Polygon2& clip);

/// Area shared by two simple polygons (either may be concave).
double intersection_area(const Polygon2& a, const Polygon2& b);

/// Triangles that exactly cover the union of `include` minus the union of `exclude`
/// (each polygon read with the even-odd rule). Counter-clockwise triangles; the region is
/// cut into horizontal trapezoids, so holes, touching and overlapping polygons all work.
std::vector<Triangle2> triangulate_region(const std::vector<Polygon2>& include,
                                          const std::vector<Polygon2>& exclude = {});

}  // namespace tsgraphs
