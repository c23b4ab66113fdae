#include "tsgraphs/eval/footprint_raster.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>

namespace tsgraphs::eval {
namespace {

// Cell indices are biased into unsigned halves of the key so that key order is (y, x) order.
constexpr std::int64_t kBias = std::int64_t{1} << 31;

// An output iterator that only counts.
struct Counter {
  using iterator_category = std::output_iterator_tag;
  using value_type = void;
  using difference_type = std::ptrdiff_t;
  using pointer = void;
  using reference = void;
  std::size_t* n;
  Counter& operator*() { return *this; }
  Counter& operator++() { return *this; }
  Counter operator++(int) { return *this; }
  Counter& operator=(CellKey) {
    ++*n;
    return *this;
  }
};

}  // namespace

CellKey cell_key(int x, int y) {
  return (static_cast<CellKey>(static_cast<std::int64_t>(y) + kBias) << 32) |
         static_cast<CellKey>(static_cast<std::int64_t>(x) + kBias);
}

Vec2 cell_center(CellKey key, double cell) {
  const std::int64_t x = static_cast<std::int64_t>(key & 0xffffffffu) - kBias;
  const std::int64_t y = static_cast<std::int64_t>(key >> 32) - kBias;
  return {(static_cast<double>(x) + 0.5) * cell, (static_cast<double>(y) + 0.5) * cell};
}

std::vector<CellKey> raster_cells(const Polygon2& polygon, double cell) {
  std::vector<CellKey> cells;
  if (polygon.size() < 3) return cells;
  double x_min = std::numeric_limits<double>::infinity(), y_min = x_min, x_max = -x_min, y_max = -x_min;
  for (const Vec2& p : polygon) {
    if (!p.allFinite()) throw std::invalid_argument("polygon vertex is not finite");
    x_min = std::min(x_min, p.x());
    x_max = std::max(x_max, p.x());
    y_min = std::min(y_min, p.y());
    y_max = std::max(y_max, p.y());
  }
  // Cells whose centre (i + 0.5) c lies in the bounding box.
  const double i0 = std::ceil(x_min / cell - 0.5), i1 = std::floor(x_max / cell - 0.5);
  const double j0 = std::ceil(y_min / cell - 0.5), j1 = std::floor(y_max / cell - 0.5);
  if (i1 < i0 || j1 < j0) return cells;
  constexpr double kIndexLimit = static_cast<double>(kBias - 1);
  // The area bounds the cells made, the rows the time (a long thin strip is cheap).
  if (area(polygon) > kMaxRasterCells * cell * cell || j1 - j0 + 1 > kMaxRasterCells ||
      std::max(std::abs(i0), std::abs(i1)) > kIndexLimit ||
      std::max(std::abs(j0), std::abs(j1)) > kIndexLimit)
    throw std::invalid_argument("polygon too large to rasterise");

  std::vector<double> crossings;
  for (int j = static_cast<int>(j0); j <= static_cast<int>(j1); ++j) {
    const double yc = (j + 0.5) * cell;
    crossings.clear();
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      Vec2 a = polygon[k], b = polygon[(k + 1) % polygon.size()];
      if ((a.y() <= yc) == (b.y() <= yc)) continue;  // half-open in y: a centre on a bottom edge is inside
      if (a.y() > b.y()) std::swap(a, b);            // the same crossing whichever way the edge runs
      crossings.push_back(a.x() + (yc - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
      // Centres in [x0, x1): half-open in x as well.
      const int first = static_cast<int>(std::ceil(crossings[k] / cell - 0.5));
      const int end = static_cast<int>(std::ceil(crossings[k + 1] / cell - 0.5));
      for (int i = first; i < end; ++i) cells.push_back(cell_key(i, j));
    }
  }
  return cells;
}

std::size_t shared_cells(const std::vector<CellKey>& a, const std::vector<CellKey>& b) {
  std::size_t n = 0;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), Counter{&n});
  return n;
}

std::vector<CellKey> cell_intersection(const std::vector<CellKey>& a, const std::vector<CellKey>& b) {
  std::vector<CellKey> out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

std::vector<CellKey> cell_union(const std::vector<CellKey>& a, const std::vector<CellKey>& b) {
  std::vector<CellKey> out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

}  // namespace tsgraphs::eval
