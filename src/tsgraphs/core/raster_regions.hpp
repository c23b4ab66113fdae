#pragma once
/// Regions of a raster: connected labelling, outlines traced along cell edges, and their
/// simplification. Shared by the occupancy-map import and the room segmentation.
#include <cstdint>
#include <vector>

#include "tsgraphs/core/polygon.hpp"

namespace tsgraphs {

/// Labels the cells where `in` holds (cols x rows, index r * cols + c): 4- or 8-connected
/// regions numbered from 0 in the order of their first cell (index order); -1 elsewhere.
/// `sizes` gets each region's cell count.
std::vector<int> label_regions(const std::vector<std::uint8_t>& in, int cols, int rows, bool eight,
                               std::vector<std::size_t>* sizes);

/// The cells of the 8-connected regions of `in` that touch no border of the raster and have at
/// most `max_cells` cells: what the rest surrounds. Of the blocked cells of a map, what stands
/// free inside the building (furniture, a pillar) rather than its structure, which is joined to
/// what lies round it.
std::vector<std::uint8_t> enclosed_regions(const std::vector<std::uint8_t>& in, int cols, int rows,
                                           double max_cells);

/// The outer outlines of the 4-connected (eight_connected false) or 8-connected regions of
/// `mask` (cols x rows, row 0 at the bottom), traced along cell edges, counter-clockwise, in
/// cell units: the regions' ids are `labels` (one per cell, -1 outside every region), region k
/// gets outline k. Where a region touches itself diagonally the outline passes the corner
/// twice; both passes cut it a tenth of a cell short, so that every outline is a simple polygon.
std::vector<Polygon2> trace_outlines(const std::vector<int>& labels, int cols, int rows, int n_regions,
                                     bool eight_connected);

/// Douglas-Peucker on closed outlines with `tolerance`, together: where a simplified edge
/// would meet another (of any outline), the vertex the simplification dropped that is farthest
/// from it is put back, until no two edges meet. Outlines that are simple and disjoint stay so.
std::vector<Polygon2> simplify_outlines(const std::vector<Polygon2>& outlines, double tolerance);

}  // namespace tsgraphs
