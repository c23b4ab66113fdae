// Dilation, erosion and closing by a disc: distances between cell centres, the channel widths
// a closing fills, and nothing seen beyond the raster's edge.
#include <gtest/gtest.h>

#include <numeric>
#include <string>
#include <vector>

#include "tsgraphs/core/raster_morphology.hpp"

using namespace tsgraphs;

namespace {

/// A mask from rows of text (any row order: the operations are symmetric): '#' set.
std::vector<std::uint8_t> mask(const std::vector<std::string>& rows, int* cols, int* n_rows) {
  *n_rows = static_cast<int>(rows.size());
  *cols = static_cast<int>(rows.front().size());
  std::vector<std::uint8_t> out;
  for (const std::string& r : rows)
    for (char ch : r) out.push_back(ch == '#');
  return out;
}

std::size_t count(const std::vector<std::uint8_t>& m) { return std::accumulate(m.begin(), m.end(), std::size_t{0}); }

/// Two 8 x 12 set blocks with a channel of `gap` unset columns between them, and unset margins.
std::vector<std::uint8_t> blocks_with_channel(int gap, int* cols, int* rows) {
  *cols = 4 + 8 + gap + 8 + 4;
  *rows = 20;
  std::vector<std::uint8_t> m(static_cast<std::size_t>(*cols) * *rows, 0);
  for (int r = 4; r < 16; ++r)
    for (int c = 4; c < *cols - 4; ++c) m[static_cast<std::size_t>(r) * *cols + c] = c < 12 || c >= 12 + gap;
  return m;
}

}  // namespace

TEST(RasterMorphology, DilationAndErosionMeasureBetweenCellCentres) {
  int cols, rows;
  const std::vector<std::uint8_t> dot = mask({".....", ".....", "..#..", ".....", "....."}, &cols, &rows);
  EXPECT_EQ(count(dilate(dot, cols, rows, 1.0)), 5u);  // the diagonals are sqrt(2) away
  EXPECT_EQ(count(dilate(dot, cols, rows, 1.5)), 9u);
  EXPECT_EQ(count(dilate(dot, cols, rows, 2.0)), 13u);
  const std::vector<std::uint8_t> block = mask({".....", ".###.", ".###.", ".###.", "....."}, &cols, &rows);
  const std::vector<std::uint8_t> core = erode(block, cols, rows, 1.0);
  EXPECT_EQ(count(core), 1u);
  EXPECT_TRUE(core[2 * cols + 2]);
  // Beyond the raster counts as unset: a full raster erodes from its edge.
  const std::vector<std::uint8_t> full(25, 1);
  EXPECT_EQ(count(erode(full, 5, 5, 1.0)), 9u);
}

TEST(RasterMorphology, ClosingFillsChannelsUpToTwiceTheRadius) {
  for (const double radius : {1.0, 2.0, 3.0}) {
    for (int gap = 1; gap <= 8; ++gap) {
      int cols, rows;
      const std::vector<std::uint8_t> m = blocks_with_channel(gap, &cols, &rows);
      const std::vector<std::uint8_t> c = close(m, cols, rows, radius);
      const bool filled = c[static_cast<std::size_t>(10) * cols + 12 + gap / 2];  // mid-channel, mid-height
      EXPECT_EQ(filled, gap <= 2 * radius) << "radius " << radius << ", gap " << gap;
      for (std::size_t i = 0; i < m.size(); ++i) ASSERT_TRUE(!m[i] || c[i]);  // keeps every set cell
      // Nothing grows round the blocks' outer edges (straight edges and convex corners).
      for (int r = 0; r < rows; ++r)
        for (int col = 0; col < cols; ++col)
          if (r < 4 || r >= 16 || col < 4 || col >= cols - 4) ASSERT_FALSE(c[static_cast<std::size_t>(r) * cols + col]);
    }
  }
}

TEST(RasterMorphology, ClosingSeesNothingBeyondTheRastersEdge) {
  int cols, rows;
  // Set cells along the raster's edge, a pocket open to it: the closing is the one the same
  // cells get inside a larger raster with nothing set round them.
  const std::vector<std::uint8_t> m =
      mask({"###########", "###########", "###.....###", "###.....###", "###.....###"}, &cols, &rows);
  const int pad = 5, big_cols = cols + 2 * pad, big_rows = rows + 2 * pad;
  std::vector<std::uint8_t> big(static_cast<std::size_t>(big_cols) * big_rows, 0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) big[static_cast<std::size_t>(r + pad) * big_cols + c + pad] = m[r * cols + c];
  for (const double radius : {1.0, 2.0, 3.0}) {
    const std::vector<std::uint8_t> small = close(m, cols, rows, radius), wide = close(big, big_cols, big_rows, radius);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c)
        EXPECT_EQ(small[r * cols + c], wide[static_cast<std::size_t>(r + pad) * big_cols + c + pad]) << radius;
  }
  EXPECT_FALSE(close(m, cols, rows, 1.0)[4 * cols + 5]);  // the pocket's mouth stays open
  const std::vector<std::uint8_t> lone = mask({"#....", ".....", "....."}, &cols, &rows);
  EXPECT_EQ(close(lone, cols, rows, 2.0), lone);
  EXPECT_THROW(close(lone, cols, rows + 1, 1.0), std::invalid_argument);
}
