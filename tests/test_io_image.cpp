// Images for occupancy maps: PGM (P5, P2; 8 and 16 bit) parsed by hand, PNG through libpng
// (grey, grey + alpha, RGB, RGBA, palette, 16 bit), the format told by content, and every
// malformed file an InputError naming it.
#include <gtest/gtest.h>
#include <png.h>

#include <cstring>
#include <string>

#include "test_support.hpp"
#include "tsgraphs/io/image.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;
using tsgraphs::test::input_error_of;
using tsgraphs::test::TempDirTest;

namespace {

Image grey(int w, int h, std::vector<std::uint8_t> v) {
  Image img;
  img.width = w;
  img.height = h;
  img.channels = 1;
  img.samples = std::move(v);
  return img;
}

/// A PNG written with libpng directly, for layouts encode_png does not make (16 bit, palette).
std::string raw_png(int w, int h, int bit_depth, int color_type, const std::vector<std::uint8_t>& rows_bytes,
                    const std::vector<png_color>& palette = {}) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    ADD_FAILURE() << "libpng write failed";
    return "";
  }
  png_set_write_fn(
      png, &out,
      [](png_structp p, png_bytep d, png_size_t n) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<char*>(d), n);
      },
      nullptr);
  png_set_IHDR(png, info, w, h, bit_depth, color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (!palette.empty()) png_set_PLTE(png, info, palette.data(), static_cast<int>(palette.size()));
  png_write_info(png, info);
  const std::size_t stride = rows_bytes.size() / h;
  for (int y = 0; y < h; ++y) png_write_row(png, const_cast<png_bytep>(rows_bytes.data() + y * stride));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

class ImageTest : public TempDirTest {};

}  // namespace

TEST_F(ImageTest, BinaryPgmRowsTopFirst) {
  const std::string bytes =
      std::string("P5\n# made by hand\n3 2\n255\n") + std::string("\x00\x10\x20\x30\x40\xff", 6);
  const Image img = read_image(write_file("m.pgm", bytes));
  EXPECT_EQ(img.width, 3);
  EXPECT_EQ(img.height, 2);
  EXPECT_EQ(img.channels, 1);
  EXPECT_EQ(img.at(0, 0), 0x00);
  EXPECT_EQ(img.at(2, 0), 0x20);
  EXPECT_EQ(img.at(0, 1), 0x30);
  EXPECT_EQ(img.at(2, 1), 0xff);
}

TEST_F(ImageTest, AsciiPgmWithCommentsAndOtherMaxvals) {
  const Image img = decode_image("P2 # plain\n2 2 # size\n15\n0 15\n# a comment\n7\n8\n", "a.pgm");
  ASSERT_EQ(img.samples.size(), 4u);
  EXPECT_EQ(img.at(0, 0), 0);
  EXPECT_EQ(img.at(1, 0), 255);
  EXPECT_EQ(img.at(0, 1), 119);  // 7 * 255 / 15, rounded
  EXPECT_EQ(img.at(1, 1), 136);
  // 16-bit binary: two bytes per sample, most significant first, scaled to 8 bits.
  const Image wide =
      decode_image(std::string("P5 2 1 65535\n") + std::string("\xff\xff\x80\x00", 4), "w.pgm");
  EXPECT_EQ(wide.at(0, 0), 255);
  EXPECT_EQ(wide.at(1, 0), 128);
}

TEST_F(ImageTest, PngLayoutsRoundTrip) {
  for (int channels = 1; channels <= 4; ++channels) {
    Image img;
    img.width = 5;
    img.height = 3;
    img.channels = channels;
    for (int i = 0; i < 5 * 3 * channels; ++i) img.samples.push_back(static_cast<std::uint8_t>(17 * i));
    const Image back = decode_image(encode_png(img), "x.png");
    EXPECT_EQ(back.width, 5);
    EXPECT_EQ(back.height, 3);
    EXPECT_EQ(back.channels, channels);
    EXPECT_EQ(back.samples, img.samples) << channels << " channels";
  }
}

TEST_F(ImageTest, SixteenBitPalettedAndOneBitPngs) {
  // 16-bit grey keeps the high byte, as map_server's SDL_image reader.
  const Image wide = decode_png(raw_png(2, 1, 16, PNG_COLOR_TYPE_GRAY, {0xab, 0xcd, 0x01, 0xff}), "w.png");
  EXPECT_EQ(wide.channels, 1);
  EXPECT_EQ(wide.at(0, 0), 0xab);
  EXPECT_EQ(wide.at(1, 0), 0x01);
  // A palette becomes its colours.
  const Image pal =
      decode_png(raw_png(2, 1, 8, PNG_COLOR_TYPE_PALETTE, {1, 0}, {{0, 0, 0}, {10, 20, 30}}), "p.png");
  EXPECT_EQ(pal.channels, 3);
  EXPECT_EQ(pal.at(0, 0, 0), 10);
  EXPECT_EQ(pal.at(0, 0, 2), 30);
  EXPECT_EQ(pal.at(1, 0, 1), 0);
  // 1-bit grey is scaled to 0 / 255.
  const Image bits = decode_png(raw_png(3, 1, 1, PNG_COLOR_TYPE_GRAY, {0xa0}), "b.png");
  EXPECT_EQ(bits.at(0, 0), 255);
  EXPECT_EQ(bits.at(1, 0), 0);
  EXPECT_EQ(bits.at(2, 0), 255);
}

TEST_F(ImageTest, FormatIsToldByContentNotName) {
  const Image img = grey(2, 2, {1, 2, 3, 4});
  EXPECT_EQ(read_image(write_file("looks_like.pgm", encode_png(img))).samples, img.samples);
  EXPECT_EQ(read_image(write_file("looks_like.png", encode_pgm(img))).samples, img.samples);
}

TEST_F(ImageTest, LumaAsOpenCvReadsGrey) {
  Image rgb;
  rgb.width = 3;
  rgb.height = 1;
  rgb.channels = 4;
  rgb.samples = {255, 0, 0, 9, 0, 255, 0, 9, 255, 255, 255, 0};
  EXPECT_EQ(luma(rgb), (std::vector<std::uint8_t>{76, 150, 255}));
  EXPECT_EQ(luma(grey(2, 1, {7, 250})), (std::vector<std::uint8_t>{7, 250}));
}

TEST_F(ImageTest, MalformedFilesNameTheFileAndTheFault) {
  const auto fails = [&](const std::string& name, const std::string& bytes, const std::string& what) {
    const std::string path = write_file(name, bytes);
    const std::string msg = input_error_of([&] { read_image(path); });
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << name << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  };
  fails("empty.pgm", "", "empty file");
  fails("text.pgm", "hello, not an image", "not a PGM or PNG");
  fails("height.pgm", "P5\n4 x\n255\n", "height is not a number");
  fails("zero.pgm", "P5\n0 4\n255\n", "must be at least 1 x 1");
  fails("huge.pgm", "P5\n100000 100000\n255\n", "absurd");
  fails("maxval.pgm", "P5\n2 2\n0\n\x01\x02\x03\x04", "maxval 0");
  fails("deep.pgm", "P5\n2 2\n70000\n", "maxval 70000");
  fails("short.pgm", "P5\n4 4\n255\n\x01\x02\x03", "truncated PGM: 3 of 16");
  fails("short16.pgm", "P5\n2 2\n1000\n\x01\x02\x03\x04\x05", "truncated PGM: 2 of 4");
  fails("over.pgm", "P2\n2 1\n100\n50 101\n", "value 101 exceeds maxval 100");
  fails("few.pgm", "P2\n2 2\n255\n1 2 3\n", "truncated PGM: 3 of 4");
  fails("colour.ppm", "P6\n2 2\n255\n", "P6");
  fails("header.pgm", "P5", "header ends before its width");
  const std::string png = encode_png(grey(40, 40, std::vector<std::uint8_t>(1600, 9)));
  fails("cut.png", png.substr(0, png.size() / 2), "bad PNG");
  fails("sig.png", png.substr(0, 20), "bad PNG");
  std::string crc = png;
  crc[30] = static_cast<char>(crc[30] ^ 0x55);  // inside IHDR: its CRC no longer matches
  fails("crc.png", crc, "bad PNG");
  const std::string missing = (dir_ / "missing.png").string();
  EXPECT_NE(input_error_of([&] { read_image(missing); }).find(missing + ": no such image file"),
            std::string::npos);
}
