// Survey paths: every stop visited, the clearance kept (corners included), unreachable stops named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/survey_path.hpp"
#include "tsgraphs/scene/trajectory.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;
using ::testing::HasSubstr;

namespace {

// Three rooms off a 1.4 m corridor, through 0.9 m doors; a pillar in the east room.
const char* kScene = R"(name: survey
levels: [{name: L0, ceiling: 3.0, slab: [[0,0],[18,0],[18,8],[0,8]]}]
walls:
  - {level: L0, from: [0, 5], to: [18, 5], thickness: 0.15,
     openings: [{at: 3.0, width: 0.9}, {at: 9.0, width: 0.9}, {at: 15.0, width: 0.9}]}
  - {level: L0, from: [6, 0], to: [6, 5], thickness: 0.15}
  - {level: L0, from: [12, 0], to: [12, 5], thickness: 0.15}
  - {level: L0, from: [0, 6.4], to: [18, 6.4], thickness: 0.15}
boxes:
  - {level: L0, min: [14.5, 2.0, 0], max: [15.5, 3.0, 2.9], label: pillar}
trajectory: {waypoints: [[1, 5.7], [17, 5.7]], speed: 1.0, yaw_rate_deg: 45}
)";

}  // namespace

TEST(SurveyPath, VisitsEveryStopKeepingTheClearance) {
  Scene s = parse_scene(kScene, "survey.yaml", ".");
  const WalkableGrid g = rasterise_walkable(s, 0, frame_covering(s, 0.05, 0.5));
  std::vector<SurveyStop> stops = {{0, {1.0, 5.7}}};
  for (const Polygon2& room :
       {Polygon2{{0, 0}, {6, 0}, {6, 5}, {0, 5}}, Polygon2{{6, 0}, {12, 0}, {12, 5}, {6, 5}},
        Polygon2{{12, 0}, {18, 0}, {18, 5}, {12, 5}}}) {
    Vec2 p;
    ASSERT_TRUE(most_interior_point(g, room, &p));
    EXPECT_GT(g.clearance_at(p), 1.0);
    stops.push_back({0, p});
  }
  SurveyConfig config;
  config.clearance = 0.3;
  s.trajectory.waypoints = plan_survey({g}, {}, stops, config);
  EXPECT_EQ(s.trajectory.waypoints.front().xy, stops[0].xy);
  for (const SurveyStop& stop : stops) {
    bool visited = false;
    for (const Waypoint& w : s.trajectory.waypoints) visited = visited || (w.xy - stop.xy).norm() < 1e-9;
    EXPECT_TRUE(visited) << stop.xy.transpose();
  }
  const ClearanceAt exact = [&](const Vec2& xy, double floor_z, int) {
    return obstacle_distance(s, xy, floor_z, 0.35);
  };
  keep_clearance_on_turns(&s, exact, config);
  EXPECT_GE(path_clearance(s, exact).min_clearance, 0.3);
  // And the result loads as a scene without warnings.
  const Scene reloaded = parse_scene(kScene, "survey.yaml", ".");
  EXPECT_TRUE(Trajectory(s).warnings().empty());
  EXPECT_TRUE(reloaded.warnings.empty());
}

TEST(SurveyPath, CornersWhoseArcWouldCutAWallBecomeTurnsInPlace) {
  // An L-shaped corridor 1.4 m wide, walked along its middle at 1.5 m/s turning 30 deg/s:
  // the 2.9 m arc at the bend would cut the inner corner.
  const char* text = R"(name: bend
levels: [{name: L0, ceiling: 3.0, slab: [[0,0],[14,0],[14,14],[0,14]]}]
walls:
  - {level: L0, from: [0, 0], to: [14, 0], thickness: 0.1}
  - {level: L0, from: [14, 0], to: [14, 14], thickness: 0.1}
  - {level: L0, from: [0, 1.4], to: [12.6, 1.4], thickness: 0.1}
  - {level: L0, from: [12.6, 1.4], to: [12.6, 14], thickness: 0.1}
trajectory:
  waypoints: [[1, 0.7], [13.3, 0.7], [13.3, 13]]
  closed: false
  laps: 1
  speed: 1.5
  yaw_rate_deg: 30
)";
  Scene s = parse_scene(text, "bend.yaml", ".");
  const ClearanceAt exact = [&](const Vec2& xy, double floor_z, int) {
    return obstacle_distance(s, xy, floor_z, 0.35);
  };
  EXPECT_LT(path_clearance(s, exact).min_clearance, 0.3);
  SurveyConfig config;
  config.clearance = 0.3;
  EXPECT_GE(keep_clearance_on_turns(&s, exact, config), 0.3);
  EXPECT_EQ(s.trajectory.waypoints.size(), 4u);  // one stub before the bend
  EXPECT_EQ(Trajectory(s).turns_in_place(), 1);
}

TEST(SurveyPath, AStopBehindADoorTooNarrowForTheClearanceIsNamed) {
  const Scene s = parse_scene(kScene, "survey.yaml", ".");
  const WalkableGrid g = rasterise_walkable(s, 0, frame_covering(s, 0.05, 0.5));
  SurveyConfig config;
  config.clearance = 0.5;  // more than the 0.45 m a 0.9 m door leaves
  try {
    plan_survey({g}, {}, {{0, {1.0, 5.7}}, {0, {3.0, 2.5}}}, config,
                [](std::size_t i) { return i == 0 ? std::string("the corridor") : std::string("room_a"); });
    FAIL() << "a stop behind a 0.9 m door was reached with 0.5 m clearance";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("room_a"));
    EXPECT_THAT(e.what(), HasSubstr("cannot be reached"));
  }
  EXPECT_THROW(plan_survey({g}, {}, {{0, {14.9, 2.5}}}, config), std::invalid_argument);  // inside the pillar
}

TEST(SurveyPath, TheOrderIsShortAndTheSameEveryTime) {
  const Scene s = parse_scene(kScene, "survey.yaml", ".");
  const WalkableGrid g = rasterise_walkable(s, 0, frame_covering(s, 0.05, 0.5));
  // Stops along the corridor given out of order: the tour runs along it and back.
  const std::vector<SurveyStop> stops = {
      {0, {1, 5.7}}, {0, {13, 5.7}}, {0, {5, 5.7}}, {0, {17, 5.7}}, {0, {9, 5.7}}};
  SurveyConfig config;
  config.clearance = 0.3;
  const std::vector<Waypoint> a = plan_survey({g}, {}, stops, config);
  const std::vector<Waypoint> b = plan_survey({g}, {}, stops, config);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].xy, b[i].xy);
  double length = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) length += (a[(i + 1) % a.size()].xy - a[i].xy).norm();
  EXPECT_NEAR(length, 32.0, 0.5);  // 16 m out and back
}
