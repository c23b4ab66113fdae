// Room-label images: the convention told from the image (grey -> IPA, any colour -> one colour
// per room), IPA rooms as 8-connected white regions, colour rooms in as many pieces as they
// have, small regions and colours dropped, reading order, rows flipped to the map's order, a
// warning for an image with no room, and the size checked against the map.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "tsgraphs/io/image.hpp"
#include "tsgraphs/io/occupancy_map.hpp"
#include "tsgraphs/io/room_labels.hpp"
#include "tsgraphs/io/room_labels_writer.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;

namespace {

using Rgb = std::array<std::uint8_t, 3>;

/// An RGB image, every pixel `fill`.
Image rgb_image(int w, int h, Rgb fill) {
  Image img;
  img.width = w;
  img.height = h;
  img.channels = 3;
  for (int i = 0; i < w * h; ++i) img.samples.insert(img.samples.end(), fill.begin(), fill.end());
  return img;
}

/// Paints the pixels [x0, x1) x [y0, y1) (row 0 at the image's top) of an image of any channels.
void paint(Image* img, int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int ch = 0; ch < img->channels; ++ch)
        img->samples[(static_cast<std::size_t>(y) * img->width + x) * img->channels + ch] =
            c[std::min(ch, 2)];
}

Image grey_image(int w, int h, std::uint8_t v) {
  Image img;
  img.width = w;
  img.height = h;
  img.channels = 1;
  img.samples.assign(static_cast<std::size_t>(w) * h, v);
  return img;
}

/// The room at pixel (x, y) of the image (row 0 at the top) in the labels' bottom-first rows.
int room_at_pixel(const RoomLabels& l, int x, int y) { return l.at(x, l.height - 1 - y); }

}  // namespace

TEST(RoomLabels, ColourImageGivesOneRoomPerColourInAsManyPiecesAsItHas) {
  Image img = rgb_image(60, 40, {0, 0, 0});
  const Rgb red{200, 30, 30}, green{30, 200, 30}, blue{30, 30, 200}, speck{9, 9, 9};
  paint(&img, 30, 2, 50, 12, green);  // first in reading order: its top row is the image's row 2
  paint(&img, 5, 5, 25, 15, red);     // red, piece 1
  paint(&img, 5, 25, 15, 35, red);    // red, piece 2, apart from piece 1
  paint(&img, 20, 20, 55, 38, blue);
  paint(&img, 0, 39, 50, 40, speck);  // a colour of 50 pixels: no room
  const RoomLabels l = room_labels(img);
  EXPECT_EQ(l.convention, RoomLabelConvention::kColour);
  EXPECT_STREQ(convention_name(l.convention), "one colour per room");
  ASSERT_EQ(l.count, 3);
  EXPECT_EQ(l.colours, (std::vector<Rgb>{green, red, blue}));
  EXPECT_EQ(l.pixels, (std::vector<std::size_t>{200, 300, 630}));
  EXPECT_EQ(l.small_left_out, 1u);
  EXPECT_TRUE(l.warnings.empty());
  EXPECT_EQ(room_at_pixel(l, 40, 5), 0);
  EXPECT_EQ(room_at_pixel(l, 10, 10), 1);
  EXPECT_EQ(room_at_pixel(l, 10, 30), 1);  // the second piece is the same room
  EXPECT_EQ(room_at_pixel(l, 30, 30), 2);
  EXPECT_EQ(room_at_pixel(l, 2, 2), -1);    // black
  EXPECT_EQ(room_at_pixel(l, 10, 39), -1);  // the small colour
  EXPECT_EQ(l.at(10, 0), -1);               // the labels' row 0 is the image's bottom row
  // Alpha is dropped: the same image as RGBA with a transparent corner reads the same.
  Image rgba;
  rgba.width = img.width;
  rgba.height = img.height;
  rgba.channels = 4;
  for (std::size_t i = 0; i < img.samples.size(); i += 3) {
    rgba.samples.insert(rgba.samples.end(), img.samples.begin() + i, img.samples.begin() + i + 3);
    rgba.samples.push_back(i < 30 ? 0 : 255);
  }
  EXPECT_EQ(room_labels(rgba).room, l.room);
}

TEST(RoomLabels, WrittenLabelsReadBackAsTheSameRooms) {
  // 31 x 8 cells, row 0 at the bottom: room 0 left, room 1 right, no room along the middle
  // column (rooms are numbered in the image's reading order, so these keep theirs); 40 rooms'
  // colours must differ from black and from each other.
  const int w = 31, h = 8;
  std::vector<int> labels(static_cast<std::size_t>(w) * h, -1);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) labels[static_cast<std::size_t>(r) * w + c] = c < 15 ? 0 : c > 15 ? 1 : -1;
  const RoomLabels back = room_labels(room_label_image(labels, w, h));
  EXPECT_EQ(back.convention, RoomLabelConvention::kColour);
  ASSERT_EQ(back.count, 2);
  for (std::size_t i = 0; i < labels.size(); ++i) EXPECT_EQ(back.room[i], labels[i]) << "cell " << i;
  std::vector<int> many(40 * 200);
  for (std::size_t i = 0; i < many.size(); ++i) many[i] = static_cast<int>(i / 200);
  EXPECT_EQ(room_labels(room_label_image(many, 200, 40)).count, 40);
}

TEST(RoomLabels, GreyImageIsTheIpaConventionAsItsEvaluationReadsIt) {
  Image img = grey_image(60, 40, 0);
  paint(&img, 2, 2, 28, 38, {255, 255, 255});    // a room...
  paint(&img, 14, 2, 15, 38, {0, 0, 0});         // ...split by a door line into two
  paint(&img, 32, 2, 58, 20, {251, 251, 251});   // white is above 250
  paint(&img, 32, 22, 58, 38, {250, 250, 250});  // 250 is not white
  paint(&img, 50, 30, 51, 31, {255, 255, 255});  // a one-pixel speck: too small
  paint(&img, 29, 39, 30, 40, {254, 254, 254});  // another lone pixel
  const RoomLabels l = room_labels(img);
  EXPECT_EQ(l.convention, RoomLabelConvention::kIpa);
  EXPECT_STREQ(convention_name(l.convention), "IPA: white rooms, black door lines");
  ASSERT_EQ(l.count, 3);
  EXPECT_TRUE(l.colours.empty());
  EXPECT_EQ(l.small_left_out, 2u);  // the two specks
  EXPECT_EQ(room_at_pixel(l, 5, 10), 0);
  EXPECT_EQ(room_at_pixel(l, 20, 10), 1);
  EXPECT_EQ(room_at_pixel(l, 14, 10), -1);
  EXPECT_EQ(room_at_pixel(l, 40, 10), 2);
  EXPECT_EQ(room_at_pixel(l, 40, 30), -1);
  EXPECT_EQ(l.pixels, (std::vector<std::size_t>{12 * 36, 13 * 36, 26 * 18}));
  // An RGB image whose every pixel is grey is the same image.
  Image rgb = rgb_image(60, 40, {0, 0, 0});
  for (std::size_t i = 0; i < img.samples.size(); ++i)
    for (int ch = 0; ch < 3; ++ch) rgb.samples[3 * i + ch] = img.samples[i];
  const RoomLabels again = room_labels(rgb);
  EXPECT_EQ(again.convention, RoomLabelConvention::kIpa);
  EXPECT_EQ(again.room, l.room);
}

TEST(RoomLabels, AnImageWithNoRoomSaysWhy) {
  const RoomLabels grey = room_labels(grey_image(30, 20, 205));
  EXPECT_EQ(grey.count, 0);
  ASSERT_EQ(grey.warnings.size(), 1u);
  EXPECT_NE(grey.warnings[0].find("no room"), std::string::npos) << grey.warnings[0];
  EXPECT_NE(grey.warnings[0].find("IPA"), std::string::npos) << grey.warnings[0];
  Image colour = rgb_image(30, 20, {0, 0, 0});
  paint(&colour, 0, 0, 10, 10, {1, 2, 3});  // 100 pixels: not more than 100
  const RoomLabels c = room_labels(colour);
  EXPECT_EQ(c.count, 0);
  EXPECT_EQ(c.convention, RoomLabelConvention::kColour);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("no room"), std::string::npos) << c.warnings[0];
  EXPECT_TRUE(room_labels(grey_image(30, 20, 255)).warnings.empty());
}

class RoomLabelFile : public test::TempDirTest {};

TEST_F(RoomLabelFile, IsReadAndMustHaveTheMapsSize) {
  Image img = rgb_image(40, 30, {0, 0, 0});
  paint(&img, 5, 5, 35, 25, {10, 20, 30});
  write_file("labels.png", encode_png(img));
  OccupancyMap map;
  map.meta.image = "floor.pgm";
  map.width = 40;
  map.height = 30;
  const RoomLabels l = read_room_labels((dir_ / "labels.png").string(), map);
  EXPECT_EQ(l.count, 1);
  EXPECT_EQ(l.width, 40);
  EXPECT_EQ(l.height, 30);
  map.height = 31;
  const std::string err =
      test::input_error_of([&] { read_room_labels((dir_ / "labels.png").string(), map); });
  for (const std::string& part :
       {std::string("labels.png"), std::string("40 x 30"), std::string("floor.pgm"), std::string("40 x 31")})
    EXPECT_NE(err.find(part), std::string::npos) << part << " in " << err;
  EXPECT_NE(
      test::input_error_of([&] { read_room_labels((dir_ / "none.png").string(), map); }).find("none.png"),
      std::string::npos);
}
