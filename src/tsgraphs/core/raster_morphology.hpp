#pragma once
/// Binary morphology on a raster with a disc: dilation, erosion and closing, measured as the
/// exact Euclidean distance between cell centres (core/grid_frame.hpp's distance transform).
/// Shared by the occupancy-map import (bridging a laser map's fringe) and its room labels.
#include <cstdint>
#include <vector>

namespace tsgraphs {

/// The cells (cols x rows, index r * cols + c) within `radius` cells of a set cell of `mask`.
std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius);

/// The set cells of `mask` farther than `radius` cells from every cell that is not set. Cells
/// beyond the raster count as not set.
std::vector<std::uint8_t> erode(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius);

/// The closing (the dilation, then the erosion, by the same disc) of `mask`: it keeps every
/// set cell and adds the cells of gaps and notches too narrow for the disc: a channel of unset
/// cells g cells wide between two set areas is filled when g <= 2 radius. Computed on a raster
/// padded by the radius: the closing at the edge is what it would be on a larger raster with
/// nothing set beyond the edge.
std::vector<std::uint8_t> close(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius);

}  // namespace tsgraphs
