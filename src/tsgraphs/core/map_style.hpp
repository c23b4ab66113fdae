#pragma once
/// How the map's layers are drawn, held once for every output that draws them (map.ply, the
/// Foxglove export), so that a wall or a room looks the same in each: colours, outline height.
#include <cstddef>

namespace tsgraphs {

struct Rgb {
  unsigned char r, g, b;
};

/// Distinct colours for neighbouring wall ids; the other layers use fixed colours.
inline Rgb wall_colour(int id) {
  static constexpr Rgb kPalette[] = {{230, 25, 75},  {60, 180, 75},  {0, 130, 200},  {245, 130, 48},
                                     {145, 30, 180}, {70, 240, 240}, {240, 50, 230}, {210, 245, 60},
                                     {0, 128, 128},  {170, 110, 40}, {128, 0, 0},    {0, 0, 128}};
  constexpr std::size_t kCount = sizeof kPalette / sizeof kPalette[0];
  return kPalette[static_cast<std::size_t>(id) % kCount];
}
constexpr Rgb kKeyframePointColour{150, 150, 150};
constexpr Rgb kHorizontalPlaneColour{222, 200, 160};
constexpr Rgb kTraversableNodeColour{255, 0, 255};  // magenta, as DESIGN.md's outputs say
constexpr Rgb kRoomOutlineColour{0, 200, 255};
constexpr Rgb kCorridorOutlineColour{255, 150, 0};
constexpr Rgb kFloorNodeColour{255, 255, 0};
constexpr double kOutlineLift = 0.05;  // room outlines this far above their floor (m)

}  // namespace tsgraphs
