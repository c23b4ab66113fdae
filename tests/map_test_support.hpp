#pragma once
/// A small building drawn as a ROS occupancy map and its IPA-style room labels, shared by the
/// import-map tests: a corridor with three rooms off it through 1 m doors, a 0.5 m thick wall
/// between two rooms, a closet behind a 0.6 m door (too narrow for the survey path), unknown
/// space round the building, an unknown hole of 1.44 m² (a void) and one of 0.25 m² (floor),
/// and a stray free speck outside. Header only (tests/CMakeLists.txt makes executables of
/// tests/test_*.cpp only).
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/io/image.hpp"

namespace tsgraphs::test {

constexpr double kMapRes = 0.05;                                          // m per pixel
constexpr int kMapCols = 280, kMapRows = 200;                             // 14 m x 10 m
constexpr std::uint8_t kFreePx = 254, kOccupiedPx = 0, kUnknownPx = 205;  // what map_saver writes
constexpr double kWallHeightCells = 52;                                   // 2.6 m ceiling at 0.05 m

/// An axis-aligned rectangle in the map frame (m from the map's lower-left corner).
struct MapBox {
  double x0, y0, x1, y1;
  double area() const { return (x1 - x0) * (y1 - y0); }
  double cx() const { return 0.5 * (x0 + x1); }
  double cy() const { return 0.5 * (y0 + y1); }
};

struct DrawnRoom {
  std::string name;  ///< the name import-map gives it (reading order of the label image)
  MapBox box;
  bool reachable;  ///< wide enough for the survey path at 0.35 m clearance
};

struct DrawnMap {
  io::Image map;                           ///< grey, row 0 at the top
  io::Image labels;                        ///< the map with its doors closed by black lines
  std::vector<DrawnRoom> rooms;            ///< room_1 ... room_5
  MapBox building{1.0, 1.0, 13.0, 9.0};    ///< the known area (outer wall included)
  MapBox void_hole{10.4, 5.4, 11.6, 6.6};  ///< unknown, 1.44 m²: a void
  MapBox small_hole{2.0, 7.5, 2.5, 8.0};   ///< unknown, 0.25 m²: stays floor
};

/// Sets every pixel whose centre lies in `b` to `v`.
inline void fill_box(io::Image* img, const MapBox& b, std::uint8_t v) {
  for (int j = 0; j < img->height; ++j) {
    const double y = (img->height - 1 - j + 0.5) * kMapRes;  // row 0 is the map's top
    if (y < b.y0 || y > b.y1) continue;
    for (int i = 0; i < img->width; ++i) {
      const double x = (i + 0.5) * kMapRes;
      if (x >= b.x0 && x <= b.x1) img->samples[static_cast<std::size_t>(j) * img->width + i] = v;
    }
  }
}

inline DrawnMap draw_test_building() {
  DrawnMap d;
  d.map.width = kMapCols;
  d.map.height = kMapRows;
  d.map.channels = 1;
  d.map.samples.assign(static_cast<std::size_t>(kMapCols) * kMapRows, kUnknownPx);
  io::Image& m = d.map;
  fill_box(&m, d.building, kOccupiedPx);  // outer wall, 0.15 m
  fill_box(&m, {1.15, 1.15, 12.85, 8.85}, kFreePx);
  fill_box(&m, {1.15, 3.0, 12.85, 3.1}, kOccupiedPx);  // corridor wall, 0.1 m
  const std::vector<MapBox> doors = {
      {2.5, 3.0, 3.5, 3.1}, {6.5, 3.0, 7.5, 3.1}, {10.0, 3.0, 11.0, 3.1}, {12.15, 1.8, 12.25, 2.4}};
  fill_box(&m, {5.0, 3.1, 5.5, 8.85}, kOccupiedPx);  // thick wall, 0.5 m
  fill_box(&m, {9.0, 3.1, 9.1, 8.85}, kOccupiedPx);
  fill_box(&m, {12.15, 1.15, 12.25, 3.0}, kOccupiedPx);  // the closet's wall
  for (const MapBox& door : doors) fill_box(&m, door, kFreePx);
  fill_box(&m, d.void_hole, kUnknownPx);
  fill_box(&m, d.small_hole, kUnknownPx);
  fill_box(&m, {0.2, 0.2, 0.45, 0.45}, kFreePx);  // a speck of known space outside
  d.labels = m;
  for (const MapBox& door : doors) fill_box(&d.labels, door, kOccupiedPx);
  d.rooms = {{"room_1", {1.15, 3.1, 5.0, 8.85}, true},
             {"room_2", {5.5, 3.1, 9.0, 8.85}, true},
             {"room_3", {9.1, 3.1, 12.85, 8.85}, true},
             {"room_4", {1.15, 1.15, 12.15, 3.0}, true},
             {"room_5", {12.25, 1.15, 12.85, 3.0}, false}};
  return d;
}

/// The map YAML of a map image.
inline std::string map_yaml(const std::string& image, const std::string& origin = "[-2.0, -1.0, 0.0]") {
  return "image: " + image + "\nresolution: 0.05\norigin: " + origin +
         "\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
}

}  // namespace tsgraphs::test
