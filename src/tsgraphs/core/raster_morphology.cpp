#include "tsgraphs/core/raster_morphology.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "tsgraphs/core/grid_frame.hpp"

namespace tsgraphs {
namespace {

// Distances are exact square roots of integers, and lengths whole steps: this absorbs rounding.
constexpr double kSlack = 1e-4;

void check(std::size_t size, int cols, int rows, double length) {
  if (cols < 1 || rows < 1 || size != static_cast<std::size_t>(cols) * rows || !(length >= 0.0))
    throw std::invalid_argument(
        "raster morphology: a mask's size disagrees with the raster, or a negative length");
}

/// Marks the gap runs of one line of cells (indices `line`) that qualify (see bridge_gaps).
void bridge_line(const std::vector<std::size_t>& line, const std::vector<std::uint8_t>& end,
                 const std::vector<std::uint8_t>& gap, int max_cells, std::vector<std::uint8_t>* out) {
  long open = -1;  // the position after the last end cell, while only gap cells followed it
  for (std::size_t k = 0; k < line.size(); ++k) {
    const std::size_t i = line[k];
    if (end[i]) {
      const long run = open < 0 ? 0 : static_cast<long>(k) - open;
      if (run > 0 && run <= max_cells)
        for (std::size_t j = static_cast<std::size_t>(open); j < k; ++j) (*out)[line[j]] = 1;
      open = static_cast<long>(k) + 1;
    } else if (!gap[i]) {
      open = -1;
    }
  }
}

}  // namespace

std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& mask, int cols, int rows, double radius) {
  check(mask.size(), cols, rows, radius);
  GridFrame f;
  f.resolution = 1.0;
  f.cols = cols;
  f.rows = rows;
  std::vector<std::uint8_t> unset(mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) unset[i] = !mask[i];
  const std::vector<float> d = distance_transform(f, unset, false);
  std::vector<std::uint8_t> out(mask.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = d[i] <= radius + kSlack;
  return out;
}

std::vector<std::uint8_t> bridge_gaps(const std::vector<std::uint8_t>& end,
                                      const std::vector<std::uint8_t>& gap, int cols, int rows,
                                      double max_length) {
  check(end.size(), cols, rows, max_length);
  check(gap.size(), cols, rows, max_length);
  std::vector<std::uint8_t> out(end.size(), 0);
  const std::array<std::array<int, 2>, 4> directions = {{{1, 0}, {0, 1}, {1, 1}, {1, -1}}};
  std::vector<std::size_t> line;
  for (const auto& d : directions) {
    const int max_cells = static_cast<int>(std::floor(max_length / std::hypot(d[0], d[1]) + kSlack));
    if (max_cells < 1) continue;
    // Each line starts at a cell whose predecessor lies off the raster.
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        const int pc = c - d[0], pr = r - d[1];
        if (pc >= 0 && pr >= 0 && pc < cols && pr < rows) continue;
        line.clear();
        for (int cc = c, rr = r; cc >= 0 && rr >= 0 && cc < cols && rr < rows; cc += d[0], rr += d[1])
          line.push_back(static_cast<std::size_t>(rr) * cols + cc);
        bridge_line(line, end, gap, max_cells, &out);
      }
    }
  }
  return out;
}

}  // namespace tsgraphs
