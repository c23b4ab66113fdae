// split_at_narrowings: spaces are the parts of the walkable area joined only by narrowings.
#include <gtest/gtest.h>

#include <set>

#include "tsgraphs/rooms/narrowings.hpp"

namespace tsgraphs::rooms {
namespace {

constexpr double kRes = 0.1;

/// A blocked raster of w x h metres; `open` clears boxes on it (metres, lower-left origin).
struct Plan {
  GridFrame f;
  std::vector<std::uint8_t> walkable;
  Plan(double w, double h) {
    f.resolution = kRes;
    f.cols = static_cast<int>(w / kRes);
    f.rows = static_cast<int>(h / kRes);
    walkable.assign(f.size(), 0);
  }
  void set(double x0, double y0, double x1, double y1, std::uint8_t v) {
    for (int r = 0; r < f.rows; ++r)
      for (int c = 0; c < f.cols; ++c) {
        const Vec2 p = f.center(c, r);
        if (p.x() > x0 && p.x() < x1 && p.y() > y0 && p.y() < y1) walkable[f.index(c, r)] = v;
      }
  }
  void open(double x0, double y0, double x1, double y1) { set(x0, y0, x1, y1, 1); }
  void block(double x0, double y0, double x1, double y1) { set(x0, y0, x1, y1, 0); }
  int at(const std::vector<int>& label, double x, double y) const {
    int c, r;
    return f.cell_of(Vec2(x, y), &c, &r) ? label[f.index(c, r)] : -2;
  }
};

int split(const Plan& p, std::vector<int>* label) {
  return split_at_narrowings(p.f, p.walkable, 1.0, 0.7, 2.0, label);
}

TEST(Narrowings, TwoRoomsJoinedByADoorAreTwoSpaces) {
  Plan p(12.0, 6.0);
  p.open(1.0, 1.0, 5.0, 5.0);   // 4 x 4 m
  p.open(5.2, 1.0, 11.0, 5.0);  // 5.8 x 4 m, a 0.2 m wall between them
  p.open(4.9, 2.6, 5.3, 3.4);   // a 0.8 m door through it
  std::vector<int> label;
  EXPECT_EQ(split(p, &label), 2);
  EXPECT_NE(p.at(label, 3.0, 3.0), p.at(label, 8.0, 3.0));
  EXPECT_EQ(p.at(label, 1.5, 1.5), p.at(label, 3.0, 3.0));
  EXPECT_EQ(p.at(label, 0.5, 0.5), -1);  // a wall cell is no space
}

TEST(Narrowings, RoomsOffACorridorAreSpacesOfTheirOwnAndTheCorridorIsOne) {
  Plan p(20.0, 8.0);
  p.open(1.0, 1.0, 19.0, 2.6);  // a 1.6 m corridor, 18 m long
  for (double x : {1.0, 7.0, 13.0}) {
    p.open(x, 2.8, x + 5.8, 7.0);        // a room north of it
    p.open(x + 2.5, 2.5, x + 3.4, 2.9);  // its 0.9 m door
  }
  std::vector<int> label;
  EXPECT_EQ(split(p, &label), 4);
  std::set<int> corridor;
  for (double x = 1.5; x < 19.0; x += 0.5) corridor.insert(p.at(label, x, 1.8));
  EXPECT_EQ(corridor.size(), 1u);
  std::set<int> rooms{p.at(label, 4.0, 5.0), p.at(label, 10.0, 5.0), p.at(label, 16.0, 5.0)};
  EXPECT_EQ(rooms.size(), 3u);
  EXPECT_EQ(rooms.count(*corridor.begin()), 0u);
}

TEST(Narrowings, FurnitureABayAndAnLShapeDoNotSplitARoom) {
  Plan p(14.0, 12.0);
  p.open(1.0, 1.0, 13.0, 5.0);   // an L: a 12 x 4 m arm...
  p.open(1.0, 5.0, 5.0, 11.0);   // ...and a 4 x 6 m arm
  p.open(13.0, 2.0, 13.5, 4.0);  // a shallow bay in the east wall
  p.block(7.4, 2.6, 8.6, 3.4);   // a desk the floor surrounds
  p.block(2.5, 7.5, 2.9, 7.9);   // a pillar
  std::vector<int> label;
  EXPECT_EQ(split(p, &label), 1);
  EXPECT_EQ(p.at(label, 8.0, 3.0), -1);  // the desk's cells stay no space
}

TEST(Narrowings, AWideOpeningBetweenHallsIsNoDoorButANarrowOneIs) {
  for (const auto& [opening, spaces] : {std::pair<double, int>{3.0, 1}, std::pair<double, int>{1.0, 2}}) {
    Plan p(18.0, 10.0);
    p.open(1.0, 1.0, 8.8, 9.0);
    p.open(9.0, 1.0, 17.0, 9.0);
    p.open(8.7, 5.0 - 0.5 * opening, 9.1, 5.0 + 0.5 * opening);
    std::vector<int> label;
    EXPECT_EQ(split(p, &label), spaces) << opening << " m";
  }
}

TEST(Narrowings, RejectsAMaskOfAnotherSize) {
  Plan p(4.0, 4.0);
  std::vector<int> label;
  EXPECT_THROW(split_at_narrowings(p.f, std::vector<std::uint8_t>(3, 1), 1.0, 0.7, 2.0, &label),
               std::invalid_argument);
}

}  // namespace
}  // namespace tsgraphs::rooms
