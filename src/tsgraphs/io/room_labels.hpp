#pragma once
/// Room-label images: a ground-truth room segmentation of an occupancy map, drawn as a PGM or
/// PNG of the map's size. Two conventions, told apart by the image itself:
///
/// - IPA (the ipa320 room-segmentation benchmark's ground truth; every pixel grey): rooms are
///   white, closed off from each other by black door lines. Read as its evaluation reads it:
///   grey as OpenCV's imread grayscale (alpha dropped), white above 250, a room an 8-connected
///   white region, regions of 100 pixels or fewer ("mini rooms") no rooms.
/// - colour (any pixel not grey): one colour per room, black (0, 0, 0) no room. A room is every
///   pixel of its colour, in as many pieces as it has (a room seen through a door is a fan of
///   laser rays); alpha is dropped; a colour of 100 pixels or fewer is no room (a stray mark).
///
/// Rooms are numbered in reading order of the image (by their first pixel, top row first, left
/// to right). The segment-map command scores against these labels; import-map makes the
/// scene's ground-truth rooms of them.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/io/image.hpp"
#include "tsgraphs/io/occupancy_map.hpp"

namespace tsgraphs::io {

enum class RoomLabelConvention { kIpa, kColour };

/// IPA convention: a room pixel is grey above this (the evaluation's cv::threshold at 250).
constexpr int kIpaWhiteAbove = 250;
/// A region (IPA) or a colour (colour convention) of this many pixels or fewer is no room.
constexpr std::size_t kMaxSmallRoomPixels = 100;

/// What a label image says, on the map's raster.
struct RoomLabels {
  int width = 0;   ///< cells along x (the image's width)
  int height = 0;  ///< cells along y
  RoomLabelConvention convention = RoomLabelConvention::kIpa;
  int count = 0;  ///< rooms, indexed 0 .. count - 1
  /// width * height, index row * width + column with row 0 at the bottom (the map's lowest y),
  /// as OccupancyMap::cells: the cell's room, or -1 for none.
  std::vector<int> room;
  std::vector<std::size_t> pixels;                   ///< each room's pixel count
  std::vector<std::array<std::uint8_t, 3>> colours;  ///< colour convention: each room's RGB; empty for IPA
  std::size_t small_left_out = 0;                    ///< regions or colours too small to be rooms
  std::vector<std::string> warnings;                 ///< set when the image gives no room: why

  int at(int col, int row) const { return room[static_cast<std::size_t>(row) * width + col]; }
};

/// "IPA: white rooms, black door lines" or "one colour per room".
const char* convention_name(RoomLabelConvention convention);

/// The rooms of a decoded label image (no size check).
RoomLabels room_labels(const Image& image);

/// Reads a label image and checks that it has `map`'s size: an InputError naming the file,
/// both sizes and the map's image otherwise (and for any error of reading the image).
RoomLabels read_room_labels(const std::string& file, const OccupancyMap& map);

}  // namespace tsgraphs::io
