// Ground-truth rooms of an imported map as regions: the joint closing (pieces joined, gaps
// between rooms left), contacts given up by the later room, pieces beyond the closing left out
// and counted, holes filled unless they hold another room, which a slit opens instead; the
// outlines traced from the regions are simple and never overlap.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/core/raster_regions.hpp"
#include "tsgraphs/map_import/map_rooms.hpp"

using namespace tsgraphs;
using namespace tsgraphs::map_import;

namespace {

/// Per-cell rooms from rows of text, the first line the top row: 'a' room 0, 'b' room 1, ...;
/// anything else none.
struct Labels {
  int cols = 0, rows = 0;
  std::vector<int> room;
  int at(const std::vector<int>& v, int c, int r_from_top) const {
    return v[static_cast<std::size_t>(rows - 1 - r_from_top) * cols + c];
  }
};

Labels labels(const std::vector<std::string>& top_first) {
  Labels l;
  l.rows = static_cast<int>(top_first.size());
  l.cols = static_cast<int>(top_first.front().size());
  l.room.assign(static_cast<std::size_t>(l.cols) * l.rows, -1);
  for (int j = 0; j < l.rows; ++j)
    for (int c = 0; c < l.cols; ++c) {
      const char ch = top_first[j][c];
      if (ch >= 'a' && ch <= 'z') l.room[static_cast<std::size_t>(l.rows - 1 - j) * l.cols + c] = ch - 'a';
    }
  return l;
}

/// A rectangle of room `k` (columns [c0, c1), rows [r0, r1) from the top) on a blank raster.
void fill(Labels* l, int c0, int r0, int c1, int r1, int k) {
  for (int r = r0; r < r1; ++r)
    for (int c = c0; c < c1; ++c) l->room[static_cast<std::size_t>(l->rows - 1 - r) * l->cols + c] = k;
}

Labels blank(int cols, int rows) {
  Labels l;
  l.cols = cols;
  l.rows = rows;
  l.room.assign(static_cast<std::size_t>(cols) * rows, -1);
  return l;
}

/// True when the cells of room `k` in `region` touch a cell of another room (8-neighbours).
bool touches_another(const std::vector<int>& region, int cols, int rows, int k) {
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      if (region[static_cast<std::size_t>(r) * cols + c] != k) continue;
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
          const int cc = c + dc, rr = r + dr;
          if (cc < 0 || rr < 0 || cc >= cols || rr >= rows) continue;
          const int j = region[static_cast<std::size_t>(rr) * cols + cc];
          if (j >= 0 && j != k) return true;
        }
    }
  return false;
}

}  // namespace

TEST(MapRooms, TheClosingJoinsARoomsPiecesAndLeavesFarOnesOut) {
  // Room a: two 10 x 10 pieces 4 cells apart, and a 3 x 3 piece 12 cells beyond; a closing of
  // radius 3 (a 6-cell gap) joins the first two only.
  Labels l = blank(60, 20);
  fill(&l, 2, 5, 12, 15, 0);
  fill(&l, 16, 5, 26, 15, 0);
  fill(&l, 38, 8, 41, 11, 0);
  const MapRoomRegions reg = room_regions(l.room, 1, l.cols, l.rows, 3.0);
  EXPECT_EQ(reg.slits, 0);
  EXPECT_EQ(reg.labelled_out, std::vector<std::size_t>{9});  // the far piece
  // Both pieces and the gap between them, less the corners the disc rounds off at its mouths.
  EXPECT_GE(reg.cells[0], 200u + 4u * 8u);
  EXPECT_LE(reg.cells[0], 200u + 4u * 10u);
  for (int c = 2; c < 26; ++c) EXPECT_EQ(l.at(reg.region, c, 10), 0) << c;
  EXPECT_EQ(l.at(reg.region, 39, 9), -1);
  // Without a closing the larger of the two first pieces (the first of equal ones) is kept.
  const MapRoomRegions raw = room_regions(l.room, 1, l.cols, l.rows, 0.0);
  EXPECT_EQ(raw.cells, std::vector<std::size_t>{100});
  EXPECT_EQ(l.at(raw.region, 5, 10), 0);
}

TEST(MapRooms, TheClosingNeverFillsBetweenTwoRooms) {
  // Rooms a and b 4 cells apart: each closed alone would fill that gap; together they leave it.
  Labels l = blank(40, 20);
  fill(&l, 2, 2, 18, 18, 0);
  fill(&l, 22, 2, 38, 18, 1);
  fill(&l, 8, 8, 12, 12, -1);  // a table in room a: filled
  const MapRoomRegions reg = room_regions(l.room, 2, l.cols, l.rows, 3.0);
  EXPECT_EQ(reg.cells, (std::vector<std::size_t>{256, 256}));
  for (int c = 18; c < 22; ++c) EXPECT_EQ(l.at(reg.region, c, 10), -1) << c;
  EXPECT_EQ(l.at(reg.region, 10, 10), 0);
}

TEST(MapRooms, TouchingRoomsKeepACellApartTheLaterGivingItUp) {
  // Colour labels: rooms a and b share an edge; c touches b only at a corner.
  const Labels l =
      labels({"..........", ".aaaabbbb.", ".aaaabbbb.", ".aaaabbbb.", ".........c", "........cc"});
  const MapRoomRegions reg = room_regions(l.room, 3, l.cols, l.rows, 0.0);
  EXPECT_EQ(reg.labelled_out, (std::vector<std::size_t>{0, 3, 1}));
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(touches_another(reg.region, l.cols, l.rows, k)) << k;
  EXPECT_EQ(l.at(reg.region, 4, 2), 0);
  EXPECT_EQ(l.at(reg.region, 5, 2), -1);  // b's column along a
  EXPECT_EQ(l.at(reg.region, 6, 2), 1);
  const std::vector<Polygon2> out =
      simplify_outlines(trace_outlines(reg.region, l.cols, l.rows, 3, true), 1.0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_FALSE(find_self_intersection(out[a]));
    for (int b = a + 1; b < 3; ++b)
      EXPECT_NEAR(intersection_area(out[a], out[b]), 0.0, 1e-9) << a << " " << b;
  }
}

TEST(MapRooms, AHoleHoldingAnotherRoomIsOpenedNotFilled) {
  // A ring corridor (a) round a block holding room b, and a furniture hole in the ring's corner.
  Labels l = blank(50, 40);
  fill(&l, 2, 2, 48, 38, 0);
  fill(&l, 12, 12, 38, 28, -1);  // the block
  fill(&l, 16, 16, 34, 24, 1);   // room b inside it
  fill(&l, 4, 4, 7, 7, -1);      // a 3 x 3 hole of nothing: filled
  const MapRoomRegions reg = room_regions(l.room, 2, l.cols, l.rows, 1.0);
  EXPECT_EQ(reg.slits, 1);
  EXPECT_EQ(l.at(reg.region, 5, 5), 0);
  EXPECT_EQ(reg.cells[1], 18u * 8u);
  EXPECT_EQ(reg.labelled_out[0], 10u);  // the slit: the ring's width, the shortest cut
  // The ring's outline leaves room b out: the polygons do not overlap, and b's centre is not in a's.
  const std::vector<Polygon2> out =
      simplify_outlines(trace_outlines(reg.region, l.cols, l.rows, 2, true), 1.0);
  EXPECT_FALSE(find_self_intersection(out[0]));
  EXPECT_FALSE(contains(out[0], Vec2(25.0, 20.0)));
  EXPECT_NEAR(intersection_area(out[0], out[1]), 0.0, 1e-9);
  // Simplified within a cell: the area is the region's within a cell along the outline.
  EXPECT_NEAR(area(out[0]), static_cast<double>(reg.cells[0]), 0.05 * reg.cells[0]);
  // Without room b the block is a hole of nothing: filled, no slit.
  fill(&l, 16, 16, 34, 24, -1);
  const MapRoomRegions solid = room_regions(l.room, 1, l.cols, l.rows, 1.0);
  EXPECT_EQ(solid.slits, 0);
  EXPECT_EQ(solid.cells[0], 46u * 36u);
}

TEST(MapRooms, BadInputIsRefused) {
  EXPECT_THROW(room_regions({0, 0, -1}, 1, 2, 2, 1.0), std::invalid_argument);
  EXPECT_THROW(room_regions({0, 1, -1, -1}, 1, 2, 2, 1.0), std::invalid_argument);
  EXPECT_THROW(room_regions({0, 0, 0, 0}, 1, 2, 2, -1.0), std::invalid_argument);
  const MapRoomRegions none = room_regions({-1, -1, -1, -1}, 0, 2, 2, 1.0);
  EXPECT_TRUE(none.cells.empty());
}
