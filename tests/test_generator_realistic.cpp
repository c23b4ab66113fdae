// generate --realistic: every style still gives sound buildings (check_building), with door
// leaves hinged at their jambs, windows in the facades, rooms that are not rectangles and
// rows of small offices; the same seed gives the same file; and without the option every
// building is byte for byte what it was before the option existed.
// ctest: slow (seconds a test: simulated runs or generated buildings)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/generator/door_leaves.hpp"
#include "tsgraphs/generator/generator.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;
using namespace tsgraphs::generator;

namespace {

constexpr double kClearance = 0.3;  // GeneratorConfig's default
constexpr double kQuickSize = 0.3;  // small buildings: a few tenths of a second each

GeneratorConfig realistic(double size = kQuickSize) {
  GeneratorConfig c;
  c.size = size;
  c.realistic = true;
  return c;
}

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

/// What a building holds of the realistic option.
struct Census {
  int doors = 0, doors_with_leaf = 0, leaves = 0, leaves_at_a_jamb = 0;
  int facade_windows = 0, glazed = 0, small_offices = 0, shaped_rooms = 0, boxes = 0;
};

bool is_rectangle(const Polygon2& p) {
  if (p.size() != 4) return false;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec2 a = p[(i + 1) % 4] - p[i], b = p[(i + 2) % 4] - p[(i + 1) % 4];
    if (std::abs(a.normalized().dot(b.normalized())) > 1e-6) return false;
  }
  return true;
}

Census census(const Scene& s) {
  Census c;
  c.boxes = static_cast<int>(s.boxes.size());
  std::vector<OrientedRect> leaves;
  for (const Box& b : s.boxes) {
    if (b.label != kDoorLeafLabel) continue;
    OrientedRect r;
    r.center = 0.5 * (b.min.head<2>() + b.max.head<2>());
    r.size = b.max.head<2>() - b.min.head<2>();
    r.yaw = b.yaw_deg * M_PI / 180.0;
    leaves.push_back(r);
    EXPECT_NEAR(r.size.y(), 0.04, 1e-9);  // a thin leaf...
    EXPECT_GT(b.max.z(), 2.0);            // ...as high as its door
    EXPECT_LE(b.max.z(), 2.1);
  }
  c.leaves = static_cast<int>(leaves.size());
  for (const Wall& w : s.walls) {
    const Vec2 u = (w.to - w.from).normalized();
    const double wall_yaw = std::atan2(u.y(), u.x());
    for (const Opening& o : w.openings) {
      if (o.sill > 0.0) {
        c.facade_windows += w.thickness >= 0.2 - 1e-9;  // facades are 0.2-0.3 m, inner walls 0.1-0.2
        if (o.transmission < 1.0) {
          ++c.glazed;
          EXPECT_GE(o.transmission, 0.5);
          EXPECT_LE(o.transmission, 0.9);
        }
        EXPECT_GE(o.sill, 0.8);
        EXPECT_LE(o.sill + o.height, 2.2 + 1e-9);
        continue;
      }
      ++c.doors;
      bool has = false;
      for (const OrientedRect& r : leaves) {
        // A leaf's hinge edge is at one of the door's jambs, its thickness off the wall's face.
        const Vec2 d(std::cos(r.yaw), std::sin(r.yaw));
        for (const double side : {-1.0, 1.0}) {
          const Vec2 hinge_end = r.center + side * 0.5 * r.size.x() * d;
          for (const double jamb : {-0.5, 0.5}) {
            const Vec2 j = w.from + (o.at + jamb * o.width) * u;
            if ((hinge_end - j).norm() > 0.5 * w.thickness + 0.1) continue;
            has = true;
            ++c.leaves_at_a_jamb;
            double open =
                std::abs(std::remainder(r.yaw - wall_yaw, M_PI)) * 180.0 / M_PI;  // 0..90 off the wall
            EXPECT_GE(open, 30.0 - 1e-6);
          }
        }
      }
      c.doors_with_leaf += has;
    }
  }
  for (const Room& r : s.rooms) {
    const double a = area(r.polygon);
    c.small_offices += a >= 6.0 && a <= 12.0;
    c.shaped_rooms += !is_rectangle(r.polygon);
  }
  return c;
}

class RealisticStyle : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(RealisticStyle, SoundBuildingsWithLeavesAndWindows) {
  Census all;
  for (const std::uint64_t seed : {1, 2}) {
    const GeneratedBuilding b = generate_building(GetParam(), seed, realistic());
    const std::vector<std::string> problems = check_building(b.scene, kClearance);
    EXPECT_TRUE(problems.empty()) << GetParam() << " seed " << seed << ": " << problems.front();
    EXPECT_LE(b.attempts, 5) << GetParam() << " seed " << seed;
    EXPECT_NE(b.yaml.find("--realistic"), std::string::npos);
    const Census c = census(b.scene);
    all.doors += c.doors;
    all.doors_with_leaf += c.doors_with_leaf;
    all.leaves += c.leaves;
    all.leaves_at_a_jamb += c.leaves_at_a_jamb;
    all.facade_windows += c.facade_windows;
    all.glazed += c.glazed;
  }
  EXPECT_GE(all.doors_with_leaf, 0.8 * all.doors) << GetParam();
  EXPECT_EQ(all.leaves_at_a_jamb, all.leaves) << GetParam() << ": a leaf away from every jamb";
  EXPECT_GT(all.facade_windows, 0) << GetParam();
  EXPECT_GT(all.glazed, 0) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Generator, RealisticStyle, ::testing::ValuesIn(building_style_names()),
                         [](const auto& info) { return info.param; });

// The FNV-1a of three buildings' files as `generate` wrote them before --realistic existed: the
// option must change nothing for a building without it.
TEST(Realistic, WithoutTheOptionABuildingIsWhatItWas) {
  struct Known {
    const char* style;
    std::uint64_t seed, hash;
  };
  const Known known[] = {{"office", 1, 0xec118c6c28cdc144ULL},
                         {"atrium", 2, 0x323d1f1bd847db5eULL},
                         {"irregular", 3, 0x2d61288e7622e569ULL}};
  GeneratorConfig plain;
  plain.size = kQuickSize;
  for (const Known& k : known) {
    const GeneratedBuilding before = generate_building(k.style, k.seed, plain);
    EXPECT_EQ(fnv1a(before.yaml), k.hash) << k.style << " seed " << k.seed;
    const GeneratedBuilding real = generate_building(k.style, k.seed, realistic());
    EXPECT_NE(real.yaml, before.yaml);
    // Nothing carries over from one building to the next.
    EXPECT_EQ(generate_building(k.style, k.seed, plain).yaml, before.yaml);
  }
}

TEST(Realistic, TheSameSeedGivesTheSameFile) {
  const GeneratedBuilding a = generate_building("mixed", 4, realistic());
  const GeneratedBuilding b = generate_building("mixed", 4, realistic());
  EXPECT_EQ(a.yaml, b.yaml);
  EXPECT_NE(generate_building("mixed", 5, realistic()).yaml, a.yaml);
}

// Full-size offices: rows of small offices (6-12 m^2 inside the walls) along the corridors,
// and rooms that are not rectangles (a notch, a pilaster or a chamfer taken by a shaft).
TEST(Realistic, OfficesHaveSmallOfficesAndRoomsOfOtherShapes) {
  Census all;
  int rooms = 0;
  for (const std::uint64_t seed : {2, 3}) {
    const GeneratedBuilding b = generate_building("office", seed, realistic(1.0));
    const Census c = census(b.scene);
    all.small_offices += c.small_offices;
    all.shaped_rooms += c.shaped_rooms;
    all.boxes += c.boxes;
    rooms += static_cast<int>(b.scene.rooms.size());
  }
  EXPECT_GE(all.small_offices, 4) << "of " << rooms << " rooms";
  EXPECT_GE(all.shaped_rooms, 2) << "of " << rooms << " rooms";
  EXPECT_GE(all.boxes, 3 * rooms) << "clutter: boxes per room";
}
