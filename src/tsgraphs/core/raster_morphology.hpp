#pragma once
/// Morphology on a raster for the occupancy-map import: the cells near a set of cells (a
/// dilation by a disc, exact Euclidean distances between cell centres through
/// core/grid_frame.hpp's distance transform), and the short gaps between cells of one kind
/// along rows, columns and diagonals (a closing by line segments, which bridges a dashed line's
/// gaps where a disc would not).
#include <cstdint>
#include <vector>

namespace tsgraphs {

/// The cells (cols x rows, index r * cols + c) within `radius` cells of a set cell of `mask`.
std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius);

/// The `gap` cells that lie on a run of gap cells along a row, a column or a diagonal with an
/// `end` cell at each end, the run no longer than `max_length` cells (a diagonal step counts
/// sqrt(2)): the gaps of a fringe between known cells, or of a wall seen in dashes. Cells that
/// are neither end nor gap break a run; the raster's edge is no end.
std::vector<std::uint8_t> bridge_gaps(const std::vector<std::uint8_t>& end,
                                      const std::vector<std::uint8_t>& gap, int cols, int rows,
                                      double max_length);

}  // namespace tsgraphs
