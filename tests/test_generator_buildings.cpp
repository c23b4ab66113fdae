// Generated buildings: deterministic per seed, and over 200 seeds every one loads without a
// warning, its path keeps its clearance and enters every ground-truth room, and its rooms
// neither overlap nor leave the walkable slab.
// ctest: slow (seconds a test: simulated runs or generated buildings)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/generator/generator.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/scene/survey_path.hpp"
#include "tsgraphs/scene/trajectory.hpp"
#include "tsgraphs/scene/walkable_grid.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;
using namespace tsgraphs::generator;
using ::testing::HasSubstr;

namespace {

constexpr int kSeedsPerStyle = 29;  // 7 styles x 29 = 203 buildings
constexpr double kClearance = 0.3;  // GeneratorConfig's default

/// Checks one building with the test's own code where it is simple (rooms entered, overlaps,
/// slab) and the library's exact obstacle distance for the clearance.
void check(const GeneratedBuilding& b) {
  const Scene& s = b.scene;
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  // The text is a scene file: it loads to the same scene.
  const Scene again = parse_scene(b.yaml, "again.yaml", ".");
  EXPECT_EQ(again.walls.size(), s.walls.size());
  const Trajectory t(s);
  EXPECT_TRUE(t.warnings().empty()) << t.warnings().front();
  EXPECT_EQ(s.trajectory.laps, 2);
  EXPECT_TRUE(s.trajectory.closed);
  EXPECT_GE(s.sensor.mount_height, 0.3);
  EXPECT_LE(s.sensor.mount_height, 1.8);
  ASSERT_FALSE(s.rooms.empty());

  const ClearanceAt exact = [&](const Vec2& xy, double floor_z, int) {
    return obstacle_distance(s, xy, floor_z, kClearance + 0.05);
  };
  const PathClearance c = path_clearance(s, exact, 0.05);
  EXPECT_GE(c.min_clearance, kClearance) << "at " << c.where.transpose() << " on " << s.levels[c.level].name;

  std::vector<bool> entered(s.rooms.size(), false);
  for (double time = 0.0; time <= t.duration(); time += 0.05 / s.trajectory.speed) {
    const Pose3 p = t.body_pose(time);
    const Vec2 xy = p.translation().head<2>();
    const double floor = p.translation().z() - s.sensor.mount_height;
    for (std::size_t i = 0; i < s.rooms.size(); ++i) {
      if (std::abs(s.levels[s.rooms[i].level].elevation - floor) < 0.05 && contains(s.rooms[i].polygon, xy))
        entered[i] = true;
    }
  }
  for (std::size_t i = 0; i < s.rooms.size(); ++i) EXPECT_TRUE(entered[i]) << "room " << s.rooms[i].name;

  std::set<std::string> names;
  for (std::size_t i = 0; i < s.rooms.size(); ++i) {
    const Room& a = s.rooms[i];
    EXPECT_TRUE(names.insert(a.name).second) << "two rooms named " << a.name;
    EXPECT_FALSE(find_self_intersection(a.polygon).has_value()) << a.name;
    for (std::size_t j = i + 1; j < s.rooms.size(); ++j) {
      if (s.rooms[j].level == a.level)
        EXPECT_LT(intersection_area(a.polygon, s.rooms[j].polygon), 1e-4)
            << a.name << " and " << s.rooms[j].name;
    }
    const Level& l = s.levels[a.level];
    EXPECT_NEAR(intersection_area(a.polygon, l.slab), area(a.polygon), 1e-4) << a.name << " leaves the slab";
    for (const Polygon2& v : l.voids)
      EXPECT_LT(intersection_area(a.polygon, v), 1e-4) << a.name << " over a void";
  }
}

class EveryStyle : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(EveryStyle, ManySeedsGiveSoundBuildings) {
  for (int seed = 1; seed <= kSeedsPerStyle; ++seed) {
    SCOPED_TRACE(GetParam() + " seed " + std::to_string(seed));
    check(generate_building(GetParam(), static_cast<std::uint64_t>(seed)));
    if (HasFailure()) return;  // one broken building is enough to look at
  }
}

INSTANTIATE_TEST_SUITE_P(Generator, EveryStyle, ::testing::ValuesIn(building_style_names()),
                         [](const auto& info) { return info.param; });

TEST(Generator, TheSameSeedGivesTheSameBuildingAnotherSeedAnother) {
  for (const std::string& style : {"office", "irregular"}) {
    const GeneratedBuilding a = generate_building(style, 7);
    EXPECT_EQ(generate_building(style, 7).yaml, a.yaml);
    EXPECT_NE(generate_building(style, 8).yaml, a.yaml);
  }
}

// People walk stretches of the survey path on flat floor, drawn last: the building, its
// platform and its path are the same without them.
TEST(Generator, PeopleWalkTheSurveyPathAndChangeNothingElse) {
  for (const std::string& style : {"office", "multi_storey"}) {
    GeneratorConfig config;
    config.size = 0.5;
    const GeneratedBuilding plain = generate_building(style, 4, config);
    config.people = 6;
    const GeneratedBuilding with = generate_building(style, 4, config);
    EXPECT_EQ(generate_building(style, 4, config).yaml, with.yaml);
    ASSERT_EQ(with.scene.people.size(), 6u) << style;
    Scene without = with.scene;
    without.people.clear();
    EXPECT_EQ(scene_yaml(without, ""), scene_yaml(plain.scene, "")) << style;
    for (const Person& p : with.scene.people) {
      ASSERT_GE(p.path.size(), 2u);
      EXPECT_GE(p.speed, 0.8);
      EXPECT_LE(p.speed, 1.5);
      for (const Vec2& xy : p.path) {
        const bool on_path =
            std::any_of(plain.scene.trajectory.waypoints.begin(), plain.scene.trajectory.waypoints.end(),
                        [&](const Waypoint& w) { return w.level == p.level && (w.xy - xy).norm() < 1e-9; });
        EXPECT_TRUE(on_path) << style << ": [" << xy.x() << ", " << xy.y() << "]";
        double z = 0.0;
        ASSERT_TRUE(walkable_height(with.scene, p.level, xy, &z));
        EXPECT_NEAR(z, with.scene.levels[p.level].elevation, 1e-9);  // not on a ramp
      }
    }
  }
  GeneratorConfig too_many;
  too_many.people = kMaxGeneratedPeople + 1;
  EXPECT_THROW(generate_building("office", 4, too_many), InputError);
}

TEST(Generator, AnUnknownStyleIsAnInputErrorListingTheStyles) {
  try {
    generate_building("castle", 1);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown building style 'castle'"));
    EXPECT_THAT(e.what(), HasSubstr("multi_storey"));
  }
}

TEST(Generator, EachStyleHasWhatMakesItThatStyle) {
  std::set<std::string> presets;
  std::set<RailingStyle> railings;
  bool two_doors = false, bend_or_branch = false, l_or_t_room = false, oblique_wall = false, pentagon = false;
  bool low_partition = false, pillar = false, bookshelf = false, ramp = false, three_levels = false;
  for (int seed = 1; seed <= 5; ++seed) {
    for (const std::string& style : building_style_names()) {
      const Scene s = generate_building(style, static_cast<std::uint64_t>(seed)).scene;
      presets.insert(s.sensor.preset);
      for (const Railing& r : s.railings) railings.insert(r.style);
      for (const Room& r : s.rooms) {
        l_or_t_room = l_or_t_room || (r.polygon.size() >= 6 && r.name.find("corridor") == std::string::npos);
        pentagon = pentagon || r.name.find("corridor_4") != std::string::npos;
        bend_or_branch = bend_or_branch || r.name.find("corridor_b") != std::string::npos;
      }
      for (const Wall& w : s.walls) {
        const Vec2 d = (w.to - w.from).normalized();
        const double deg = std::abs(std::atan2(d.y(), d.x())) * 180.0 / M_PI;
        const double off_axis = std::min(std::fmod(deg, 90.0), 90.0 - std::fmod(deg, 90.0));
        oblique_wall = oblique_wall || (off_axis >= 29.0 && off_axis <= 46.0);
        low_partition = low_partition || w.height < s.levels[w.level].ceiling - 0.5;
        for (const Opening& o : w.openings) {
          EXPECT_GE(o.width, 0.8 - 1e-9);
          EXPECT_LE(o.width, 2.0 + 1e-9);
        }
      }
      for (const Box& b : s.boxes) {
        pillar = pillar || b.label == "pillar";
        bookshelf = bookshelf || b.label == "bookshelf";
      }
      ramp = ramp || !s.ramps.empty();
      three_levels = three_levels || (style == "multi_storey" && s.levels.size() == 3);
      // A room with two doors: two openings on the walls round it (a door lies on its boundary).
      for (const Room& r : s.rooms) {
        int doors = 0;
        for (const Wall& w : s.walls) {
          for (const Opening& o : w.openings) {
            const Vec2 c = w.from + o.at * (w.to - w.from).normalized();
            double d = 1e9;
            for (std::size_t i = 0; i < r.polygon.size(); ++i)
              d = std::min(d, distance_to_segment(c, r.polygon[i], r.polygon[(i + 1) % r.polygon.size()]));
            doors += d < 0.5 * w.thickness + 1e-6 && w.level == r.level;
          }
        }
        two_doors = two_doors || (doors >= 2 && r.name.find("room") != std::string::npos);
      }
    }
  }
  EXPECT_EQ(presets.size(), 4u);
  EXPECT_EQ(railings.size(), 3u);  // solid, bars and glass
  EXPECT_TRUE(two_doors);
  EXPECT_TRUE(bend_or_branch);
  EXPECT_TRUE(l_or_t_room);
  EXPECT_TRUE(oblique_wall);
  EXPECT_TRUE(pentagon);
  EXPECT_TRUE(low_partition);
  EXPECT_TRUE(pillar);
  EXPECT_TRUE(bookshelf);
  EXPECT_TRUE(ramp);
  // Three storeys are the rarer draw (a quarter of multi_storey buildings): look further.
  for (int seed = 6; seed <= 30 && !three_levels; ++seed)
    three_levels =
        generate_building("multi_storey", static_cast<std::uint64_t>(seed)).scene.levels.size() == 3;
  EXPECT_TRUE(three_levels);
}

TEST(Generator, SmallBuildingsForQuickTests) {
  GeneratorConfig config;
  config.size = 0.3;
  config.laps = 1;
  for (const std::string& style : {"office", "atrium", "library"}) {
    const GeneratedBuilding b = generate_building(style, 3, config);
    check_building(b.scene, config.clearance);
    EXPECT_TRUE(check_building(b.scene, config.clearance).empty());
    EXPECT_LT(Trajectory(b.scene).length(), 80.0) << style;
  }
}
