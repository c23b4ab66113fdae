#include "tsgraphs/io/room_labels.hpp"

#include <unordered_map>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/raster_regions.hpp"

namespace tsgraphs::io {
namespace {

bool all_grey(const Image& image) {
  if (image.channels <= 2) return true;
  const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = image.samples.data() + i * image.channels;
    if (p[0] != p[1] || p[1] != p[2]) return false;
  }
  return true;
}

/// Candidate regions in image order (row 0 at the top), numbered in reading order, made rooms:
/// the ones of more than kMaxSmallRoomPixels pixels, renumbered in the same order, rows flipped
/// so that row 0 is the bottom.
void keep_rooms(const std::vector<int>& region, const std::vector<std::size_t>& sizes, int width, int height,
                RoomLabels* out) {
  std::vector<int> rank(sizes.size(), -1);
  for (std::size_t id = 0; id < sizes.size(); ++id) {
    if (sizes[id] > kMaxSmallRoomPixels) {
      rank[id] = out->count++;
      out->pixels.push_back(sizes[id]);
    } else {
      ++out->small_left_out;
    }
  }
  out->width = width;
  out->height = height;
  out->room.assign(region.size(), -1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int id = region[static_cast<std::size_t>(y) * width + x];
      if (id >= 0) out->room[static_cast<std::size_t>(height - 1 - y) * width + x] = rank[id];
    }
  }
}

void ipa_rooms(const Image& image, RoomLabels* out) {
  const std::vector<std::uint8_t> grey = luma(image);
  std::vector<std::uint8_t> white(grey.size());
  for (std::size_t i = 0; i < grey.size(); ++i) white[i] = grey[i] > kIpaWhiteAbove;
  std::vector<std::size_t> sizes;
  // label_regions numbers regions by their first cell in index order: reading order here.
  const std::vector<int> region = label_regions(white, image.width, image.height, true, &sizes);
  keep_rooms(region, sizes, image.width, image.height, out);
  if (out->count == 0)
    out->warnings.push_back("no room: every pixel is grey (the IPA convention: rooms white, above " +
                            std::to_string(kIpaWhiteAbove) + ") and no white region has more than " +
                            std::to_string(kMaxSmallRoomPixels) + " pixels");
}

void colour_rooms(const Image& image, RoomLabels* out) {
  const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
  std::unordered_map<std::uint32_t, int> id_of;  // RGB -> candidate, numbered by first pixel
  std::vector<std::array<std::uint8_t, 3>> colours;
  std::vector<std::size_t> sizes;
  std::vector<int> region(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = image.samples.data() + i * image.channels;
    const std::uint32_t rgb = (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
    if (rgb == 0) continue;
    const auto [it, added] = id_of.try_emplace(rgb, static_cast<int>(sizes.size()));
    if (added) {
      colours.push_back({p[0], p[1], p[2]});
      sizes.push_back(0);
    }
    region[i] = it->second;
    ++sizes[it->second];
  }
  keep_rooms(region, sizes, image.width, image.height, out);
  for (std::size_t id = 0; id < sizes.size(); ++id) {
    if (sizes[id] > kMaxSmallRoomPixels) out->colours.push_back(colours[id]);
  }
  if (out->count == 0)
    out->warnings.push_back(
        "no room: the image has colours (one colour per room, black none) but no colour other "
        "than black covers more than " +
        std::to_string(kMaxSmallRoomPixels) + " pixels");
}

}  // namespace

const char* convention_name(RoomLabelConvention convention) {
  return convention == RoomLabelConvention::kIpa ? "IPA: white rooms, black door lines"
                                                 : "one colour per room";
}

RoomLabels room_labels(const Image& image) {
  RoomLabels out;
  if (all_grey(image)) {
    out.convention = RoomLabelConvention::kIpa;
    ipa_rooms(image, &out);
  } else {
    out.convention = RoomLabelConvention::kColour;
    colour_rooms(image, &out);
  }
  return out;
}

RoomLabels read_room_labels(const std::string& file, const OccupancyMap& map) {
  const Image image = read_image(file);
  if (image.width != map.width || image.height != map.height) {
    throw input_error(file, 0,
                      "room labels are " + std::to_string(image.width) + " x " +
                          std::to_string(image.height) + " pixels but the map " + map.meta.image + " is " +
                          std::to_string(map.width) + " x " + std::to_string(map.height));
  }
  return room_labels(image);
}

}  // namespace tsgraphs::io
