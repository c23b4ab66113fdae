#include "tsgraphs/rooms/map_segmentation.hpp"

#include <stdexcept>

namespace tsgraphs::rooms {

MapSegmentation segment_map(const GridFrame& frame, const std::vector<std::uint8_t>& free,
                            const std::vector<std::uint8_t>& occupied, const MapSegmentationConfig& config) {
  if (free.size() != frame.size() || occupied.size() != frame.size())
    throw std::invalid_argument("segment_map: a mask does not match the map's raster");
  MapSegmentation out;
  out.walls = map_walls(frame, free, occupied, config.walls);
  SegmentationInput in;
  in.frame = frame;
  // The map's free cells are what the rays saw; each is a ground cell of its own.
  in.seen = free;
  for (std::size_t i = 0; i < free.size(); ++i)
    if (free[i]) in.ground.push_back(frame.center(i));
  in.known.resize(free.size());
  for (std::size_t i = 0; i < free.size(); ++i) in.known[i] = free[i] || occupied[i] ? 1 : 0;
  in.free_radius = config.robot_radius;
  in.ground_radius = 0.5 * frame.resolution;  // a free cell covers itself
  in.floor_z = 0.0;
  in.walls = out.walls;
  in.label_every_cell = true;
  RoomSegmentationConfig seg = config.segmentation;
  seg.cell = frame.resolution;
  out.rooms = segment_rooms(in, seg);
  return out;
}

}  // namespace tsgraphs::rooms
