#include "tsgraphs/core/rect.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

double distance(const OrientedRect& r, const Vec2& p) {
  const Vec2 d = p - r.center;
  const double c = std::cos(r.yaw), s = std::sin(r.yaw);
  const double a = std::max(std::abs(c * d.x() + s * d.y()) - 0.5 * r.size.x(), 0.0);
  const double b = std::max(std::abs(-s * d.x() + c * d.y()) - 0.5 * r.size.y(), 0.0);
  return std::hypot(a, b);
}

double distance(const OrientedRect& r, const Vec2& a, const Vec2& b) {
  if (r.contains(a) || r.contains(b)) return 0.0;
  const Polygon2 k = r.corners();
  double d = std::numeric_limits<double>::infinity();
  // Apart, the nearest points are an end of the segment and a side, or a corner and the segment.
  for (std::size_t i = 0; i < k.size(); ++i) {
    const Vec2& p = k[i];
    const Vec2& q = k[(i + 1) % k.size()];
    if (segments_intersect(a, b, p, q)) return 0.0;
    d = std::min(
        {d, distance_to_segment(p, a, b), distance_to_segment(a, p, q), distance_to_segment(b, p, q)});
  }
  return d;
}

double distance(const OrientedRect& a, const OrientedRect& b) {
  const Polygon2 k = b.corners();
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < k.size(); ++i) d = std::min(d, distance(a, k[i], k[(i + 1) % k.size()]));
  // Apart or crossing, the sides tell; one wholly inside the other meets no side of it.
  return a.contains(b.center) || b.contains(a.center) ? 0.0 : d;
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

OrientedRect min_area_rect(const std::vector<Vec2>& points) {
  OrientedRect best;
  if (!points.empty()) best.center = points.front();
  const Polygon2 hull = convex_hull(points);
  if (hull.size() < 3) return best;
  double best_area = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 u = (hull[(i + 1) % hull.size()] - hull[i]).normalized();
    const Vec2 v(-u.y(), u.x());
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec2& p : hull) {
      const Vec2 q(u.dot(p), v.dot(p));
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const Vec2 size = hi - lo;
    if (size.x() * size.y() >= best_area) continue;
    best_area = size.x() * size.y();
    const Vec2 mid = 0.5 * (lo + hi);
    best.center = u * mid.x() + v * mid.y();
    const bool along_u = size.x() >= size.y();  // x axis along the longer side
    best.size = along_u ? size : Vec2(size.y(), size.x());
    best.yaw = along_u ? std::atan2(u.y(), u.x()) : std::atan2(v.y(), v.x());
  }
  return best;
}

double dice(const Polygon2& a, const Polygon2& b) {
  const double total = area(a) + area(b);
  return total > 0.0 ? 2.0 * intersection_area(a, b) / total : 0.0;
}

double iou(const Polygon2& a, const Polygon2& b) {
  const double inter = intersection_area(a, b);
  const double uni = area(a) + area(b) - inter;
  return uni > 0.0 ? inter / uni : 0.0;
}

}  // namespace tsgraphs
