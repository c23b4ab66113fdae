// Scene loading: defaults, presets, and every validation error with the right key and line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

using namespace tsgraphs;
using namespace tsgraphs::scene;
using ::testing::HasSubstr;

namespace {

// A valid one-room scene; tests replace parts of it.
const std::string kRoom = R"(name: room
levels:
  - name: L0
    slab: [[0,0],[10,0],[10,8],[0,8]]
walls:
  - level: L0
    from: [0, 0]
    to: [10, 0]
    openings:
      - {at: 5.0, width: 1.0, height: 2.1}
trajectory:
  waypoints: [[2, 2], [8, 2], [8, 6]]
)";

// 1-based line of the first line of `text` that contains `marker`.
int line_of(const std::string& text, const std::string& marker) {
  const std::size_t pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << marker;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "test.yaml", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "scene loaded but should not:\n" << text;
  return "";
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

std::string at_line(const std::string& text, const std::string& marker) {
  return "test.yaml:" + std::to_string(line_of(text, marker)) + ":";
}

}  // namespace

TEST(SceneLoader, DefaultsFollowTheFormat) {
  const Scene s = parse_scene(kRoom, "test.yaml", ".");
  EXPECT_EQ(s.name, "room");
  ASSERT_EQ(s.levels.size(), 1u);
  EXPECT_DOUBLE_EQ(s.levels[0].ceiling, 3.0);
  ASSERT_EQ(s.walls.size(), 1u);
  EXPECT_DOUBLE_EQ(s.walls[0].thickness, 0.2);
  EXPECT_DOUBLE_EQ(s.walls[0].height, 3.0);  // the level's ceiling
  EXPECT_DOUBLE_EQ(s.walls[0].openings[0].sill, 0.0);
  EXPECT_EQ(s.sensor.channels, 64);
  EXPECT_EQ(s.sensor.vertical_angles_deg.size(), 64u);
  EXPECT_DOUBLE_EQ(s.sensor.vertical_angles_deg.front(), 22.5);
  EXPECT_DOUBLE_EQ(s.sensor.vertical_angles_deg.back(), -22.5);
  EXPECT_DOUBLE_EQ(s.sensor.mount_height, 0.55);
  EXPECT_DOUBLE_EQ(s.odometry.trans_noise_per_m, 0.01);
  EXPECT_EQ(s.trajectory.laps, 2);
  EXPECT_TRUE(s.trajectory.closed);
  EXPECT_DOUBLE_EQ(s.trajectory.speed, 1.0);
  EXPECT_EQ(s.trajectory.waypoints.size(), 3u);
  EXPECT_EQ(s.source_text, kRoom);
}

TEST(SceneLoader, PresetsCarryTheDatasheetBeamLayouts) {
  SensorSpec s;
  ASSERT_TRUE(apply_preset("vlp-16", &s));
  ASSERT_EQ(s.vertical_angles_deg.size(), 16u);
  for (int i = 0; i < 16; ++i) EXPECT_DOUBLE_EQ(s.vertical_angles_deg[i], 15.0 - 2.0 * i);
  EXPECT_EQ(s.columns, 1800);
  ASSERT_TRUE(apply_preset("hesai-xt32", &s));
  ASSERT_EQ(s.vertical_angles_deg.size(), 32u);
  EXPECT_DOUBLE_EQ(s.vertical_angles_deg.front(), 15.0);
  EXPECT_DOUBLE_EQ(s.vertical_angles_deg.back(), -16.0);
  ASSERT_TRUE(apply_preset("os0-128", &s));
  EXPECT_EQ(s.vertical_angles_deg.size(), 128u);
  EXPECT_DOUBLE_EQ(s.vertical_angles_deg.back(), -45.0);
  ASSERT_TRUE(apply_preset("os1-64", &s));
  EXPECT_EQ(s.channels, 64);
  EXPECT_FALSE(apply_preset("hdl-64", &s));
}

TEST(SceneLoader, PresetFieldsCanBeOverridden) {
  const std::string text =
      replace(kRoom, "levels:", "sensor:\n  preset: vlp-16\n  max_range: 30\n  mount_height: 1.2\nlevels:");
  const Scene s = parse_scene(text, "test.yaml", ".");
  EXPECT_EQ(s.sensor.preset, "vlp-16");
  EXPECT_EQ(s.sensor.channels, 16);
  EXPECT_DOUBLE_EQ(s.sensor.max_range, 30.0);
  EXPECT_DOUBLE_EQ(s.sensor.mount_height, 1.2);
  // Overriding the field of view spreads the beams evenly over it.
  const Scene s2 =
      parse_scene(replace(text, "max_range: 30", "vertical_fov_deg: [-10, 10]"), "test.yaml", ".");
  EXPECT_DOUBLE_EQ(s2.sensor.vertical_angles_deg.front(), 10.0);
  EXPECT_DOUBLE_EQ(s2.sensor.vertical_angles_deg.back(), -10.0);
  // An explicit beam table (for example from a sensor's calibration) is sorted top to bottom.
  const Scene s3 = parse_scene(
      replace(kRoom, "levels:", "sensor:\n  vertical_angles_deg: [-5, 3.5, 1]\nlevels:"), "test.yaml", ".");
  EXPECT_EQ(s3.sensor.channels, 3);
  EXPECT_THAT(s3.sensor.vertical_angles_deg, ::testing::ElementsAre(3.5, 1.0, -5.0));
}

TEST(SceneLoader, UnknownKeyNamesKeyAndLine) {
  const std::string text = replace(kRoom, "    to: [10, 0]\n", "    to: [10, 0]\n    colour: red\n");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr(at_line(text, "colour")));
  EXPECT_THAT(msg, HasSubstr("unknown key 'walls[0].colour'"));
  const std::string top = kRoom + "lights: 3\n";
  EXPECT_THAT(error_of(top), HasSubstr(at_line(top, "lights")));
  EXPECT_THAT(error_of(top), HasSubstr("'lights'"));
}

TEST(SceneLoader, MissingSlab) {
  const std::string text = replace(kRoom, "    slab: [[0,0],[10,0],[10,8],[0,8]]\n", "    elevation: 0\n");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr(at_line(text, "- name: L0")));
  EXPECT_THAT(msg, HasSubstr("no slab"));
}

TEST(SceneLoader, ZeroLengthWall) {
  const std::string text = replace(kRoom, "to: [10, 0]", "to: [0, 0]");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr(at_line(text, "to: [0, 0]")));
  EXPECT_THAT(msg, HasSubstr("walls[0].to: zero-length wall"));
}

TEST(SceneLoader, SelfIntersectingPolygon) {
  const std::string text = replace(kRoom, "[[0,0],[10,0],[10,8],[0,8]]", "[[0,0],[10,8],[10,0],[0,8]]");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr(at_line(text, "slab:")));
  EXPECT_THAT(msg, HasSubstr("levels[0].slab: self-intersecting polygon"));
  const std::string voids =
      replace(kRoom, "    slab: [[0,0],[10,0],[10,8],[0,8]]\n",
              "    slab: [[0,0],[10,0],[10,8],[0,8]]\n    voids:\n      - [[4,4],[6,6],[6,4],[4,6]]\n");
  EXPECT_THAT(error_of(voids), HasSubstr(at_line(voids, "[[4,4]")));
  EXPECT_THAT(error_of(voids), HasSubstr("levels[0].voids[0]: self-intersecting"));
}

TEST(SceneLoader, OpeningWiderThanWall) {
  const std::string text =
      replace(kRoom, "{at: 5.0, width: 1.0, height: 2.1}", "{at: 5.0, width: 12.0, height: 2.1}");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr(at_line(text, "width: 12.0")));
  EXPECT_THAT(msg, HasSubstr("walls[0].openings[0].width"));
  EXPECT_THAT(msg, HasSubstr("wider than its wall"));
  const std::string off_end = replace(kRoom, "{at: 5.0,", "{at: 9.8,");
  EXPECT_THAT(error_of(off_end), HasSubstr("walls[0].openings[0].at"));
  const std::string too_tall = replace(kRoom, "height: 2.1}", "height: 2.5, sill: 1.0}");
  EXPECT_THAT(error_of(too_tall), HasSubstr("exceeds the wall's height"));
}

TEST(SceneLoader, WaypointInsideWall) {
  // The wall runs along y = 0 with thickness 0.2: y = 0.05 is inside it, away from the door.
  const std::string text = replace(kRoom, "[[2, 2], [8, 2], [8, 6]]", "[[2, 2], [8, 0.05], [8, 6]]");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr(at_line(text, "waypoints:")));
  EXPECT_THAT(msg, HasSubstr("trajectory.waypoints[1]"));
  EXPECT_THAT(
      msg, HasSubstr("inside the wall walls[0] (line " + std::to_string(line_of(text, "- level: L0")) + ")"));
  // In the door opening (at 5.0, 1.0 wide) the same offset is allowed.
  EXPECT_NO_THROW(parse_scene(replace(kRoom, "[[2, 2], [8, 2], [8, 6]]", "[[2, 2], [5.1, 0.05], [8, 6]]"),
                              "t.yaml", "."));
}

TEST(SceneLoader, WaypointOutsideEverySlab) {
  const std::string text = replace(kRoom, "[[2, 2], [8, 2], [8, 6]]", "[[2, 2], [12, 2], [8, 6]]");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr("trajectory.waypoints[1]"));
  EXPECT_THAT(msg, HasSubstr("outside every slab of level L0"));
  const std::string in_void =
      replace(replace(kRoom, "    slab: [[0,0],[10,0],[10,8],[0,8]]\n",
                      "    slab: [[0,0],[10,0],[10,8],[0,8]]\n    voids: [[[7,1],[9,1],[9,3],[7,3]]]\n"),
              "[[2, 2], [8, 2], [8, 6]]", "[[2, 2], [4, 2], [8, 6],\n    [8, 2]]");
  const std::string msg2 = error_of(in_void);
  EXPECT_THAT(msg2, HasSubstr("test.yaml:" + std::to_string(line_of(in_void, "[8, 2]]")) + ":"));
  EXPECT_THAT(msg2, HasSubstr("trajectory.waypoints[3]"));
}

TEST(SceneLoader, UnknownLevel) {
  const std::string text = replace(kRoom, "  - level: L0\n    from", "  - level: L9\n    from");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr(at_line(text, "level: L9")));
  EXPECT_THAT(msg, HasSubstr("walls[0].level: unknown level 'L9' (levels: L0)"));
  const std::string wp = replace(kRoom, "[8, 6]]", "[8, 6, L2]]");
  EXPECT_THAT(error_of(wp), HasSubstr("trajectory.waypoints[2]: unknown level 'L2'"));
}

TEST(SceneLoader, UnknownPreset) {
  const std::string text = replace(kRoom, "levels:", "sensor:\n  preset: os2-256\nlevels:");
  const std::string msg = error_of(text);
  EXPECT_THAT(msg, HasSubstr(at_line(text, "preset:")));
  EXPECT_THAT(msg, HasSubstr("sensor.preset: unknown preset 'os2-256'"));
  EXPECT_THAT(msg, HasSubstr("vlp-16"));
}

TEST(SceneLoader, OutOfRangeValuesAndTypes) {
  EXPECT_THAT(error_of(replace(kRoom, "levels:", "sensor: {dropout: 1.5}\nlevels:")),
              HasSubstr("sensor.dropout"));
  EXPECT_THAT(error_of(replace(kRoom, "levels:", "sensor: {rate_hz: .nan}\nlevels:")),
              HasSubstr("not a finite number"));
  EXPECT_THAT(error_of(replace(kRoom, "levels:", "sensor: {channels: many}\nlevels:")),
              HasSubstr("expected an integer"));
  EXPECT_THAT(error_of(replace(kRoom, "waypoints:", "speed: 0\n  waypoints:")),
              HasSubstr("trajectory.speed: must be > 0"));
  EXPECT_THAT(error_of(replace(kRoom, "[[2, 2], [8, 2], [8, 6]]", "[[2, 2]]")),
              HasSubstr("at least two waypoints"));
  EXPECT_THAT(error_of("levels: [\n"), HasSubstr("YAML syntax error"));
}

TEST(SceneLoader, ARecordingThatWouldFillTheDiskIsRefused) {
  // Each of these made `simulate` allocate or write without end (bad_alloc, gigabytes).
  EXPECT_THAT(error_of(replace(kRoom, "levels:", "sensor: {rate_hz: 1e9}\nlevels:")),
              HasSubstr("sensor.rate_hz: must be <= 1000 Hz"));
  EXPECT_THAT(error_of(replace(kRoom, "waypoints:", "speed: 1000\n  waypoints:")),
              HasSubstr("trajectory.speed: must be <= 30 m/s"));
  EXPECT_THAT(error_of(replace(kRoom, "waypoints:", "laps: 2000000000\n  waypoints:")),
              HasSubstr("trajectory.laps: must be in [1, 10000]"));
  // Each value within its bounds, but together: 10,000 laps of a 16 m path at 1 m/s, 10 Hz.
  const std::string text = replace(kRoom, "waypoints:", "laps: 10000\n  waypoints:");
  EXPECT_THAT(error_of(text),
              HasSubstr("test.yaml:" + std::to_string(line_of(text, "laps:")) + ": trajectory.laps:"));
  EXPECT_THAT(error_of(text), HasSubstr("more than 1000000 (speed, laps)"));
  EXPECT_THAT(error_of(replace(kRoom, "waypoints:", "speed: 1e-9\n  waypoints:")),
              HasSubstr("more than 1000000"));
  EXPECT_NO_THROW(parse_scene(replace(kRoom, "waypoints:", "laps: 100\n  waypoints:"), "test.yaml", "."));
}

TEST(SceneLoader, ASceneBeyondTheBoundsOfABuildingIsRefused) {
  // A slab vertex at 1e12 m made a 4e13-pixel drawing.
  const std::string far = replace(kRoom, "[10,0],[10,8]", "[1e12,0],[1e12,8]");
  EXPECT_THAT(error_of(far),
              HasSubstr("test.yaml:" + std::to_string(line_of(far, "slab:")) + ": levels[0].slab:"));
  EXPECT_THAT(error_of(far), HasSubstr("is not a coordinate within 1e7 m"));
  EXPECT_THAT(error_of(replace(kRoom, "[10,0],[10,8]", "[20000,0],[20000,8]")), HasSubstr("more than 10 km"));
  EXPECT_THAT(error_of(replace(kRoom, "to: [10, 0]", "to: [50000, 0]")),
              HasSubstr("walls[0].to: the scene spans"));
}

TEST(SceneLoader, ValuesThatEmptyEveryScanOrWreckTheOdometryAreRefused) {
  // Each of these loaded and simulated: scans of 0 points, or an odometry of 1e300 m.
  const std::string high = replace(kRoom, "name: L0", "name: L0\n    elevation: 1e9");
  EXPECT_THAT(error_of(high),
              HasSubstr(at_line(high, "elevation:") + " levels[0].elevation: must lie in [-10000, 10000]"));
  EXPECT_THAT(error_of(replace(kRoom, "levels:", "sensor: {range_noise_std: 1e300}\nlevels:")),
              HasSubstr("sensor.range_noise_std: must lie in [0, 1]"));
  EXPECT_THAT(error_of(replace(kRoom, "levels:", "odometry: {trans_noise_per_m: 1e300}\nlevels:")),
              HasSubstr("odometry.trans_noise_per_m: must lie in [0, 1]"));
  const std::string mount = replace(kRoom, "levels:", "sensor: {mount_height: 10}\nlevels:");
  EXPECT_THAT(error_of(mount),
              HasSubstr(at_line(mount, "mount_height") +
                        " sensor.mount_height: 10 m is not below the ceiling of level 'L0' (3 m)"));
  // A box or a railing 2,000 km long (a bars railing reached 16.7 GB in 90 s).
  const std::string railing = replace(
      kRoom,
      "trajectory:", "railings:\n  - {level: L0, from: [1, 1], to: [2e6, 1], style: bars}\ntrajectory:");
  EXPECT_THAT(error_of(railing), HasSubstr("railings[0].to: the scene spans"));
  const std::string box = replace(
      kRoom, "trajectory:", "boxes:\n  - {level: L0, min: [1, 1, 0], max: [1e300, 2, 1]}\ntrajectory:");
  EXPECT_THAT(error_of(box), HasSubstr("boxes[0].max:"));
  EXPECT_THAT(error_of(box), HasSubstr("is not a coordinate within 1e7 m"));
  // A voxel map moved 1e300 m.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tsgraphs_scene_offsets_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream pcd(dir / "w.pcd");
    pcd << "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 "
           "0 1 0 0 0\n"
           "POINTS 1\nDATA ascii\n1 1 1\n";
  }
  for (const std::string offset : {"[1e300, 0, 0]", "[0, 0, 1e300]"}) {
    const std::string voxels = replace(
        kRoom, "trajectory:",
        "voxel_maps:\n  - {file: w.pcd, voxel_size: 0.1, level: L0, offset: " + offset + "}\ntrajectory:");
    try {
      parse_scene(voxels, "test.yaml", dir.string());
      ADD_FAILURE() << offset;
    } catch (const InputError& e) {
      EXPECT_THAT(std::string(e.what()), HasSubstr("voxel_maps[0].offset:")) << offset;
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneLoader, MissingFileAndVoxelMapFile) {
  try {
    load_scene("/nonexistent/scene.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/scene.yaml"));
  }
  const std::string text = kRoom + "voxel_maps:\n  - {file: maps/none.pcd, voxel_size: 0.1, level: L0}\n";
  EXPECT_THAT(error_of(text), HasSubstr("voxel_maps[0].file: no such file"));
}

TEST(SceneLoader, WalkableHeightFollowsRamps) {
  const std::string text = R"(levels:
  - {name: low, elevation: 0.0, slab: [[0,0],[20,0],[20,10],[0,10]]}
  - name: high
    elevation: 2.0
    slab: [[0,0],[20,0],[20,10],[0,10]]
    voids: [[[4,2],[16,2],[16,4],[4,4]]]
ramps:
  - {from_level: low, to_level: high, polygon: [[4,2],[16,2],[16,4],[4,4]], axis: [1, 0]}
trajectory:
  waypoints: [[2, 3, low], [10, 3], [18, 3, high]]
)";
  const Scene s = parse_scene(text, "ramp.yaml", ".");
  double z = -1;
  ASSERT_TRUE(walkable_height(s, 0, {10, 3}, &z));
  EXPECT_NEAR(z, 1.0, 1e-9);  // half way up a 12 m ramp rising 2 m
  ASSERT_TRUE(walkable_height(s, 1, {4.6, 3}, &z));
  EXPECT_NEAR(z, 0.1, 1e-9);
  ASSERT_TRUE(walkable_height(s, 1, {10, 8}, &z));
  EXPECT_NEAR(z, 2.0, 1e-9);
}

TEST(SceneLoader, WarnsAboutPathsThroughWallsBoxesAndVoids) {
  EXPECT_TRUE(parse_scene(kRoom, "test.yaml", ".").warnings.empty());
  // A second wall across the room, x = 5: the legs out (y = 2) and back (the closing leg)
  // both cross it.
  const std::string wall =
      replace(kRoom, "trajectory:", "  - {level: L0, from: [5, 1], to: [5, 7]}\ntrajectory:");
  const Scene s1 = parse_scene(wall, "test.yaml", ".");
  ASSERT_EQ(s1.warnings.size(), 2u);
  EXPECT_THAT(s1.warnings[0], HasSubstr("trajectory.waypoints[0]-[1]: the path crosses wall walls[1]"));
  EXPECT_THAT(s1.warnings[1], HasSubstr("trajectory.waypoints[2]-[0]: the path crosses wall walls[1]"));
  EXPECT_THAT(s1.warnings[0], HasSubstr("test.yaml:" + std::to_string(line_of(wall, "waypoints:")) + ":"));
  // Through a door it is fine.
  const std::string door =
      replace(wall, "to: [5, 7]}", "to: [5, 7], openings: [{at: 1.0, width: 1.0}, {at: 3.0, width: 1.2}]}");
  EXPECT_TRUE(parse_scene(door, "test.yaml", ".").warnings.empty());
  const std::string box = replace(
      kRoom, "trajectory:", "boxes: [{level: L0, min: [4, 1.5, 0], max: [4.5, 2.5, 1]}]\ntrajectory:");
  const Scene s2 = parse_scene(box, "test.yaml", ".");
  ASSERT_EQ(s2.warnings.size(), 1u);
  EXPECT_THAT(s2.warnings[0], HasSubstr("crosses box boxes[0]"));
  // A hanging box (a shelf above head height) is not in the way.
  EXPECT_TRUE(
      parse_scene(replace(box, "[4, 1.5, 0], max: [4.5, 2.5, 1]", "[4, 1.5, 2.2], max: [4.5, 2.5, 2.8]"),
                  "test.yaml", ".")
          .warnings.empty());
  const std::string in_void =
      replace(kRoom, "    slab: [[0,0],[10,0],[10,8],[0,8]]\n",
              "    slab: [[0,0],[10,0],[10,8],[0,8]]\n    voids: [[[7.5,3],[8.5,3],[8.5,4],[7.5,4]]]\n");
  const Scene s3 = parse_scene(in_void, "test.yaml", ".");
  ASSERT_EQ(s3.warnings.size(), 1u);
  EXPECT_THAT(s3.warnings[0], HasSubstr("trajectory.waypoints[1]-[2]: the path crosses a void of level L0"));
}

TEST(SceneLoader, WarnsWhenACeilingIsAboveTheNextFloor) {
  const std::string text = R"(levels:
  - {name: G, elevation: 0.0, ceiling: 2.7, slab: [[0,0],[10,0],[10,10],[0,10]]}
  - {name: U, elevation: 2.0, slab: [[5,5],[15,5],[15,15],[5,15]]}
trajectory: {waypoints: [[1, 1], [3, 1]]}
)";
  const Scene s = parse_scene(text, "stack.yaml", ".");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_THAT(s.warnings[0],
              HasSubstr("stack.yaml:3: levels: the ceiling of G (z 2.7) is above the floor of U (z 2)"));
  // Side by side (no overlap), the same heights are fine.
  std::string apart = text;
  apart.replace(apart.find("[[5,5],[15,5],[15,15],[5,15]]"), 29, "[[20,0],[30,0],[30,10],[20,10]]");
  EXPECT_TRUE(parse_scene(apart, "stack.yaml", ".").warnings.empty());
}

TEST(SceneLoader, WallEndsThatMeetAreJoined) {
  const std::string text = R"(levels: [{name: L0, slab: [[0,0],[10,0],[10,8],[0,8]]}]
walls:
  - {level: L0, from: [0, 0], to: [10, 0]}
  - {level: L0, from: [10, 0], to: [10, 8]}
  - {level: L0, from: [3, 4], to: [6, 4]}
trajectory: {waypoints: [[2, 2], [8, 2]]}
)";
  const Scene s = parse_scene(text, "join.yaml", ".");
  EXPECT_FALSE(s.walls[0].joined_from);
  EXPECT_TRUE(s.walls[0].joined_to);
  EXPECT_TRUE(s.walls[1].joined_from);
  EXPECT_FALSE(s.walls[2].joined_from || s.walls[2].joined_to);
}

TEST(SceneLoader, RejectsScansTooLargeForMemory) {
  const std::string text = replace(kRoom, "levels:", "sensor: {channels: 100000, columns: 100000}\nlevels:");
  EXPECT_THAT(error_of(text), HasSubstr("sensor.columns: channels x columns = 10000000000 rays per scan"));
}

TEST(SceneLoader, GlassRailingsHaveATransmission) {
  const std::string railing =
      "railings:\n  - {level: L0, from: [1, 5], to: [9, 5], style: glass, transmission: 0.6}\n";
  const Scene s = parse_scene(replace(kRoom, "trajectory:", railing + "trajectory:"), "test.yaml", ".");
  ASSERT_EQ(s.railings.size(), 1u);
  EXPECT_EQ(s.railings[0].style, RailingStyle::kGlass);
  EXPECT_DOUBLE_EQ(s.railings[0].transmission, 0.6);
  const std::string bad = replace(kRoom, "trajectory:", replace(railing, "0.6", "1.5") + "trajectory:");
  EXPECT_THAT(error_of(bad), HasSubstr("transmission: must lie in [0, 1]"));
  const std::string solid = replace(kRoom, "trajectory:", replace(railing, "glass", "solid") + "trajectory:");
  EXPECT_THAT(error_of(solid), HasSubstr("only a glass railing lets rays through"));
}

TEST(SceneLoader, AnOpeningMayHoldAGlassPane) {
  const std::string wall =  // a second wall in kRoom's list
      "  - {level: L0, from: [0, 5], to: [10, 5], openings: [{at: 3, width: 1.5, height: 1.2, sill: 0.9, "
      "transmission: 0.7}, {at: 7, width: 1.0}]}\n";
  const Scene s = parse_scene(replace(kRoom, "trajectory:", wall + "trajectory:"), "test.yaml", ".");
  ASSERT_EQ(s.walls.back().openings.size(), 2u);
  EXPECT_DOUBLE_EQ(s.walls.back().openings[0].transmission, 0.7);
  EXPECT_DOUBLE_EQ(s.walls.back().openings[1].transmission, 1.0);  // no pane: an open door
  const std::vector<GlassPane> panes = glass_panes(s.walls.back());
  ASSERT_EQ(panes.size(), 1u);
  EXPECT_DOUBLE_EQ(panes[0].s0, 2.25);
  EXPECT_DOUBLE_EQ(panes[0].z0, 0.9);
  EXPECT_DOUBLE_EQ(panes[0].z1, 2.1);
  const std::string bad = replace(kRoom, "trajectory:", replace(wall, "0.7", "-0.1") + "trajectory:");
  EXPECT_THAT(error_of(bad), HasSubstr("transmission: must lie in [0, 1]"));
}
