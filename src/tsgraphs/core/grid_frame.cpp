#include "tsgraphs/core/grid_frame.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsgraphs {
namespace {

// One pass of the 1-D squared distance transform (Felzenszwalb and Huttenlocher 2012) over
// f[0..n), in cells; v and z are scratch space.
void distance_transform_1d(const float* f, int n, float* out, std::vector<int>& v, std::vector<float>& z) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  v.resize(n);
  z.resize(n + 1);
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (!std::isfinite(f[q])) continue;
    float s = -kInf;
    while (k >= 0) {
      s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0f * (q - v[k]));
      if (s > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -kInf : s;
    z[k + 1] = kInf;
  }
  if (k < 0) {
    std::fill(out, out + n, kInf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < q) ++j;
    const float d = static_cast<float>(q - v[j]);
    out[q] = d * d + f[v[j]];
  }
}

}  // namespace

bool GridFrame::cell_of(const Vec2& p, int* c, int* r) const {
  const Vec2 q = (p - origin) / resolution;
  if (!(q.x() >= 0.0 && q.y() >= 0.0)) return false;
  *c = static_cast<int>(q.x());
  *r = static_cast<int>(q.y());
  return inside(*c, *r);
}

GridFrame GridFrame::around(const Vec2& lo, const Vec2& hi, double resolution, double margin) {
  GridFrame f;
  f.resolution = resolution;
  f.origin = lo - Vec2::Constant(margin);
  f.cols = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * margin) / resolution));
  f.rows = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * margin) / resolution));
  return f;
}

std::vector<float> distance_transform(const GridFrame& f, const std::vector<std::uint8_t>& free,
                                      bool border_blocked) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  // Blocked cells are the sources; one ring outside the raster stands for what lies beyond it.
  const int W = f.cols + 2, H = f.rows + 2;
  std::vector<float> d(static_cast<std::size_t>(W) * H, border_blocked ? 0.0f : kInf);
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c)
      d[static_cast<std::size_t>(r + 1) * W + c + 1] = free[f.index(c, r)] ? kInf : 0.0f;
  }
  std::vector<int> v;
  std::vector<float> z, col(H), out(std::max(W, H));
  for (int x = 0; x < W; ++x) {
    for (int y = 0; y < H; ++y) col[y] = d[static_cast<std::size_t>(y) * W + x];
    distance_transform_1d(col.data(), H, out.data(), v, z);
    for (int y = 0; y < H; ++y) d[static_cast<std::size_t>(y) * W + x] = out[y];
  }
  for (int y = 0; y < H; ++y) {
    float* row = &d[static_cast<std::size_t>(y) * W];
    distance_transform_1d(row, W, out.data(), v, z);
    std::copy(out.begin(), out.begin() + W, row);
  }
  std::vector<float> metres(f.size(), 0.0f);
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c)
      metres[f.index(c, r)] =
          static_cast<float>(std::sqrt(d[static_cast<std::size_t>(r + 1) * W + c + 1]) * f.resolution);
  }
  return metres;
}

}  // namespace tsgraphs
