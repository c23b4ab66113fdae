#pragma once
/// The room segmentation of a 2-D occupancy map (`tsgraphs segment-map`): the same segmentation
/// the room layer runs on the level it maps (room_segmentation.hpp), given the map instead. The
/// map's free cells are what the rays saw at walking height, its walls the straight edges of
/// that free space (map_walls.hpp); there is no path walked, so every space is segmented.
#include <cstdint>
#include <vector>

#include "tsgraphs/core/grid_frame.hpp"
#include "tsgraphs/rooms/map_walls.hpp"
#include "tsgraphs/rooms/room_segmentation.hpp"

namespace tsgraphs::rooms {

struct MapSegmentationConfig {
  MapWallsConfig walls;                 ///< the map's walls
  RoomSegmentationConfig segmentation;  ///< the segmentation (its cell is set to the map's resolution)
  double robot_radius = 0.4;            ///< m: the free space's lambda_th, the robot's half width
};

struct MapSegmentation {
  RoomSegmentation rooms;            ///< on the map's own raster: label per map cell, the spaces
  std::vector<WallCandidate> walls;  ///< the map's walls it was cut by
};

/// Segments the map whose cells (frame's raster, row 0 at the bottom) are `free` and `occupied`
/// (the rest unknown). Throws std::invalid_argument when a mask does not match the frame.
MapSegmentation segment_map(const GridFrame& frame, const std::vector<std::uint8_t>& free,
                            const std::vector<std::uint8_t>& occupied,
                            const MapSegmentationConfig& config = {});

}  // namespace tsgraphs::rooms
