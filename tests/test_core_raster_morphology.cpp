// Raster morphology for the map import: the dilation by a disc measured between cell centres,
// and gaps bridged along rows, columns and diagonals up to a length, a dashed line's included.
#include <gtest/gtest.h>

#include <numeric>
#include <string>
#include <vector>

#include "tsgraphs/core/raster_morphology.hpp"

using namespace tsgraphs;

namespace {

/// Two masks from rows of text (the operations do not care which row is the top): 'E' an end
/// cell, '.' a gap cell, anything else neither.
void masks(const std::vector<std::string>& text, std::vector<std::uint8_t>* end,
           std::vector<std::uint8_t>* gap, int* cols, int* rows) {
  *rows = static_cast<int>(text.size());
  *cols = static_cast<int>(text.front().size());
  end->clear();
  gap->clear();
  for (const std::string& r : text)
    for (char ch : r) {
      end->push_back(ch == 'E');
      gap->push_back(ch == '.');
    }
}

std::size_t count(const std::vector<std::uint8_t>& m) {
  return std::accumulate(m.begin(), m.end(), std::size_t{0});
}

/// The bridged cells as text: 'x' bridged, the rest as given.
std::vector<std::string> show(const std::vector<std::string>& text,
                              const std::vector<std::uint8_t>& bridged) {
  std::vector<std::string> out = text;
  const int cols = static_cast<int>(text.front().size());
  for (std::size_t i = 0; i < bridged.size(); ++i)
    if (bridged[i]) out[i / cols][i % cols] = 'x';
  return out;
}

}  // namespace

TEST(RasterMorphology, DilationMeasuresBetweenCellCentres) {
  std::vector<std::uint8_t> dot(25, 0);
  dot[12] = 1;
  EXPECT_EQ(count(dilate(dot, 5, 5, 1.0)), 5u);  // the diagonals are sqrt(2) away
  EXPECT_EQ(count(dilate(dot, 5, 5, 1.5)), 9u);
  EXPECT_EQ(count(dilate(dot, 5, 5, 2.0)), 13u);
  EXPECT_EQ(count(dilate(dot, 5, 5, 0.0)), 1u);
  EXPECT_THROW(dilate(dot, 5, 4, 1.0), std::invalid_argument);
}

TEST(RasterMorphology, GapsBetweenEndsAreBridgedUpToTheLength) {
  const std::vector<std::string> text = {"E.E..E...E....E", "###############", "E..#E.........."};
  std::vector<std::uint8_t> end, gap;
  int cols, rows;
  masks(text, &end, &gap, &cols, &rows);
  // Runs of 1, 2, 3 and 4 gap cells between ends; a run broken by another cell ('#'), and one
  // open to the raster's edge, are never bridged.
  EXPECT_EQ(show(text, bridge_gaps(end, gap, cols, rows, 3.0)),
            (std::vector<std::string>{"ExExxExxxE....E", "###############", "E..#E.........."}));
  EXPECT_EQ(show(text, bridge_gaps(end, gap, cols, rows, 4.0))[0], "ExExxExxxExxxxE");
  EXPECT_EQ(count(bridge_gaps(end, gap, cols, rows, 0.5)), 0u);
}

TEST(RasterMorphology, ColumnsAndDiagonalsBridgeTooADiagonalStepCountingSqrtTwo) {
  const std::vector<std::string> text = {"E#E#E", ".#.##", ".#E##", "E##.#", "####E"};
  std::vector<std::uint8_t> end, gap;
  int cols, rows;
  masks(text, &end, &gap, &cols, &rows);
  // Column 0: a run of 2 between ends; column 2: a run of 1; the diagonal from (2, 2) to (4, 4)
  // a run of 1 diagonal step (1.41 cells).
  EXPECT_EQ(show(text, bridge_gaps(end, gap, cols, rows, 2.0)),
            (std::vector<std::string>{"E#E#E", "x#x##", "x#E##", "E##x#", "####E"}));
  EXPECT_EQ(show(text, bridge_gaps(end, gap, cols, rows, 1.4))[3], "E##.#");  // too long for the diagonal
}

TEST(RasterMorphology, ADashedLineIsJoinedAcrossItsGaps) {
  // A wall two cells thick seen in dashes, free space above and below: what a disc's closing
  // leaves open, the gaps along the wall are bridged; nothing beside the wall is.
  const std::vector<std::string> text = {"fffffffffffffffff", "EEEE..EEE..EEEE..", "EEEE..EEE..EEEE..",
                                         "fffffffffffffffff"};
  std::vector<std::uint8_t> end, gap;
  int cols, rows;
  masks(text, &end, &gap, &cols, &rows);
  EXPECT_EQ(show(text, bridge_gaps(end, gap, cols, rows, 2.0)),
            (std::vector<std::string>{"fffffffffffffffff", "EEEExxEEExxEEEE..", "EEEExxEEExxEEEE..",
                                      "fffffffffffffffff"}));
}
