#pragma once
/// ROS map_server occupancy maps: the map YAML (image, resolution, origin, negate, thresholds,
/// mode) and its PGM or PNG image, each cell classified free, occupied or unknown exactly as
/// map_server's image loader does (docs/import-map.md).
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/io/image.hpp"

namespace tsgraphs::io {

/// map_server's modes: trinary (free / occupied / unknown), scale (in-between values are
/// partial occupancy, transparent pixels unknown), raw (the pixel value is the occupancy).
enum class MapMode { kTrinary, kScale, kRaw };

/// What a cell is, for building a scene.
enum class CellState : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

/// The map YAML, as map_server reads it.
struct MapMetadata {
  std::string yaml_file;     ///< the YAML file (for messages)
  std::string image;         ///< the image file, resolved against the YAML's folder
  double resolution = 0.05;  ///< m per pixel (required)
  double origin_x = 0.0;     ///< m: world position of the lower-left pixel's corner (required)
  double origin_y = 0.0;
  double origin_yaw = 0.0;        ///< rad: the map's rotation about that corner
  bool negate = false;            ///< white is occupied and black free
  double occupied_thresh = 0.65;  ///< occupancy above this is occupied (map_saver's default)
  double free_thresh = 0.196;     ///< occupancy below this is free (map_saver's default)
  MapMode mode = MapMode::kTrinary;
};

/// A map: one state per cell, row 0 at the bottom (the lowest y), as nav_msgs/OccupancyGrid
/// orders its data; the image's row 0 (its top) is the map's last row.
struct OccupancyMap {
  MapMetadata meta;
  int width = 0;                 ///< cells along x
  int height = 0;                ///< cells along y
  std::vector<CellState> cells;  ///< width * height, index = row * width + column

  CellState at(int col, int row) const { return cells[static_cast<std::size_t>(row) * width + col]; }
};

/// Parses a map YAML (text, for tests: `file` names it, `base_dir` resolves `image`). image,
/// resolution and origin are required; negate, occupied_thresh, free_thresh and mode default
/// to map_saver's values. An unknown key, a missing or out-of-range value is an InputError
/// naming file:line: key.
MapMetadata parse_map_yaml(const std::string& text, const std::string& file, const std::string& base_dir);
/// The same from a file; `image` resolves against the file's folder.
MapMetadata read_map_yaml(const std::string& file);

/// map_server's classification of each pixel: the grey value v is the mean of the pixel's
/// channels (alpha included in trinary mode, left out in scale and raw mode); the occupancy
/// p = (255 - v) / 255, or v / 255 with negate; occupied when p > occupied_thresh, free when
/// p < free_thresh, else unknown (in scale mode the in-between cells are partial occupancy,
/// unknown here too). Raw mode: the value itself (after negate) is the occupancy in percent,
/// compared with the same thresholds; values above 100 (ROS's -1 is 255) are unknown.
OccupancyMap classify(const Image& image, const MapMetadata& meta);

/// Reads the YAML and its image and classifies it.
OccupancyMap read_occupancy_map(const std::string& yaml_file);

}  // namespace tsgraphs::io
