#pragma once
/// The raster the ground-truth room figures are counted on (docs/metrics.md): cells of a
/// fixed grid anchored at the origin, so that every polygon rasterised at one cell size
/// shares its cells with every other, and overlaps are counts of shared cells.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/core/polygon.hpp"

namespace tsgraphs::eval {

/// Cell edge, m: IPA's maps are 0.05 m per pixel (metrics.md).
constexpr double kRasterCell = 0.05;
/// A polygon of more than this many cells of area (62,500 m^2 at 0.05 m), or spanning more rows,
/// is refused rather than rasterised: no room is that large, and a corrupt size must not
/// exhaust memory.
constexpr double kMaxRasterCells = 2.5e7;

/// Cell (x, y) covers [x c, (x + 1) c) x [y c, (y + 1) c) for the cell edge c. Keys order the
/// cells row by row (y, then x), so sorted key lists are sets.
using CellKey = std::uint64_t;
CellKey cell_key(int x, int y);
/// The centre of the cell `key` for the cell edge `cell`.
Vec2 cell_center(CellKey key, double cell = kRasterCell);

/// The cells whose centres lie inside `polygon` (even-odd rule; a centre on a left or bottom
/// edge is inside, on a right or top edge outside, so polygons that share an edge share no
/// cell), ascending. Throws std::invalid_argument for a non-finite vertex or a polygon
/// larger than kMaxRasterCells.
std::vector<CellKey> raster_cells(const Polygon2& polygon, double cell = kRasterCell);

/// Set operations on ascending key lists.
std::size_t shared_cells(const std::vector<CellKey>& a, const std::vector<CellKey>& b);
std::vector<CellKey> cell_intersection(const std::vector<CellKey>& a, const std::vector<CellKey>& b);
std::vector<CellKey> cell_union(const std::vector<CellKey>& a, const std::vector<CellKey>& b);

/// A room footprint in the truth frame on a named level (the ground truth's level names).
struct LevelFootprint {
  Polygon2 polygon;
  std::string level;
};

}  // namespace tsgraphs::eval
