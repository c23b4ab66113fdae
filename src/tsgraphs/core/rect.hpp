#pragma once
/// Oriented 2-D rectangle: the footprint of a room or corridor segment.
#include "tsgraphs/core/polygon.hpp"

namespace tsgraphs {

struct OrientedRect {
  Vec2 center = Vec2::Zero();
  Vec2 size = Vec2::Zero();  ///< extent along the rectangle's own x and y axes
  double yaw = 0.0;          ///< rotation of the rectangle's x axis from the map x axis, rad

  double area() const { return size.x() * size.y(); }
  /// Corners in counter-clockwise order.
  Polygon2 corners() const;
  bool contains(const Vec2& p) const;
};

/// Distance from a point to an oriented rectangle; 0 inside it.
double distance(const OrientedRect& r, const Vec2& p);
/// Distance from the segment [a, b] to an oriented rectangle; 0 when they meet.
double distance(const OrientedRect& r, const Vec2& a, const Vec2& b);
/// Distance between two oriented rectangles; 0 when they meet.
double distance(const OrientedRect& a, const OrientedRect& b);

/// Area of the intersection of two oriented rectangles.
double intersection_area(const OrientedRect& a, const OrientedRect& b);
/// Dice score 2|A n B| / (|A| + |B|); 0 when both are empty.
double dice(const OrientedRect& a, const OrientedRect& b);
/// Intersection over union; 0 when both are empty.
double iou(const OrientedRect& a, const OrientedRect& b);

/// The smallest-area rectangle enclosing `points` (rotating calipers over their convex hull);
/// its x axis runs along the longer side. Empty (zero size at the first point) for fewer than 3
/// points or collinear ones.
OrientedRect min_area_rect(const std::vector<Vec2>& points);

/// A footprint as a polygon: `outline` when it has one, else the rectangle's corners.
inline Polygon2 footprint_of(const OrientedRect& rect, const Polygon2& outline) {
  return outline.size() >= 3 ? outline : rect.corners();
}
/// Dice score of two simple polygons; 0 when both are empty.
double dice(const Polygon2& a, const Polygon2& b);
/// Intersection over union of two simple polygons; 0 when both are empty.
double iou(const Polygon2& a, const Polygon2& b);

}  // namespace tsgraphs
