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

/// Area of the intersection of two oriented rectangles.
double intersection_area(const OrientedRect& a, const OrientedRect& b);
/// Dice score 2|A n B| / (|A| + |B|); 0 when both are empty.
double dice(const OrientedRect& a, const OrientedRect& b);
/// Intersection over union; 0 when both are empty.
double iou(const OrientedRect& a, const OrientedRect& b);

}  // namespace tsgraphs
