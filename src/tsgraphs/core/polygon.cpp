#include "tsgraphs/core/polygon.hpp"

#include <algorithm>
#include <cmath>

namespace tsgraphs {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

constexpr double kEps = 1e-12;

}  // namespace

double signed_area(const Polygon2& poly) {
  double s = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) s += cross(poly[i], poly[(i + 1) % n]);
  return 0.5 * s;
}

bool contains(const Polygon2& poly, const Vec2& p) {
  bool inside = false;
  for (std::size_t i = 0, n = poly.size(), j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

Vec2 centroid(const Polygon2& poly) {
  Vec2 c = Vec2::Zero();
  double a2 = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % n];
    const double w = p.x() * q.y() - q.x() * p.y();
    a2 += w;
    c += w * (p + q);
  }
  return std::abs(a2) > 0.0 ? Vec2(c / (3.0 * a2)) : poly.front();
}

Polygon2 convex_hull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  Polygon2 hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t pass = 0; pass < 2; ++pass) {  // lower hull, then upper
    const std::size_t start = k;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec2& p = pass == 0 ? points[i] : points[points.size() - 1 - i];
      while (k >= start + 2 && cross(hull[k - 1] - hull[k - 2], p - hull[k - 2]) <= 0.0) --k;
      hull[k++] = p;
    }
    --k;  // the last point starts the other half
  }
  hull.resize(k);
  return hull;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2* at) {
  const Vec2 r = b - a;
  const Vec2 s = d - c;
  const double denom = cross(r, s);
  const double scale = std::max({r.squaredNorm(), s.squaredNorm(), 1.0});
  if (std::abs(denom) <= kEps * scale) {
    // Parallel: they meet only when collinear and overlapping.
    if (std::abs(cross(c - a, r)) > 1e-9 * std::sqrt(scale)) return false;
    const double rr = r.squaredNorm();
    if (rr <= 0.0) return (a - c).norm() < 1e-9 || distance_to_segment(a, c, d) < 1e-9;
    const double t0 = (c - a).dot(r) / rr;
    const double t1 = (d - a).dot(r) / rr;
    const double lo = std::max(0.0, std::min(t0, t1));
    const double hi = std::min(1.0, std::max(t0, t1));
    if (lo > hi + 1e-12) return false;
    if (at) *at = a + lo * r;
    return true;
  }
  const double t = cross(c - a, s) / denom;
  const double u = cross(c - a, r) / denom;
  constexpr double tol = 1e-12;
  if (t < -tol || t > 1 + tol || u < -tol || u > 1 + tol) return false;
  if (at) *at = a + t * r;
  return true;
}

std::optional<std::pair<std::size_t, std::size_t>> find_self_intersection(const Polygon2& poly) {
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    if ((poly[i] - poly[(i + 1) % n]).norm() < 1e-9) return std::make_pair(i, i);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % n];
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec2& c = poly[j];
      const Vec2& d = poly[(j + 1) % n];
      const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
      if (adjacent) {
        // Adjacent edges share one vertex; they are bad only if they fold back on each other.
        const Vec2 shared = (j == i + 1) ? b : a;
        const Vec2 e1 = ((j == i + 1) ? a : b) - shared;
        const Vec2 e2 = ((j == i + 1) ? d : c) - shared;
        if (std::abs(cross(e1, e2)) < 1e-12 * e1.norm() * e2.norm() && e1.dot(e2) > 0)
          return std::make_pair(i, j);
        continue;
      }
      if (segments_intersect(a, b, c, d)) return std::make_pair(i, j);
    }
  }
  return std::nullopt;
}

Polygon2 clip_to_convex(const Polygon2& subject, const Polygon2& clip) {
  Polygon2 out = subject;
  const double orientation = signed_area(clip) >= 0.0 ? 1.0 : -1.0;
  for (std::size_t i = 0, n = clip.size(); i < n && !out.empty(); ++i) {
    const Vec2& a = clip[i];
    const Vec2& b = clip[(i + 1) % n];
    auto inside = [&](const Vec2& p) { return orientation * cross(b - a, p - a) >= 0.0; };
    Polygon2 in = std::move(out);
    out.clear();
    for (std::size_t k = 0, m = in.size(); k < m; ++k) {
      const Vec2& p = in[k];
      const Vec2& q = in[(k + 1) % m];
      const bool pin = inside(p);
      const bool qin = inside(q);
      if (pin) out.push_back(p);
      if (pin != qin) {
        const double dp = cross(b - a, p - a);
        const double dq = cross(b - a, q - a);
        out.push_back(p + (q - p) * (dp / (dp - dq)));
      }
    }
  }
  return out;
}

double intersection_area(const Polygon2& a, const Polygon2& b) {
  // Sutherland-Hodgman needs a convex clip: clip `a` by each triangle of `b`.
  double sum = 0.0;
  for (const Triangle2& t : triangulate_region({b})) sum += area(clip_to_convex(a, {t[0], t[1], t[2]}));
  return sum;
}

std::vector<Triangle2> triangulate_region(const std::vector<Polygon2>& include,
                                          const std::vector<Polygon2>& exclude) {
  struct Edge {
    Vec2 a, b;         // a.y() < b.y()
    std::size_t poly;  // index into the combined polygon list
  };
  std::vector<Edge> edges;
  std::vector<bool> is_include;
  std::vector<double> ys;
  auto add_polygons = [&](const std::vector<Polygon2>& polys, bool inc) {
    for (const Polygon2& poly : polys) {
      const std::size_t id = is_include.size();
      is_include.push_back(inc);
      for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
        Vec2 a = poly[i];
        Vec2 b = poly[(i + 1) % n];
        ys.push_back(a.y());
        if (a.y() == b.y()) continue;  // horizontal edges never cross a strip's middle
        if (a.y() > b.y()) std::swap(a, b);
        edges.push_back({a, b, id});
      }
    }
  };
  add_polygons(include, true);
  add_polygons(exclude, false);
  // Split strips where edges cross, so that inside a strip the left-to-right order holds.
  for (std::size_t i = 0; i < edges.size(); ++i) {
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      Vec2 at;
      if (segments_intersect(edges[i].a, edges[i].b, edges[j].a, edges[j].b, &at)) ys.push_back(at.y());
    }
  }
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end(), [](double p, double q) { return q - p < 1e-10; }), ys.end());

  std::vector<Triangle2> triangles;
  struct Crossing {
    double xm, x0, x1;
    std::size_t poly;
  };
  std::vector<Crossing> crossings;
  std::vector<int> parity(is_include.size());
  for (std::size_t s = 0; s + 1 < ys.size(); ++s) {
    const double y0 = ys[s];
    const double y1 = ys[s + 1];
    const double ym = 0.5 * (y0 + y1);
    crossings.clear();
    for (const Edge& e : edges) {
      if (e.a.y() >= ym || e.b.y() <= ym) continue;
      auto x_at = [&](double y) {
        return e.a.x() + (y - e.a.y()) * (e.b.x() - e.a.x()) / (e.b.y() - e.a.y());
      };
      crossings.push_back({x_at(ym), x_at(y0), x_at(y1), e.poly});
    }
    std::sort(crossings.begin(), crossings.end(),
              [](const Crossing& p, const Crossing& q) { return p.xm < q.xm; });
    std::fill(parity.begin(), parity.end(), 0);
    int n_inc = 0, n_exc = 0;
    bool in_region = false;
    const Crossing* left = nullptr;
    for (const Crossing& c : crossings) {
      parity[c.poly] ^= 1;
      const int delta = parity[c.poly] ? 1 : -1;
      (is_include[c.poly] ? n_inc : n_exc) += delta;
      const bool now = n_inc > 0 && n_exc == 0;
      if (now && !in_region) {
        left = &c;
      } else if (!now && in_region) {
        const Vec2 p0(left->x0, y0), p1(c.x0, y0), p2(c.x1, y1), p3(left->x1, y1);
        if (cross(p1 - p0, p2 - p0) > kEps) triangles.push_back({p0, p1, p2});
        if (cross(p2 - p0, p3 - p0) > kEps) triangles.push_back({p0, p2, p3});
      }
      in_region = now;
    }
  }
  return triangles;
}

}  // namespace tsgraphs
