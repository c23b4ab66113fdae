#pragma once
/// The room segmentation's bend cuts (room_segmentation.cpp): a corridor-like region cut into its
/// straight legs. Internal to the rooms module.
#include <cstdint>
#include <vector>

#include "tsgraphs/core/grid_frame.hpp"

namespace tsgraphs::rooms::segmentation_steps {

/// Region k of `lab` in its bounding box, one cell of margin round it (cell units), with what
/// is not the region: the outside (`outside`) and its holes (`parts`, `sizes`). A hole smaller
/// than a region (a pillar, a wall drawn round one) is something one walks round inside the
/// space, not what the space runs round: it neither narrows the width nor has corners.
struct RegionInBox {
  GridFrame box;
  int c0 = 0, r0 = 0;
  std::size_t cells = 0;
  std::vector<std::uint8_t> in;
  std::vector<int> parts;
  std::vector<std::size_t> sizes;
  int outside = -1;
  double width = 0.0;  ///< twice the largest clearance, holes smaller than a region filled (cells)
};

RegionInBox region_in_box(const GridFrame& f, const std::vector<int>& lab, int k, double min_cells);
/// Long for its width (its area at least `corridor_aspect` times the square of its width) and
/// no wider than `max_width` (cells): a passage, not a hall.
bool corridor_like(const RegionInBox& region, double corridor_aspect, double max_width);
/// Cuts each corridor-like region into its straight legs (cut_bends' comment in bend_cuts.cpp);
/// cut cells lose their label; returns whether any was cut.
bool cut_bends(const GridFrame& f, int n, double corridor_aspect, double max_width_cells, double min_cells,
               double tolerance_cells, double min_turn, const std::vector<Vec2>& wall_directions,
               std::vector<int>* label);

}  // namespace tsgraphs::rooms::segmentation_steps
