#pragma once
/// A small office floor drawn as a 2-D occupancy raster with its true rooms, shared by the
/// segment-map tests: a 1.5 m corridor along the south with three rooms off it through 0.8 m
/// doors, the east one L-shaped round a small office entered from it through a 0.8 m door; a
/// table, a cabinet against a wall and chairs' legs in the rooms; unknown space round the
/// building. Header only (tests/CMakeLists.txt makes executables of tests/test_*.cpp only).
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/core/grid_frame.hpp"

namespace tsgraphs::test {

struct FloorBox {
  double x0, y0, x1, y1;  ///< m from the raster's lower-left corner
};

enum class FloorCell : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

struct DrawnFloor {
  GridFrame frame;                 ///< 0.05 m cells, origin (0, 0)
  std::vector<FloorCell> cells;    ///< row 0 at the bottom
  std::vector<int> truth;          ///< per cell: the true room (index into names), -1 none
  std::vector<std::string> names;  ///< corridor, west, middle, east (L-shaped), office

  std::vector<std::uint8_t> mask(FloorCell which) const {
    std::vector<std::uint8_t> m(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) m[i] = cells[i] == which ? 1 : 0;
    return m;
  }
};

inline DrawnFloor draw_floor() {
  DrawnFloor d;
  d.frame.resolution = 0.05;
  d.frame.cols = 340;  // 17 m
  d.frame.rows = 220;  // 11 m
  d.cells.assign(d.frame.size(), FloorCell::kUnknown);
  d.truth.assign(d.frame.size(), -1);
  const auto fill = [&](const FloorBox& b, FloorCell v) {
    for (int r = 0; r < d.frame.rows; ++r)
      for (int c = 0; c < d.frame.cols; ++c) {
        const Vec2 p = d.frame.center(c, r);
        if (p.x() >= b.x0 && p.x() <= b.x1 && p.y() >= b.y0 && p.y() <= b.y1)
          d.cells[d.frame.index(c, r)] = v;
      }
  };
  fill({1.0, 1.0, 16.0, 10.0}, FloorCell::kOccupied);  // the outer wall, 0.15 m
  fill({1.15, 1.15, 15.85, 9.85}, FloorCell::kFree);
  fill({1.15, 2.65, 15.85, 2.8}, FloorCell::kOccupied);  // the corridor's wall
  fill({5.0, 2.8, 5.15, 9.85}, FloorCell::kOccupied);    // west | middle
  fill({9.0, 2.8, 9.15, 9.85}, FloorCell::kOccupied);    // middle | east
  fill({12.0, 6.0, 15.85, 6.15}, FloorCell::kOccupied);  // the office's south wall
  fill({12.0, 6.0, 12.15, 9.85}, FloorCell::kOccupied);  // its west wall
  for (const FloorBox& door : {FloorBox{2.6, 2.65, 3.4, 2.8}, FloorBox{6.6, 2.65, 7.4, 2.8},
                               FloorBox{10.6, 2.65, 11.4, 2.8}, FloorBox{12.0, 7.6, 12.15, 8.4}})
    fill(door, FloorCell::kFree);
  fill({2.0, 5.5, 3.2, 6.1}, FloorCell::kUnknown);  // a table (unseen under it)
  fill({2.0, 5.45, 3.2, 5.5}, FloorCell::kOccupied);
  fill({5.15, 7.0, 5.75, 9.0}, FloorCell::kOccupied);  // a cabinet against the middle room's wall
  for (const Vec2& leg : {Vec2(1.8, 5.2), Vec2(3.5, 5.3), Vec2(1.9, 6.5), Vec2(3.4, 6.4), Vec2(7.2, 5.0),
                          Vec2(10.5, 4.0), Vec2(13.0, 8.0)})
    fill({leg.x() - 0.03, leg.y() - 0.03, leg.x() + 0.03, leg.y() + 0.03}, FloorCell::kOccupied);
  d.names = {"corridor", "west", "middle", "east", "office"};
  const std::vector<std::vector<FloorBox>> rooms = {{{1.15, 1.15, 15.85, 2.65}},
                                                    {{1.15, 2.8, 5.0, 9.85}},
                                                    {{5.15, 2.8, 9.0, 9.85}},
                                                    {{9.15, 2.8, 15.85, 6.0}, {9.15, 6.0, 12.0, 9.85}},
                                                    {{12.15, 6.15, 15.85, 9.85}}};
  for (std::size_t k = 0; k < rooms.size(); ++k)
    for (int r = 0; r < d.frame.rows; ++r)
      for (int c = 0; c < d.frame.cols; ++c) {
        const std::size_t i = d.frame.index(c, r);
        const Vec2 p = d.frame.center(c, r);
        for (const FloorBox& b : rooms[k])
          if (d.cells[i] == FloorCell::kFree && p.x() >= b.x0 && p.x() <= b.x1 && p.y() >= b.y0 &&
              p.y() <= b.y1)
            d.truth[i] = static_cast<int>(k);
      }
  return d;
}

}  // namespace tsgraphs::test
