#include "tsgraphs/core/raster_regions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace tsgraphs {
namespace {

constexpr double kSaddleCut =
    0.1;  // cells cut off a corner the outline passes twice: well above the writer's 0.1 mm
constexpr int kBucketCells = 16;  // cells a side of the buckets that find meeting edges

using Cell = std::array<int, 2>;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Ring Douglas-Peucker state: the kept original indices of one outline, ascending.
struct Ring {
  const Polygon2* points = nullptr;
  std::vector<std::size_t> kept;
};

/// The vertex of the span (i, j) of a ring farthest from the segment i-j, as a span index
/// (i < k < j; indices past the ring's end wrap), and its distance; -1 when the span is empty.
std::pair<long, double> farthest_in_span(const Polygon2& p, std::size_t i, std::size_t j) {
  const std::size_t n = p.size();
  long best = -1;
  double worst = -1.0;
  for (std::size_t k = i + 1; k < j; ++k) {
    const double d = distance_to_segment(p[k % n], p[i % n], p[j % n]);
    if (d > worst) {
      worst = d;
      best = static_cast<long>(k);
    }
  }
  return {best, worst};
}

/// Douglas-Peucker of the span (i, j) of a ring, appending the kept vertices (no recursion:
/// outlines can be long).
void dp_span(const Polygon2& p, std::size_t i, std::size_t j, double tolerance,
             std::vector<std::size_t>* kept) {
  std::vector<std::pair<std::size_t, std::size_t>> pending = {{i, j}};
  while (!pending.empty()) {
    const auto [a, b] = pending.back();
    pending.pop_back();
    const auto [k, d] = farthest_in_span(p, a, b);
    if (k < 0 || d <= tolerance) continue;
    const std::size_t kk = static_cast<std::size_t>(k);
    kept->push_back(kk % p.size());
    pending.push_back({a, kk});
    pending.push_back({kk, b});
  }
}

/// The segments of the rings as they stand, each with its ring and position.
struct Segment {
  Vec2 a, b;
  std::size_t ring, pos;
};

bool edges_meet(const Segment& s, const Segment& t, const std::vector<Ring>& rings) {
  if (s.ring == t.ring) {
    const std::size_t m = rings[s.ring].kept.size();
    const bool next = (s.pos + 1) % m == t.pos, prev = (t.pos + 1) % m == s.pos;
    if (next || prev) {
      if (m < 3) return true;
      // Adjacent edges share a vertex: they meet elsewhere only by folding back on each other.
      const Vec2 shared = next ? s.b : s.a;
      const Vec2 e1 = (next ? s.a : s.b) - shared, e2 = (next ? t.b : t.a) - shared;
      return std::abs(cross(e1, e2)) <= 1e-12 * e1.norm() * e2.norm() && e1.dot(e2) > 0.0;
    }
  }
  return segments_intersect(s.a, s.b, t.a, t.b);
}

/// Pairs of meeting edges (ring, position) of all rings, found through square buckets.
std::vector<std::pair<const Segment*, const Segment*>> meeting_edges(const std::vector<Segment>& segs,
                                                                     const std::vector<Ring>& rings) {
  std::unordered_map<std::int64_t, std::vector<std::size_t>> buckets;
  const auto key = [](int bx, int by) {
    return (static_cast<std::int64_t>(bx) << 32) ^ static_cast<std::uint32_t>(by);
  };
  const auto bucket = [](double v) { return static_cast<int>(std::floor(v / kBucketCells)); };
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Segment& s = segs[i];
    const int x0 = bucket(std::min(s.a.x(), s.b.x())), x1 = bucket(std::max(s.a.x(), s.b.x()));
    const int y0 = bucket(std::min(s.a.y(), s.b.y())), y1 = bucket(std::max(s.a.y(), s.b.y()));
    for (int bx = x0; bx <= x1; ++bx)
      for (int by = y0; by <= y1; ++by) buckets[key(bx, by)].push_back(i);
  }
  std::vector<std::pair<const Segment*, const Segment*>> out;
  for (const auto& [k, ids] : buckets) {
    for (std::size_t u = 0; u < ids.size(); ++u) {
      for (std::size_t v = u + 1; v < ids.size(); ++v) {
        const Segment& s = segs[ids[u]];
        const Segment& t = segs[ids[v]];
        // Each pair once: in the bucket of the lower-left corner of their boxes' overlap.
        const double ox = std::max(std::min(s.a.x(), s.b.x()), std::min(t.a.x(), t.b.x()));
        const double oy = std::max(std::min(s.a.y(), s.b.y()), std::min(t.a.y(), t.b.y()));
        if (key(bucket(ox), bucket(oy)) != k) continue;
        if (edges_meet(s, t, rings)) out.emplace_back(&s, &t);
      }
    }
  }
  // Bucket order is the hash map's: sort so that the refinement is the same every run.
  std::sort(out.begin(), out.end(), [](const auto& p, const auto& q) {
    return std::tie(p.first->ring, p.first->pos, p.second->ring, p.second->pos) <
           std::tie(q.first->ring, q.first->pos, q.second->ring, q.second->pos);
  });
  return out;
}

/// Follows a region's outer outline along cell edges (see trace_outlines).
struct Tracer {
  const std::vector<int>& labels;
  int cols, rows;
  bool eight;

  bool in(int c, int r, int id) const {
    return c >= 0 && r >= 0 && c < cols && r < rows && labels[static_cast<std::size_t>(r) * cols + c] == id;
  }
  /// The cell touching vertex v on the side of direction (dx, dy) and side (sx, sy).
  static Cell cell_at(int vx, int vy, int dx, int dy, int sx, int sy) {
    return {vx + (dx + sx > 0 ? 0 : -1), vy + (dy + sy > 0 ? 0 : -1)};
  }

  Polygon2 trace(int id, std::size_t first) const {
    const int c0 = static_cast<int>(first % cols), r0 = static_cast<int>(first / cols);
    // The first cell (lowest row, then leftmost) has its bottom edge on the outer outline; walk
    // it eastwards with the region on the left: counter-clockwise.
    int vx = c0, vy = r0, dx = 1, dy = 0;
    Polygon2 out = {Vec2(vx, vy)};
    while (true) {
      vx += dx;
      vy += dy;
      const int lx = -dy, ly = dx;  // left of the direction
      const Cell al = cell_at(vx, vy, dx, dy, lx, ly), ar = cell_at(vx, vy, dx, dy, -lx, -ly);
      const bool in_l = in(al[0], al[1], id), in_r = in(ar[0], ar[1], id);
      int ndx = dx, ndy = dy;
      bool saddle = false;
      if (in_l && in_r) {
        ndx = -lx, ndy = -ly;  // right
      } else if (!in_l && !in_r) {
        ndx = lx, ndy = ly;  // left
      } else if (!in_l && in_r) {
        // Diagonal contact: pass to the cell ahead-right (8-connected) or keep round the cell
        // behind-left (4-connected). The outline comes here twice, so the corner is cut.
        saddle = true;
        ndx = eight ? -lx : lx;
        ndy = eight ? -ly : ly;
      }
      if (vx == c0 && vy == r0 && ndx == 1 && ndy == 0) break;
      const Vec2 v(vx, vy);
      if (saddle) {
        out.push_back(v - kSaddleCut * Vec2(dx, dy));
        out.push_back(v + kSaddleCut * Vec2(ndx, ndy));
      } else if (ndx != dx || ndy != dy) {
        out.push_back(v);
      }
      dx = ndx;
      dy = ndy;
    }
    return out;
  }
};

}  // namespace

std::vector<int> label_regions(const std::vector<std::uint8_t>& in, int cols, int rows, bool eight,
                               std::vector<std::size_t>* sizes) {
  std::vector<int> label(in.size(), -1);
  sizes->clear();
  std::vector<std::size_t> stack;
  static const int kDc[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  static const int kDr[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  const int n_dirs = eight ? 8 : 4;
  for (std::size_t start = 0; start < in.size(); ++start) {
    if (!in[start] || label[start] >= 0) continue;
    const int id = static_cast<int>(sizes->size());
    std::size_t count = 0;
    label[start] = id;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      ++count;
      const int c = static_cast<int>(i % cols), r = static_cast<int>(i / cols);
      for (int k = 0; k < n_dirs; ++k) {
        const int cc = c + kDc[k], rr = r + kDr[k];
        if (cc < 0 || rr < 0 || cc >= cols || rr >= rows) continue;
        const std::size_t j = static_cast<std::size_t>(rr) * cols + cc;
        if (in[j] && label[j] < 0) {
          label[j] = id;
          stack.push_back(j);
        }
      }
    }
    sizes->push_back(count);
  }
  return label;
}

std::vector<std::uint8_t> enclosed_regions(const std::vector<std::uint8_t>& in, int cols, int rows,
                                           double max_cells) {
  std::vector<std::size_t> sizes;
  const std::vector<int> parts = label_regions(in, cols, rows, true, &sizes);
  std::vector<std::uint8_t> enclosed(sizes.size(), 1);
  for (std::size_t k = 0; k < sizes.size(); ++k)
    if (static_cast<double>(sizes[k]) > max_cells) enclosed[k] = 0;
  const auto at = [&](int c, int r) { return parts[static_cast<std::size_t>(r) * cols + c]; };
  for (int c = 0; c < cols; ++c)
    for (int r : {0, rows - 1})
      if (at(c, r) >= 0) enclosed[static_cast<std::size_t>(at(c, r))] = 0;
  for (int r = 0; r < rows; ++r)
    for (int c : {0, cols - 1})
      if (at(c, r) >= 0) enclosed[static_cast<std::size_t>(at(c, r))] = 0;
  std::vector<std::uint8_t> out(in.size(), 0);
  for (std::size_t i = 0; i < in.size(); ++i)
    out[i] = parts[i] >= 0 && enclosed[static_cast<std::size_t>(parts[i])] ? 1 : 0;
  return out;
}

std::vector<Polygon2> trace_outlines(const std::vector<int>& labels, int cols, int rows, int n_regions,
                                     bool eight_connected) {
  std::vector<std::size_t> first(n_regions, std::numeric_limits<std::size_t>::max());
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const int id = labels[i];
    if (id >= 0 && id < n_regions && first[id] == std::numeric_limits<std::size_t>::max()) first[id] = i;
  }
  const Tracer tracer{labels, cols, rows, eight_connected};
  std::vector<Polygon2> out(n_regions);
  for (int id = 0; id < n_regions; ++id) {
    if (first[id] != std::numeric_limits<std::size_t>::max()) out[id] = tracer.trace(id, first[id]);
  }
  return out;
}

std::vector<Polygon2> simplify_outlines(const std::vector<Polygon2>& outlines, double tolerance) {
  std::vector<Ring> rings(outlines.size());
  for (std::size_t r = 0; r < outlines.size(); ++r) {
    const Polygon2& p = outlines[r];
    Ring& ring = rings[r];
    ring.points = &p;
    const std::size_t n = p.size();
    if (n <= 4) {
      for (std::size_t i = 0; i < n; ++i) ring.kept.push_back(i);
      continue;
    }
    // Split the ring at vertex 0 and the vertex farthest from it; each half keeps at least its
    // farthest vertex, so the outline never collapses to a line.
    std::size_t far = 0;
    for (std::size_t i = 1; i < n; ++i) {
      if ((p[i] - p[0]).squaredNorm() > (p[far] - p[0]).squaredNorm()) far = i;
    }
    ring.kept = {0, far};
    const std::array<std::pair<std::size_t, std::size_t>, 2> halves = {{{0, far}, {far, n}}};
    for (const auto& [a, b] : halves) {
      const auto [k, d] = farthest_in_span(p, a, b);
      if (k < 0) continue;
      const std::size_t kk = static_cast<std::size_t>(k);
      ring.kept.push_back(kk % n);
      dp_span(p, a, kk, tolerance, &ring.kept);
      dp_span(p, kk, b, tolerance, &ring.kept);
    }
    std::sort(ring.kept.begin(), ring.kept.end());
    ring.kept.erase(std::unique(ring.kept.begin(), ring.kept.end()), ring.kept.end());
  }
  // Put dropped vertices back where simplified edges meet, until none do.
  for (std::size_t round = 0;; ++round) {
    std::vector<Segment> segs;
    for (std::size_t r = 0; r < rings.size(); ++r) {
      const Ring& ring = rings[r];
      const std::size_t m = ring.kept.size();
      for (std::size_t i = 0; i < m; ++i)
        segs.push_back({(*ring.points)[ring.kept[i]], (*ring.points)[ring.kept[(i + 1) % m]], r, i});
    }
    const auto meets = meeting_edges(segs, rings);
    if (meets.empty()) break;
    std::vector<std::vector<std::size_t>> add(rings.size());
    bool refined = false;
    for (const auto& [s, t] : meets) {
      for (const Segment* e : {s, t}) {
        const Ring& ring = rings[e->ring];
        const std::size_t n = ring.points->size(), m = ring.kept.size();
        const std::size_t a = ring.kept[e->pos];
        std::size_t b = ring.kept[(e->pos + 1) % m];
        if (b <= a) b += n;
        const auto [k, d] = farthest_in_span(*ring.points, a, b);
        if (k < 0) continue;
        add[e->ring].push_back(static_cast<std::size_t>(k) % n);
        refined = true;
      }
    }
    if (!refined) throw std::logic_error("simplify_outlines: the outlines given meet each other");
    for (std::size_t r = 0; r < rings.size(); ++r) {
      if (add[r].empty()) continue;
      std::vector<std::size_t>& kept = rings[r].kept;
      kept.insert(kept.end(), add[r].begin(), add[r].end());
      std::sort(kept.begin(), kept.end());
      kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    }
  }
  std::vector<Polygon2> out(rings.size());
  for (std::size_t r = 0; r < rings.size(); ++r) {
    for (std::size_t i : rings[r].kept) out[r].push_back((*rings[r].points)[i]);
  }
  return out;
}

}  // namespace tsgraphs
