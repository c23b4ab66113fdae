#include "tsgraphs/core/raster_morphology.hpp"

#include <cmath>
#include <stdexcept>

#include "tsgraphs/core/grid_frame.hpp"

namespace tsgraphs {
namespace {

// Distances are exact square roots of integers; this absorbs their float rounding.
constexpr float kDistanceSlack = 1e-4f;

void check(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius) {
  if (cols < 1 || rows < 1 || mask.size() != static_cast<std::size_t>(cols) * rows || !(radius >= 0.0))
    throw std::invalid_argument("raster morphology: the mask's size disagrees with the raster, or a negative radius");
}

/// Distance (cells) from each cell to the nearest cell where `source` holds.
std::vector<float> distance_to(const std::vector<std::uint8_t>& source, int cols, int rows, bool border_is_source) {
  GridFrame f;
  f.resolution = 1.0;
  f.cols = cols;
  f.rows = rows;
  std::vector<std::uint8_t> open(source.size());
  for (std::size_t i = 0; i < source.size(); ++i) open[i] = !source[i];
  return distance_transform(f, open, border_is_source);
}

}  // namespace

std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius) {
  check(mask, cols, rows, radius);
  const std::vector<float> d = distance_to(mask, cols, rows, false);
  std::vector<std::uint8_t> out(mask.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = d[i] <= static_cast<float>(radius) + kDistanceSlack;
  return out;
}

std::vector<std::uint8_t> erode(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius) {
  check(mask, cols, rows, radius);
  std::vector<std::uint8_t> unset(mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) unset[i] = !mask[i];
  const std::vector<float> d = distance_to(unset, cols, rows, true);
  std::vector<std::uint8_t> out(mask.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = mask[i] && d[i] > static_cast<float>(radius) + kDistanceSlack;
  return out;
}

std::vector<std::uint8_t> close(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius) {
  check(mask, cols, rows, radius);
  const int pad = static_cast<int>(std::ceil(radius)) + 1;
  const int pc = cols + 2 * pad, pr = rows + 2 * pad;
  std::vector<std::uint8_t> padded(static_cast<std::size_t>(pc) * pr, 0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      padded[static_cast<std::size_t>(r + pad) * pc + c + pad] = mask[static_cast<std::size_t>(r) * cols + c];
  const std::vector<std::uint8_t> closed = erode(dilate(padded, pc, pr, radius), pc, pr, radius);
  std::vector<std::uint8_t> out(mask.size());
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * cols + c;
      out[i] = mask[i] || closed[static_cast<std::size_t>(r + pad) * pc + c + pad];
    }
  return out;
}

}  // namespace tsgraphs
