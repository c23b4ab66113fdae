// The evaluation raster: which cells a polygon covers, that polygons sharing an edge share no
// cell, keys in row order for negative coordinates too, and refusal of absurd polygons.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/eval/footprint_raster.hpp"

using namespace tsgraphs;
using namespace tsgraphs::eval;

namespace {

Polygon2 box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

}  // namespace

TEST(FootprintRaster, AnAlignedBoxCoversItsCellsExactly) {
  // 2 m x 1 m at 0.05 m: 40 x 20 cells, the first centred at (0.025, 0.025).
  const std::vector<CellKey> cells = raster_cells(box(0, 0, 2, 1));
  ASSERT_EQ(cells.size(), 800u);
  EXPECT_TRUE(std::is_sorted(cells.begin(), cells.end()));
  EXPECT_TRUE(cell_center(cells.front()).isApprox(Vec2(0.025, 0.025)));
  EXPECT_TRUE(cell_center(cells.back()).isApprox(Vec2(1.975, 0.975)));
  // Clockwise vertices give the same cells.
  Polygon2 cw = box(0, 0, 2, 1);
  std::reverse(cw.begin(), cw.end());
  EXPECT_EQ(raster_cells(cw), cells);
}

TEST(FootprintRaster, NeighboursSharingAnEdgeShareNoCell) {
  // The shared edges run through cell centres (x = 1.025, y = 0.525): each centre goes to one side.
  const auto left = raster_cells(box(0, 0, 1.025, 1)), right = raster_cells(box(1.025, 0, 2, 1));
  EXPECT_EQ(shared_cells(left, right), 0u);
  EXPECT_EQ(left.size() + right.size(), raster_cells(box(0, 0, 2, 1)).size());
  const auto low = raster_cells(box(0, 0, 2, 0.525)), high = raster_cells(box(0, 0.525, 2, 1));
  EXPECT_EQ(shared_cells(low, high), 0u);
  EXPECT_EQ(low.size() + high.size(), 800u);
}

TEST(FootprintRaster, NegativeCoordinatesAndRotatedRectangles) {
  const auto cells = raster_cells(box(-1, -0.5, 1, 0.5));
  EXPECT_EQ(cells.size(), 800u);
  EXPECT_TRUE(std::is_sorted(cells.begin(), cells.end()));
  EXPECT_TRUE(cell_center(cells.front()).isApprox(Vec2(-0.975, -0.475)));
  EXPECT_EQ(cell_center(cell_key(-3, 7), 0.5), Vec2(-1.25, 3.75));
  // A rotated 3 m x 2 m rectangle: about area / cell^2 cells, all inside it.
  OrientedRect r;
  r.center = Vec2(-4.3, 2.1);
  r.size = Vec2(3.0, 2.0);
  r.yaw = 0.4;
  const auto rotated = raster_cells(r.corners());
  EXPECT_NEAR(static_cast<double>(rotated.size()), 6.0 / (kRasterCell * kRasterCell), 60.0);
  for (const CellKey c : rotated) EXPECT_TRUE(r.contains(cell_center(c)));
}

TEST(FootprintRaster, SetOperations) {
  const auto a = raster_cells(box(0, 0, 1, 1)), b = raster_cells(box(0.5, 0, 1.5, 1));
  EXPECT_EQ(shared_cells(a, b), 200u);
  EXPECT_EQ(cell_intersection(a, b), raster_cells(box(0.5, 0, 1, 1)));
  EXPECT_EQ(cell_union(a, b), raster_cells(box(0, 0, 1.5, 1)));
}

TEST(FootprintRaster, DegenerateAndAbsurdPolygons) {
  EXPECT_TRUE(raster_cells({{0, 0}, {1, 1}}).empty());
  EXPECT_TRUE(raster_cells(box(0.01, 0.01, 0.02, 0.02)).empty());  // covers no cell centre
  EXPECT_THROW(raster_cells(box(0, 0, 1e4, 1e4)), std::invalid_argument);
  EXPECT_THROW(raster_cells({{0, 0}, {1, 0}, {std::nan(""), 1}}), std::invalid_argument);
  // A long thin strip is fine: its area, not its bounding box, counts.
  EXPECT_GT(raster_cells({{0, 0}, {400, 400}, {400, 400.1}, {0, 0.1}}).size(), 10000u);
}
