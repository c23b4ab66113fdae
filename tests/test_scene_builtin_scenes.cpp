// The four built-in scenes (scenes/*.yaml): they load, their ground-truth rooms are sane
// (inside the slab, out of the voids, not overlapping), and the planned path goes where
// each scene promises: through the rooms, round every corridor segment, up to both levels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/trajectory.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;

namespace {

std::string scene_path(const std::string& name) {
  return std::string(TSGRAPHS_SCENES_DIR) + "/" + name + ".yaml";
}

/// Grid points (cell centres, about `step` apart) of the room's bounding box that lie inside it.
std::vector<Vec2> samples_inside(const Polygon2& poly, double step) {
  Vec2 lo = poly.front(), hi = poly.front();
  for (const Vec2& p : poly) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const int nx = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / step)));
  const int ny = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / step)));
  std::vector<Vec2> out;
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const Vec2 p(lo.x() + (hi.x() - lo.x()) * (i + 0.5) / nx, lo.y() + (hi.y() - lo.y()) * (j + 0.5) / ny);
      if (contains(poly, p)) out.push_back(p);
    }
  }
  return out;
}

bool is_corridor(const Room& r) { return r.name.rfind("corridor", 0) == 0; }

/// The level whose floor the body stands on at `pose` (-1 between levels, e.g. on a ramp).
int level_at(const Scene& scene, const Pose3& pose) {
  const double floor_z = pose.translation().z() - scene.sensor.mount_height;
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    if (std::abs(floor_z - scene.levels[i].elevation) < 0.05) return static_cast<int>(i);
  }
  return -1;
}

/// Names of the ground-truth rooms that hold at least one pose of the path (10 Hz), on the
/// pose's level.
std::set<std::string> rooms_visited(const Scene& scene) {
  const Trajectory traj(scene);
  std::set<std::string> visited;
  for (double t = 0.0; t <= traj.duration(); t += 0.1) {
    const Pose3 pose = traj.body_pose(t);
    const int level = level_at(scene, pose);
    const Vec2 xy = pose.translation().head<2>();
    for (const Room& r : scene.rooms) {
      if (r.level == level && contains(r.polygon, xy)) visited.insert(r.name);
    }
  }
  return visited;
}

struct Expectation {
  std::string name;
  std::size_t min_levels;
  std::size_t min_rooms_visited;  ///< rooms other than corridor segments, over all levels
};

// Test names and failure messages show the scene's name.
void PrintTo(const Expectation& e, std::ostream* os) { *os << e.name; }

class BuiltinScene : public ::testing::TestWithParam<Expectation> {
 protected:
  void SetUp() override {
    ASSERT_NO_THROW(scene_ = load_scene(scene_path(GetParam().name))) << scene_path(GetParam().name);
  }
  Scene scene_;
};

}  // namespace

TEST_P(BuiltinScene, LoadsWithLevelsRoomsAndTwoClosedLaps) {
  EXPECT_GE(scene_.levels.size(), GetParam().min_levels);
  EXPECT_GE(scene_.rooms.size(), 4u);
  EXPECT_EQ(scene_.trajectory.laps, 2);
  EXPECT_TRUE(scene_.trajectory.closed);
  EXPECT_EQ(scene_.sensor.preset, "os1-64");
  // No path through a wall, box or void, no storey inside another.
  EXPECT_TRUE(scene_.warnings.empty()) << scene_.warnings.front();
}

TEST_P(BuiltinScene, RoomsLieOnTheirSlabOutsideVoids) {
  for (const Room& r : scene_.rooms) {
    const Level& level = scene_.levels[r.level];
    const Vec2 c = centroid(r.polygon);
    for (const Vec2& v : r.polygon) {
      // A vertex on the slab's outline counts: test it 1 cm in toward the room's centre.
      const Vec2 p = v + 0.01 * (c - v).normalized();
      EXPECT_TRUE(contains(level.slab, p))
          << r.name << ": vertex [" << v.x() << ", " << v.y() << "] is off the slab of " << level.name;
    }
    int in_void = 0;
    const std::vector<Vec2> samples = samples_inside(r.polygon, 0.1);
    for (const Vec2& p : samples) {
      for (const Polygon2& v : level.voids) in_void += contains(v, p) ? 1 : 0;
    }
    EXPECT_LE(in_void, static_cast<int>(0.01 * samples.size())) << r.name << " reaches into a void";
  }
}

TEST_P(BuiltinScene, RoomsDoNotOverlap) {
  for (const Room& a : scene_.rooms) {
    const std::vector<Vec2> samples = samples_inside(a.polygon, 0.05);
    ASSERT_FALSE(samples.empty()) << a.name;
    for (const Room& b : scene_.rooms) {
      if (&a == &b || a.level != b.level) continue;
      const auto shared = std::count_if(samples.begin(), samples.end(),
                                        [&](const Vec2& p) { return contains(b.polygon, p); });
      EXPECT_LE(shared, 0.01 * samples.size())
          << a.name << " overlaps " << b.name << " (" << shared << " of " << samples.size() << " samples)";
    }
  }
}

TEST_P(BuiltinScene, PathReturnsToItsStartAfterEachLap) {
  const Trajectory traj(scene_);
  ASSERT_EQ(traj.lap_starts().size(), 2u);
  const Vec2 start = scene_.trajectory.waypoints.front().xy;
  EXPECT_LT((traj.body_pose(0.0).translation().head<2>() - start).norm(), 1e-6);
  EXPECT_LT((traj.body_pose(traj.duration()).translation().head<2>() - start).norm(), 1e-6);
  EXPECT_LT((traj.body_pose(traj.lap_starts()[1]).translation().head<2>() - start).norm(), 0.3);
  // Modest scenes: one lap of 80 .. 220 m.
  EXPECT_GT(traj.length() / 2, 80.0);
  EXPECT_LT(traj.length() / 2, 220.0);
}

TEST_P(BuiltinScene, PathVisitsRooms) {
  const std::set<std::string> visited = rooms_visited(scene_);
  std::size_t rooms = 0;
  for (const Room& r : scene_.rooms) rooms += (!is_corridor(r) && visited.count(r.name)) ? 1 : 0;
  EXPECT_GE(rooms, GetParam().min_rooms_visited);
}

INSTANTIATE_TEST_SUITE_P(Scenes, BuiltinScene,
                         ::testing::Values(Expectation{"office", 1, 3}, Expectation{"atrium", 2, 3},
                                           Expectation{"long_corridor", 1, 3},
                                           Expectation{"two_storeys", 2, 4}),
                         [](const ::testing::TestParamInfo<Expectation>& info) { return info.param.name; });

TEST(BuiltinScenes, AtriumHasAVoidRailingsOfBothStylesAndAWalkedRing) {
  const Scene scene = load_scene(scene_path("atrium"));
  std::size_t voids = 0;
  for (const Level& l : scene.levels) voids += l.voids.size();
  EXPECT_GE(voids, 1u);
  const auto solid = std::count_if(scene.railings.begin(), scene.railings.end(),
                                   [](const Railing& r) { return r.style == RailingStyle::kSolid; });
  const auto bars = std::count_if(scene.railings.begin(), scene.railings.end(),
                                  [](const Railing& r) { return r.style == RailingStyle::kBars; });
  EXPECT_GE(solid, 1);
  EXPECT_GE(bars, 1);
  // The ring is split into corridor segments, and the path goes through every one of them.
  const std::set<std::string> visited = rooms_visited(scene);
  int segments = 0;
  for (const Room& r : scene.rooms) {
    if (!is_corridor(r)) continue;
    ++segments;
    EXPECT_TRUE(visited.count(r.name)) << "the path misses " << r.name;
  }
  EXPECT_GE(segments, 2);
  // Every ground-truth room of the atrium is on the level with the void and the path.
  for (const Room& r : scene.rooms) EXPECT_EQ(r.level, scene.trajectory.level) << r.name;
}

TEST(BuiltinScenes, LongCorridorSpansSixtyMetres) {
  const Scene scene = load_scene(scene_path("long_corridor"));
  Vec2 lo = Vec2::Constant(1e9), hi = Vec2::Constant(-1e9);
  int segments = 0;
  for (const Room& r : scene.rooms) {
    if (!is_corridor(r)) continue;
    ++segments;
    for (const Vec2& p : r.polygon) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  ASSERT_GE(segments, 1);
  EXPECT_GE((hi - lo).maxCoeff(), 60.0);
  // The bookshelf that divides a room is there.
  EXPECT_TRUE(std::any_of(scene.boxes.begin(), scene.boxes.end(), [](const Box& b) {
    return b.label == "bookshelf" && b.max.z() - b.min.z() >= 1.8;
  }));
}

TEST(BuiltinScenes, TwoStoreysPathReachesBothLevels) {
  const Scene scene = load_scene(scene_path("two_storeys"));
  ASSERT_GE(scene.levels.size(), 2u);
  ASSERT_GE(scene.ramps.size(), 1u);
  const Trajectory traj(scene);
  std::vector<bool> reached(scene.levels.size(), false);
  for (double t = 0.0; t <= traj.duration(); t += 0.1) {
    const int level = level_at(scene, traj.body_pose(t));
    if (level >= 0) reached[level] = true;
  }
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    EXPECT_TRUE(reached[i]) << "the path never stands on level " << scene.levels[i].name;
  }
  // Ground-truth rooms on every level, and the path visits rooms on each.
  const std::set<std::string> visited = rooms_visited(scene);
  for (std::size_t i = 0; i < scene.levels.size(); ++i) {
    int rooms = 0, rooms_visited_here = 0;
    for (const Room& r : scene.rooms) {
      if (r.level != static_cast<int>(i)) continue;
      ++rooms;
      rooms_visited_here += visited.count(r.name) ? 1 : 0;
    }
    EXPECT_GE(rooms, 2) << scene.levels[i].name;
    EXPECT_GE(rooms_visited_here, 2) << scene.levels[i].name;
  }
}
