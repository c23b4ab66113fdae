// `tsgraphs import-map` as a user calls it: a drawn PGM map, its YAML and a PNG of room labels
// become a scene file and its wall voxels that load and draw without a warning; bad input
// (a broken PGM header, a YAML naming a missing image, labels of another size, an unknown
// YAML key) is one line naming the file and place, exit status 2, and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "map_test_support.hpp"
#include "test_support.hpp"
#include "tsgraphs/io/image.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/io/room_labels.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using test::cli;

namespace {

std::set<std::string> names_in(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

class ImportMapCli : public test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    drawn_ = test::draw_test_building();
    fs::create_directories(dir_ / "maps");
    fs::create_directories(dir_ / "out");
    write_file("maps/floor.pgm", io::encode_pgm(drawn_.map));
    write_file("maps/floor_gt.png", io::encode_png(drawn_.labels));
    write_file("maps/floor.yaml", test::map_yaml("floor.pgm"));
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// Runs import-map with `args` after the map; expects exit 2, a one-line error holding every
  /// one of `expected`, and an empty output folder.
  void expect_refused(const std::string& yaml, const std::string& args,
                      const std::vector<std::string>& expected) {
    std::string err;
    EXPECT_EQ(cli("import-map " + yaml + " --out " + path("out/scene.yaml") + " " + args, &err), 2) << err;
    ASSERT_FALSE(err.empty());
    EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
    for (const std::string& e : expected)
      EXPECT_NE(err.find(e), std::string::npos) << "'" << e << "' in " << err;
    EXPECT_TRUE(names_in(dir_ / "out").empty()) << *names_in(dir_ / "out").begin();
  }

  test::DrawnMap drawn_;
};

}  // namespace

TEST_F(ImportMapCli, WritesASceneThatLoadsAndDrawsWithoutWarnings) {
  std::string err;
  ASSERT_EQ(cli("import-map " + path("maps/floor.yaml") + " --out " + path("out/scene.yaml") + " --rooms " +
                    path("maps/floor_gt.png") + " --laps 1",
                &err),
            0)
      << err;
  // The closet behind its narrow door is named and left out; nothing else is warned about.
  EXPECT_NE(err.find("warning: " + path("maps/floor.yaml") + ": room 'room_5'"), std::string::npos) << err;
  EXPECT_EQ(err.find("warning"), err.rfind("warning")) << err;
  EXPECT_NE(err.find("import-map: "), std::string::npos);
  EXPECT_EQ(names_in(dir_ / "out"), (std::set<std::string>{"scene.yaml", "scene_walls.pcd"}));
  const std::string yaml = test::read_file(dir_ / "out" / "scene.yaml");
  EXPECT_NE(yaml.find("file: \"scene_walls.pcd\""), std::string::npos);  // named relative to the scene
  const scene::Scene s = scene::load_scene(path("out/scene.yaml"));
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(s.name, "floor");
  EXPECT_EQ(s.rooms.size(), 5u);
  EXPECT_EQ(s.levels[0].voids.size(), 1u);
  EXPECT_EQ(s.trajectory.laps, 1);
  const PointCloud walls = io::read_pcd(path("out/scene_walls.pcd"));
  EXPECT_GT(walls.size(), 1000u);
  EXPECT_EQ(walls.size() % static_cast<std::size_t>(test::kWallHeightCells), 0u);
  ASSERT_EQ(cli("draw-scene " + path("out/scene.yaml") + " --out " + path("scene.svg"), &err), 0) << err;
  EXPECT_EQ(err.find("warning"), std::string::npos) << err;
  // The same input gives the same files.
  fs::create_directories(dir_ / "again");
  ASSERT_EQ(cli("-q import-map " + path("maps/floor.yaml") + " --out " + path("again/scene.yaml") +
                    " --rooms " + path("maps/floor_gt.png") + " --laps 1",
                &err),
            0);
  EXPECT_EQ(test::read_file(dir_ / "again" / "scene.yaml"), yaml);
  EXPECT_EQ(test::read_file(dir_ / "again" / "scene_walls.pcd"),
            test::read_file(dir_ / "out" / "scene_walls.pcd"));
}

TEST_F(ImportMapCli, BrokenPgmHeader) {
  write_file("maps/floor.pgm", "P5\n280 two hundred\n255\n");
  expect_refused(path("maps/floor.yaml"), "", {path("maps/floor.pgm"), "height is not a number"});
}

TEST_F(ImportMapCli, YamlNamingAMissingImage) {
  write_file("maps/lost.yaml", test::map_yaml("nowhere.pgm"));
  expect_refused(path("maps/lost.yaml"), "",
                 {path("maps/lost.yaml") + ":1: image: no such image file", "nowhere.pgm"});
}

TEST_F(ImportMapCli, LabelsOfAnotherSize) {
  io::Image small = drawn_.labels;
  small.height = 100;
  small.samples.resize(static_cast<std::size_t>(small.width) * small.height);
  write_file("maps/small_gt.png", io::encode_png(small));
  expect_refused(path("maps/floor.yaml"), "--rooms " + path("maps/small_gt.png"),
                 {path("maps/small_gt.png"), "280 x 100", path("maps/floor.pgm"), "280 x 200"});
}

TEST_F(ImportMapCli, UnknownYamlKey) {
  write_file("maps/odd.yaml", test::map_yaml("floor.pgm") + "frame_id: map\n");
  expect_refused(path("maps/odd.yaml"), "", {path("maps/odd.yaml") + ":7: unknown key 'frame_id'"});
}

TEST_F(ImportMapCli, BadOptions) {
  expect_refused(path("maps/floor.yaml"), "--sensor kinect", {"--sensor", "kinect"});
  expect_refused(path("maps/floor.yaml"), "--ceiling 0", {"--ceiling"});
  expect_refused(path("maps/floor.yaml"), "--clearance 3", {path("maps/floor.yaml"), "--clearance"});
}

TEST_F(ImportMapCli, BoundsAreCheckedBeforeAnyWork) {
  // 10,001 laps, or 10,000 of a path too long for them: refused at once (10,000 laps ran for
  // minutes and wrote a scene that did not load).
  expect_refused(path("maps/floor.yaml"), "--laps 10001",
                 {"--laps: must be a whole number in [1, 10000], not '10001'"});
  expect_refused(path("maps/floor.yaml"), "--laps 10000",
                 {path("maps/floor.yaml"), "--laps: the path makes"});
  // A map placed 1e9 m away: its scene would not load (it was an internal error).
  write_file("maps/far.yaml", test::map_yaml("floor.pgm", "[1.0e9, 0.0, 0.0]"));
  expect_refused(path("maps/far.yaml"), "", {path("maps/far.yaml"), "origin: the map reaches [1e+09"});
}

TEST_F(ImportMapCli, OutputsNeverOverwriteTheInputs) {
  // Each of these overwrote the map it read, exit 0.
  for (const std::string out : {"maps/floor.yaml", "maps/floor.pgm", "maps/floor_gt.png"}) {
    std::string err;
    const std::string before = test::read_file(dir_ / out);
    EXPECT_EQ(cli("import-map " + path("maps/floor.yaml") + " --rooms " + path("maps/floor_gt.png") +
                      " --out " + path(out),
                  &err),
              2)
        << out;
    EXPECT_NE(err.find("tsgraphs: error: --out: " + path(out) + " is the command's input"), std::string::npos)
        << err;
    EXPECT_EQ(test::read_file(dir_ / out), before) << out;
  }
}

TEST_F(ImportMapCli, LabelImageWithNoRoomWarns) {
  io::Image blank = drawn_.labels;
  std::fill(blank.samples.begin(), blank.samples.end(), test::kUnknownPx);
  write_file("maps/blank_gt.png", io::encode_png(blank));
  std::string err;
  ASSERT_EQ(cli("-q import-map " + path("maps/floor.yaml") + " --out " + path("out/scene.yaml") +
                    " --rooms " + path("maps/blank_gt.png"),
                &err),
            0)
      << err;
  EXPECT_NE(err.find("tsgraphs: warning: " + path("maps/blank_gt.png") + ": no room: every pixel is grey"),
            std::string::npos)
      << err;
  EXPECT_TRUE(scene::load_scene(path("out/scene.yaml")).rooms.empty());
}

TEST_F(ImportMapCli, ColourLabelsAreReadAsOneColourPerRoom) {
  // The drawn labels with each room a colour of its own (black elsewhere).
  const io::RoomLabels ipa = io::room_labels(drawn_.labels);
  io::Image colour;
  colour.width = drawn_.labels.width;
  colour.height = drawn_.labels.height;
  colour.channels = 3;
  colour.samples.assign(static_cast<std::size_t>(colour.width) * colour.height * 3, 0);
  for (int y = 0; y < colour.height; ++y)
    for (int x = 0; x < colour.width; ++x) {
      const int k = ipa.at(x, colour.height - 1 - y);
      if (k < 0) continue;
      std::uint8_t* p = &colour.samples[(static_cast<std::size_t>(y) * colour.width + x) * 3];
      p[0] = static_cast<std::uint8_t>(40 + 40 * k), p[1] = 200,
      p[2] = static_cast<std::uint8_t>(220 - 40 * k);
    }
  write_file("maps/floor_colours.png", io::encode_png(colour));
  std::string err;
  ASSERT_EQ(cli("import-map " + path("maps/floor.yaml") + " --out " + path("out/scene.yaml") + " --rooms " +
                    path("maps/floor_colours.png"),
                &err),
            0)
      << err;
  EXPECT_NE(err.find("5 rooms (one colour per room)"), std::string::npos) << err;
  const scene::Scene s = scene::load_scene(path("out/scene.yaml"));
  ASSERT_EQ(s.rooms.size(), 5u);
  EXPECT_NE(test::read_file(dir_ / "out" / "scene.yaml")
                .find("with rooms from floor_colours.png (one colour per room)"),
            std::string::npos);
}

TEST_F(ImportMapCli, MapWithoutWallsHasNoVoxelFile) {
  // A free rectangle in unknown space: floor and a path, no occupied cell, so no walls file.
  io::Image img = drawn_.map;
  std::fill(img.samples.begin(), img.samples.end(), test::kUnknownPx);
  test::fill_box(&img, {2.0, 2.0, 8.0, 6.0}, test::kFreePx);
  write_file("maps/open.pgm", io::encode_pgm(img));
  write_file("maps/open.yaml", test::map_yaml("open.pgm"));
  std::string err;
  ASSERT_EQ(cli("-q import-map " + path("maps/open.yaml") + " --out " + path("out/open.yaml"), &err), 0)
      << err;
  // Said even with -q: a scene without walls is rarely what the user wants.
  EXPECT_EQ(err, "tsgraphs: warning: " + path("maps/open.yaml") +
                     ": the map has no occupied cell: the scene has no wall\n");
  EXPECT_EQ(names_in(dir_ / "out"), (std::set<std::string>{"open.yaml"}));
  const scene::Scene s = scene::load_scene(path("out/open.yaml"));
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_TRUE(s.voxel_maps.empty());
  EXPECT_NEAR(area(s.levels[0].slab), 24.0, 1e-6);
}
