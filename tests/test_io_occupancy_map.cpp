// map_server occupancy maps: the YAML's keys, defaults and errors (file:line: key), the image
// path relative to the YAML, and each pixel classified exactly as map_server's image loader
// does (thresholds, negate, the three modes, colour and alpha channels, row order).
#include <gtest/gtest.h>

#include <filesystem>

#include "test_support.hpp"
#include "tsgraphs/io/image.hpp"
#include "tsgraphs/io/occupancy_map.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;
using tsgraphs::test::input_error_of;
using tsgraphs::test::TempDirTest;

namespace {

Image image(int w, int h, int channels, std::vector<std::uint8_t> v) {
  Image img;
  img.width = w;
  img.height = h;
  img.channels = channels;
  img.samples = std::move(v);
  return img;
}

std::vector<CellState> states(const Image& img, const MapMetadata& meta) { return classify(img, meta).cells; }

constexpr CellState F = CellState::kFree, O = CellState::kOccupied, U = CellState::kUnknown;

class OccupancyMapTest : public TempDirTest {};

}  // namespace

TEST_F(OccupancyMapTest, ReadsEveryKey) {
  const MapMetadata m = parse_map_yaml(
      "image: maps/floor.pgm\nresolution: 0.025\norigin: [-10.5, 3.25, 0.5]\nnegate: 1\n"
      "occupied_thresh: 0.7\nfree_thresh: 0.2\nmode: scale\n",
      "site/map.yaml", "site");
  EXPECT_EQ(m.image, "site/maps/floor.pgm");
  EXPECT_DOUBLE_EQ(m.resolution, 0.025);
  EXPECT_DOUBLE_EQ(m.origin_x, -10.5);
  EXPECT_DOUBLE_EQ(m.origin_y, 3.25);
  EXPECT_DOUBLE_EQ(m.origin_yaw, 0.5);
  EXPECT_TRUE(m.negate);
  EXPECT_DOUBLE_EQ(m.occupied_thresh, 0.7);
  EXPECT_DOUBLE_EQ(m.free_thresh, 0.2);
  EXPECT_EQ(m.mode, MapMode::kScale);
  // map_saver's defaults for what is left out; an absolute image path stays as it is.
  const MapMetadata d =
      parse_map_yaml("image: /data/m.png\nresolution: 0.05\norigin: [0, 0, 0]\n", "m.yaml", ".");
  EXPECT_EQ(d.image, "/data/m.png");
  EXPECT_FALSE(d.negate);
  EXPECT_DOUBLE_EQ(d.occupied_thresh, 0.65);
  EXPECT_DOUBLE_EQ(d.free_thresh, 0.196);
  EXPECT_EQ(d.mode, MapMode::kTrinary);
  EXPECT_TRUE(
      parse_map_yaml("image: a.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: true\n", "m.yaml", ".").negate);
}

TEST_F(OccupancyMapTest, BadYamlNamesFileLineAndKey) {
  const std::string base = "image: a.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  const auto fails = [&](const std::string& text, const std::string& what) {
    const std::string msg = input_error_of([&] { parse_map_yaml(text, "map.yaml", "."); });
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  };
  fails(base + "colour: red\n", "map.yaml:4: unknown key 'colour'");
  fails("resolution: 0.05\norigin: [0, 0, 0]\n", "missing required key 'image'");
  fails("image: a.pgm\norigin: [0, 0, 0]\n", "missing required key 'resolution'");
  fails("image: a.pgm\nresolution: 0.05\n", "missing required key 'origin'");
  fails("image: a.pgm\nresolution: -1\norigin: [0, 0, 0]\n", "map.yaml:2: resolution: must lie in (0, 10]");
  fails("image: a.pgm\nresolution: 0.05\norigin: [0, 0]\n", "map.yaml:3: origin: expected [x, y, yaw]");
  fails("image: a.pgm\nresolution: 0.05\norigin: [0, zero, 0]\n", "map.yaml:3: origin: expected a number");
  fails(base + "negate: 2\n", "map.yaml:4: negate: expected 0 or 1");
  fails(base + "mode: fancy\n", "map.yaml:4: mode: unknown mode 'fancy'");
  fails(base + "occupied_thresh: 1.5\n", "map.yaml:4: occupied_thresh: must lie in [0, 1]");
  fails(base + "occupied_thresh: 0.1\nfree_thresh: 0.3\n",
        "map.yaml:5: free_thresh: must not exceed occupied_thresh");
  fails("image: [a\n", "map.yaml:");
}

// Issue 52: negate's and mode's values and the image's name were quoted raw. Quoted printable.
TEST_F(OccupancyMapTest, MessagesQuoteTheFilePrintable) {
  const std::string base = "image: a.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  const auto error_of = [&](const std::string& text) {
    return input_error_of([&] { parse_map_yaml(text, "map.yaml", "."); });
  };
  EXPECT_EQ(error_of(base + "negate: \"\\x01\\x02\"\n"),
            "map.yaml:4: negate: expected 0 or 1 (got '\\x01\\x02')");
  EXPECT_EQ(error_of(base + "mode: \"tri\\x1bnary\"\n"),
            "map.yaml:4: mode: unknown mode 'tri\\x1bnary' (trinary, scale, raw)");
  const std::string yaml =
      write_file("map.yaml", "image: \"m\\x07.pgm\"\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_EQ(input_error_of([&] { read_occupancy_map(yaml); }),
            yaml + ":1: image: no such image file: " + (dir_ / "m\\x07.pgm").string());
}

TEST_F(OccupancyMapTest, TrinaryThresholdsAsMapServer) {
  MapMetadata meta;  // occupied above 0.65, free below 0.196 of p = (255 - v) / 255
  // 205 gives p = 0.19608 (unknown: what map_saver writes for unknown); 206 gives 0.1922 (free);
  // 89 gives 0.651 (occupied), 90 gives 0.647 (unknown).
  const Image img = image(6, 1, 1, {0, 89, 90, 205, 206, 254});
  EXPECT_EQ(states(img, meta), (std::vector<CellState>{O, O, U, U, F, F}));
  meta.negate = true;  // p = v / 255
  EXPECT_EQ(states(img, meta), (std::vector<CellState>{F, U, U, O, O, O}));
}

TEST_F(OccupancyMapTest, ImageTopRowIsTheMapsLastRow) {
  const OccupancyMap m = classify(image(2, 3, 1, {0, 0, 254, 254, 205, 205}), MapMetadata{});
  EXPECT_EQ(m.width, 2);
  EXPECT_EQ(m.height, 3);
  EXPECT_EQ(m.at(0, 2), O);  // image row 0
  EXPECT_EQ(m.at(1, 1), F);
  EXPECT_EQ(m.at(0, 0), U);  // image row 2: the map's bottom
}

TEST_F(OccupancyMapTest, ColourIsTheMeanOfTheChannelsAlphaOnlyInTrinary) {
  MapMetadata meta;
  // RGB: (255, 255, 0) has mean 170 (p 0.333, unknown); (0, 0, 255) mean 85 (p 0.667, occupied).
  EXPECT_EQ(states(image(2, 1, 3, {255, 255, 0, 0, 0, 255}), meta), (std::vector<CellState>{U, O}));
  // RGBA white with alpha 0: trinary averages alpha in (190.5: unknown); scale leaves it out (free).
  const Image rgba = image(1, 1, 4, {254, 254, 254, 0});
  EXPECT_EQ(states(rgba, meta), (std::vector<CellState>{U}));
  meta.mode = MapMode::kScale;
  EXPECT_EQ(states(rgba, meta), (std::vector<CellState>{F}));
  // Grey + alpha is RGBA to map_server's reader: in trinary (3 g + a) / 4.
  meta.mode = MapMode::kTrinary;
  EXPECT_EQ(states(image(2, 1, 2, {254, 0, 254, 255}), meta), (std::vector<CellState>{U, F}));
}

TEST_F(OccupancyMapTest, ScaleAndRawModes) {
  MapMetadata meta;
  meta.mode = MapMode::kScale;  // in-between values are partial occupancy: neither free nor a wall
  EXPECT_EQ(states(image(3, 1, 1, {0, 150, 254}), meta), (std::vector<CellState>{O, U, F}));
  meta.mode = MapMode::kRaw;  // the value is the occupancy in percent; 255 (ROS's -1) unknown
  EXPECT_EQ(states(image(7, 1, 1, {0, 19, 20, 65, 66, 100, 255}), meta),
            (std::vector<CellState>{F, F, U, U, O, O, U}));
  EXPECT_EQ(states(image(1, 1, 1, {101}), meta), (std::vector<CellState>{U}));
  meta.negate = true;  // 255 - v
  EXPECT_EQ(states(image(2, 1, 1, {255, 155}), meta), (std::vector<CellState>{F, O}));
}

TEST_F(OccupancyMapTest, ImagePathIsRelativeToTheYamlAndAMissingImageNamesTheKey) {
  std::filesystem::create_directories(dir_ / "site" / "maps");
  Image img = image(3, 2, 1, {0, 254, 205, 254, 254, 0});
  std::ofstream(dir_ / "site" / "maps" / "floor.pgm", std::ios::binary) << encode_pgm(img);
  const std::string yaml =
      write_file("site/map.yaml", "resolution: 0.05\nimage: maps/floor.pgm\norigin: [1, 2, 0]\n");
  const OccupancyMap m = read_occupancy_map(yaml);
  EXPECT_EQ(m.width, 3);
  EXPECT_EQ(m.at(0, 1), O);
  EXPECT_EQ(m.at(2, 0), O);
  EXPECT_DOUBLE_EQ(m.meta.origin_y, 2.0);
  const std::string bad =
      write_file("site/other.yaml", "resolution: 0.05\nimage: maps/none.pgm\norigin: [1, 2, 0]\n");
  const std::string msg = input_error_of([&] { read_occupancy_map(bad); });
  EXPECT_NE(msg.find(bad + ":2: image: no such image file"), std::string::npos) << msg;
  EXPECT_NE(input_error_of([&] { read_occupancy_map((dir_ / "nothing.yaml").string()); }).find("cannot open"),
            std::string::npos);
}
