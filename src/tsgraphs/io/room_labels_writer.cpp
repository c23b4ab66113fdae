#include "tsgraphs/io/room_labels_writer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace tsgraphs::io {
namespace {

/// A colour per room, far from black and from each other's neighbours in index: hues a golden
/// angle apart, two lightness levels.
std::array<std::uint8_t, 3> room_colour(int k) {
  const double hue = std::fmod(k * 0.6180339887498949, 1.0) * 6.0;
  const double value = k % 2 == 0 ? 0.95 : 0.7, saturation = 0.75;
  const int sector = static_cast<int>(hue) % 6;
  const double f = hue - std::floor(hue);
  const double p = value * (1.0 - saturation), q = value * (1.0 - saturation * f),
               t = value * (1.0 - saturation * (1.0 - f));
  double r = value, g = t, b = p;
  switch (sector) {
    case 1:
      r = q;
      g = value;
      b = p;
      break;
    case 2:
      r = p;
      g = value;
      b = t;
      break;
    case 3:
      r = p;
      g = q;
      b = value;
      break;
    case 4:
      r = t;
      g = p;
      b = value;
      break;
    case 5:
      r = value;
      g = p;
      b = q;
      break;
    default:
      break;
  }
  const auto byte = [](double x) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0));
  };
  return {byte(r), byte(g), byte(b)};
}

}  // namespace

Image room_label_image(const std::vector<int>& labels, int width, int height) {
  Image img;
  img.width = width;
  img.height = height;
  img.channels = 3;
  img.samples.assign(static_cast<std::size_t>(width) * height * 3, 0);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const int l = labels[static_cast<std::size_t>(row) * width + col];
      if (l < 0) continue;
      const auto c = room_colour(l);
      const std::size_t at = (static_cast<std::size_t>(height - 1 - row) * width + col) * 3;
      std::copy(c.begin(), c.end(), img.samples.begin() + static_cast<long>(at));
    }
  }
  return img;
}

}  // namespace tsgraphs::io
