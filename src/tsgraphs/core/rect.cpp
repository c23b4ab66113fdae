#include "tsgraphs/core/rect.hpp"

#include <cmath>

namespace tsgraphs {

Polygon2 OrientedRect::corners() const {
  const Vec2 ax(std::cos(yaw), std::sin(yaw));
  const Vec2 ay(-ax.y(), ax.x());
  const Vec2 hx = 0.5 * size.x() * ax;
  const Vec2 hy = 0.5 * size.y() * ay;
  return {center - hx - hy, center + hx - hy, center + hx + hy, center - hx + hy};
}

bool OrientedRect::contains(const Vec2& p) const {
  const Vec2 d = p - center;
  const double c = std::cos(yaw), s = std::sin(yaw);
  return std::abs(c * d.x() + s * d.y()) <= 0.5 * size.x() &&
         std::abs(-s * d.x() + c * d.y()) <= 0.5 * size.y();
}

double intersection_area(const OrientedRect& a, const OrientedRect& b) {
  if (a.area() <= 0.0 || b.area() <= 0.0) return 0.0;
  return area(clip_to_convex(a.corners(), b.corners()));
}

double dice(const OrientedRect& a, const OrientedRect& b) {
  const double total = a.area() + b.area();
  return total > 0.0 ? 2.0 * intersection_area(a, b) / total : 0.0;
}

double iou(const OrientedRect& a, const OrientedRect& b) {
  const double inter = intersection_area(a, b);
  const double uni = a.area() + b.area() - inter;
  return uni > 0.0 ? inter / uni : 0.0;
}

}  // namespace tsgraphs
