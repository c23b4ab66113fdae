// `tsgraphs segment-map` as a user calls it: a drawn floor as a PGM map and its YAML, its true
// rooms as a colour label image; the label image written reads back with the map's rooms, the
// figures line and JSON say they all match; bad input is one line, exit status 2, nothing written.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>

#include "drawn_floor_support.hpp"
#include "test_support.hpp"
#include "tsgraphs/io/image.hpp"
#include "tsgraphs/io/occupancy_map.hpp"
#include "tsgraphs/io/room_labels.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using test::cli;

namespace {

/// The floor as map_saver writes it (254 free, 0 occupied, 205 unknown), row 0 at the top.
io::Image map_image(const test::DrawnFloor& d) {
  io::Image img;
  img.width = d.frame.cols;
  img.height = d.frame.rows;
  img.samples.resize(d.frame.size());
  for (int r = 0; r < d.frame.rows; ++r)
    for (int c = 0; c < d.frame.cols; ++c) {
      const test::FloorCell v = d.cells[d.frame.index(c, r)];
      img.samples[static_cast<std::size_t>(d.frame.rows - 1 - r) * d.frame.cols + c] =
          v == test::FloorCell::kFree       ? 254
          : v == test::FloorCell::kOccupied ? 0
                                            : 205;
    }
  return img;
}

/// The true rooms, one colour each, black none.
io::Image truth_image(const test::DrawnFloor& d) {
  io::Image img;
  img.width = d.frame.cols;
  img.height = d.frame.rows;
  img.channels = 3;
  img.samples.assign(d.frame.size() * 3, 0);
  for (int r = 0; r < d.frame.rows; ++r)
    for (int c = 0; c < d.frame.cols; ++c) {
      const int k = d.truth[d.frame.index(c, r)];
      if (k < 0) continue;
      const std::size_t at = (static_cast<std::size_t>(d.frame.rows - 1 - r) * d.frame.cols + c) * 3;
      img.samples[at] = static_cast<std::uint8_t>(40 + 50 * k);
      img.samples[at + 1] = static_cast<std::uint8_t>(200 - 30 * k);
      img.samples[at + 2] = 90;
    }
  return img;
}

class SegmentMapCli : public test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    floor_ = test::draw_floor();
    write_file("floor.pgm", io::encode_pgm(map_image(floor_)));
    write_file("floor.yaml", "image: floor.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n");
    write_file("truth.png", io::encode_png(truth_image(floor_)));
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  test::DrawnFloor floor_;
};

}  // namespace

TEST_F(SegmentMapCli, LabelsTheRoomsAndScoresThemAgainstTheTruth) {
  std::string out, err;
  ASSERT_EQ(test::run_tsgraphs("segment-map " + path("floor.yaml") + " --out " + path("rooms.png") +
                                   " --rooms " + path("truth.png") + " --metrics " + path("figures.json"),
                               &out, &err),
            0)
      << err;
  EXPECT_NE(out.find("5 rooms"), std::string::npos) << out;
  EXPECT_NE(out.find("F1 100.0 %"), std::string::npos) << out;
  // The label image reads back as one colour per room, of the map's size.
  const io::OccupancyMap map = io::read_occupancy_map(path("floor.yaml"));
  const io::RoomLabels labels = io::read_room_labels(path("rooms.png"), map);
  EXPECT_EQ(labels.convention, io::RoomLabelConvention::kColour);
  EXPECT_EQ(labels.count, 5);
  const nlohmann::json j = nlohmann::json::parse(test::read_file(path("figures.json")));
  EXPECT_EQ(j["rooms"], 5);
  EXPECT_EQ(j["room_match"]["matched"], 5);
  EXPECT_GT(j["ipa"]["precision_micro"].get<double>(), 0.95);
  EXPECT_GT(j["ipa"]["recall_micro"].get<double>(), 0.95);
  EXPECT_FALSE(j["walls"].empty());
}

TEST_F(SegmentMapCli, BadInputWritesNothing) {
  // Labels of another size than the map.
  io::Image small = truth_image(floor_);
  small.width -= 1;
  small.samples.resize(static_cast<std::size_t>(small.width) * small.height * 3);
  write_file("small.png", io::encode_png(small));
  std::string err;
  EXPECT_EQ(cli("segment-map " + path("floor.yaml") + " --out " + path("rooms.png") + " --rooms " +
                    path("small.png"),
                &err),
            2);
  EXPECT_NE(err.find("small.png"), std::string::npos) << err;
  EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
  EXPECT_FALSE(fs::exists(path("rooms.png")));
  // An output that is an input.
  EXPECT_EQ(cli("segment-map " + path("floor.yaml") + " --out " + path("truth.png") + " --rooms " +
                    path("truth.png"),
                &err),
            2);
  EXPECT_NE(err.find("truth.png"), std::string::npos) << err;
  // A map that does not exist.
  EXPECT_EQ(cli("segment-map " + path("none.yaml") + " --out " + path("rooms.png"), &err), 2);
  EXPECT_NE(err.find("none.yaml"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(path("rooms.png")));
}
