#pragma once
/// A raster over the xy plane and the exact distance transform on it: the one grid that the
/// simulator's walkable raster, the survey planner and the room segmentation share.
#include <cstdint>
#include <vector>

#include "tsgraphs/core/polygon.hpp"

namespace tsgraphs {

/// Cell (c, r) covers [origin + c res, origin + (c + 1) res) in x and likewise in y (r grows with y).
struct GridFrame {
  Vec2 origin = Vec2::Zero();
  double resolution = 0.05;
  int cols = 0, rows = 0;

  std::size_t size() const { return static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows); }
  std::size_t index(int c, int r) const { return static_cast<std::size_t>(r) * cols + c; }
  bool inside(int c, int r) const { return c >= 0 && r >= 0 && c < cols && r < rows; }
  Vec2 center(int c, int r) const { return origin + resolution * Vec2(c + 0.5, r + 0.5); }
  Vec2 center(std::size_t i) const { return center(static_cast<int>(i % cols), static_cast<int>(i / cols)); }
  /// The cell holding `p`; false when it lies outside the raster.
  bool cell_of(const Vec2& p, int* c, int* r) const;
  /// The frame covering the box [lo, hi] with `margin` metres around it.
  static GridFrame around(const Vec2& lo, const Vec2& hi, double resolution, double margin);
};

/// The exact Euclidean distance (m) from each cell's centre to the nearest blocked cell's centre
/// (`free[i] == 0`), Felzenszwalb and Huttenlocher's two-pass lower envelope. With
/// `border_blocked` the cells outside the raster count as blocked (a free cell on the border is
/// one cell from them), else as free (infinity where no cell is blocked).
std::vector<float> distance_transform(const GridFrame& frame, const std::vector<std::uint8_t>& free,
                                      bool border_blocked = true);

}  // namespace tsgraphs
