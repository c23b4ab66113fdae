#pragma once
/// Raster images for occupancy maps and room labels: PGM (P5 binary, P2 ASCII; parsed here,
/// since netpbm's library exits the process on a bad file) and PNG (Debian's libpng), told
/// apart by their first bytes, never by the file name. Samples are 8-bit: a PGM whose maxval
/// is not 255 (16-bit ones too) is scaled to 0..255, rounded; a 16-bit PNG keeps the high byte
/// of each sample and a palette PNG becomes RGB(A), as map_server's reader (SDL_image) does.
#include <cstdint>
#include <string>
#include <vector>

namespace tsgraphs::io {

/// Images larger than this many pixels are refused as absurd (a 16k x 16k map; a real
/// building at 0.05 m is a few thousand pixels a side).
constexpr long long kMaxImagePixels = 1LL << 28;

/// A decoded image: 8-bit samples, rows top to bottom (row 0 is the image's top), the
/// channels of a pixel next to each other.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 1;                   ///< 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
  std::vector<std::uint8_t> samples;  ///< width * height * channels

  bool has_alpha() const { return channels == 2 || channels == 4; }
  /// Channel `ch` of the pixel in column x of row y (row 0 at the top).
  std::uint8_t at(int x, int y, int ch = 0) const {
    return samples[(static_cast<std::size_t>(y) * width + x) * channels + ch];
  }
};

/// Reads a PGM or PNG file. A missing file, an unknown format, a bad header, truncated data,
/// a size of 0 or above kMaxImagePixels, or an unsupported bit depth is an InputError naming
/// the file and what is wrong.
Image read_image(const std::string& path);

/// The same from bytes in memory; `name` names them in messages.
Image decode_image(const std::string& bytes, const std::string& name);
Image decode_pgm(const std::string& bytes, const std::string& name);
Image decode_png(const std::string& bytes, const std::string& name);

/// A binary PGM (P5, maxval 255) of a one-channel image.
std::string encode_pgm(const Image& image);
/// An 8-bit PNG of an image of 1 to 4 channels (for tests and pictures).
std::string encode_png(const Image& image);

/// One grey value per pixel (row 0 at the top), as OpenCV's imread(..., IMREAD_GRAYSCALE)
/// makes it: ITU-R 601 luma of the colour channels, alpha dropped. Room-label images are
/// read so, as the IPA room-segmentation benchmark reads its ground truth.
std::vector<std::uint8_t> luma(const Image& image);

}  // namespace tsgraphs::io
