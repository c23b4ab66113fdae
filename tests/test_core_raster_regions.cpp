// raster_regions: connected labelling and the regions the rest of a raster surrounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>

#include "tsgraphs/core/raster_regions.hpp"

namespace tsgraphs {
namespace {

/// Rows top first, '#' set: the raster has row 0 at the bottom.
std::vector<std::uint8_t> raster(const std::vector<std::string>& rows) {
  const int h = static_cast<int>(rows.size()), w = static_cast<int>(rows[0].size());
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w * h), 0);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      out[static_cast<std::size_t>(r * w + c)] = rows[static_cast<std::size_t>(h - 1 - r)][c] == '#';
  return out;
}

TEST(RasterRegions, LabelsFourAndEightConnectedRegions) {
  const std::vector<std::uint8_t> in = raster({"#..", ".#.", "..#"});
  std::vector<std::size_t> sizes;
  const std::vector<int> four = label_regions(in, 3, 3, false, &sizes);
  EXPECT_EQ(sizes.size(), 3u);
  EXPECT_EQ(*std::max_element(four.begin(), four.end()), 2);
  label_regions(in, 3, 3, true, &sizes);
  EXPECT_EQ(sizes.size(), 1u);
}

TEST(RasterRegions, EnclosedRegionsAreTheSmallOnesTouchingNoBorder) {
  const std::vector<std::string> rows = {"##########", "#........#", "#.##.....#", "#.##..#..#",
                                         "#.....#..#", "#.....#..#", "#........#", "##########"};
  const std::vector<std::uint8_t> in = raster(rows);
  const int w = 10, h = 8;
  const auto at = [&](const std::vector<std::uint8_t>& m, int c, int top_row) {
    return m[static_cast<std::size_t>((h - 1 - top_row) * w + c)];
  };
  const std::vector<std::uint8_t> all = enclosed_regions(in, w, h, std::numeric_limits<double>::infinity());
  EXPECT_EQ(at(all, 2, 2), 1);  // the 2 x 2 block
  EXPECT_EQ(at(all, 6, 4), 1);  // the bar of 3
  EXPECT_EQ(at(all, 0, 0), 0);  // the frame touches the border
  EXPECT_EQ(at(all, 4, 4), 0);  // a free cell is in no region
  const std::vector<std::uint8_t> small = enclosed_regions(in, w, h, 3.0);
  EXPECT_EQ(at(small, 2, 2), 0);  // 4 cells: too large
  EXPECT_EQ(at(small, 6, 4), 1);
}

}  // namespace
}  // namespace tsgraphs
