#pragma once
/// The walls of a 2-D occupancy map: the straight stretches of the edge of the free space one can
/// walk in (what stops one walking). They play, for a map, the part the mapped wall planes play
/// for a LiDAR run, so that one room segmentation (room_segmentation.hpp) takes either.
///
/// 1. The free space is opened by the robot's radius: laser fans and ragged fringes, which no
///    one can walk in, have no edge. Its edge is that of the building's structure: what is
///    joined through what is not free to the map's border (walls join walls and the unknown
///    round the building); what stands free inside (a table, a pillar) is furniture, no wall,
///    unless it is longer than furniture is (`min_free_standing`: a partition, cabinets in a row).
///    An edge is a wall only where the rays ended on something: an occupied cell lies within
///    `fringe_width` behind it (a laser map leaves a band of unknown at a wall's face). Where
///    only unknown lies behind, the view ended there (a fan's side seen through a door, the
///    map's frontier): that is no wall.
/// 2. The directions of the walls are those along which the edge lines up best: for each
///    direction (degree steps over half a turn) the edge cells facing it are projected across it
///    into one-cell bins, and the length of their straight runs is summed. The best direction is
///    taken, then the next best at least `min_direction_separation_deg` from those taken while it
///    explains `min_direction_share` of the best one's length; each is refined to a twentieth of
///    a degree. A rotated map, a chamfered corner or a diagonal wing thus gets its own walls.
/// 3. Along each direction, the edge cells are binned across it a cell wide; a slanted edge is a
///    staircase over two bins, so each two neighbouring bins are a candidate face, the faces that
///    explain the most length taken first. A face's run of edge cells with gaps of at most
///    `max_gap` cells is a wall piece when it is `min_piece` long, and a face whose pieces add up
///    to `min_wall` (`min_free_standing`) gives one WallCandidate per piece.
/// Deterministic: the same raster gives the same walls in the same order.
#include <cstdint>
#include <vector>

#include "tsgraphs/core/config_fields.hpp"
#include "tsgraphs/core/grid_frame.hpp"
#include "tsgraphs/rooms/room.hpp"

namespace tsgraphs::rooms {

struct MapWallsConfig {
  double robot_radius = 0.2;
  double fringe_width = 0.2;
  double min_piece = 0.5;
  double min_wall = 1.0;
  double min_free_standing = 2.5;
  double max_gap = 2.0;
  double min_direction_share = 0.25;
  double min_direction_separation_deg = 10.0;
  double wall_height = 2.6;

  template <class V>
  void visit(V& v) {
    v("robot_radius", robot_radius, between(0.0, 10.0),
      "the free space is opened by a disc of this radius (m): laser fans and ragged fringes have no edge");
    v("fringe_width", fringe_width, between(0.0, 10.0),
      "an edge is a wall only with an occupied cell this near behind it (m): the band of unknown a laser map "
      "leaves at a wall's face (as map_import's); with only unknown behind, the view ended there");
    v("min_piece", min_piece, above(0.0, 100.0),
      "a straight run of edge shorter than this is clutter, no wall (m)");
    v("min_wall", min_wall, above(0.0, 1000.0),
      "a wall face's pieces add up to at least this (m): a door post alone is none");
    v("min_free_standing", min_free_standing, above(0.0, 1000.0),
      "...and a face of what stands free to this (m): longer than furniture (a partition, cabinets in a "
      "row)");
    v("max_gap", max_gap, between(0.0, 100.0),
      "a run of edge continues over gaps of this many cells (a ragged laser edge)");
    v("min_direction_share", min_direction_share, above(0.0, 1.0),
      "a further wall direction explains this share of the best one's wall length");
    v("min_direction_separation_deg", min_direction_separation_deg, above(0.0, 90.0),
      "wall directions are at least this far apart (deg)");
    v("wall_height", wall_height, above(0.0, 100.0),
      "the height given to a map's walls (m): they reach the ceiling");
  }
};

/// The free space opened by a disc of `radius` (m): the cells within radius of a cell whose
/// centre is farther than radius from every blocked cell (free[i] == 0).
std::vector<std::uint8_t> open_free_space(const GridFrame& frame, const std::vector<std::uint8_t>& free,
                                          double radius);

/// The walls of the map whose free and occupied cells are `free` and `occupied` (one per cell of
/// `frame`, the rest unknown): vertical planes from the floor (z 0) to config.wall_height, each
/// normal pointing to the free side, with the extent of its piece. Throws std::invalid_argument
/// when a mask does not match the frame.
std::vector<WallCandidate> map_walls(const GridFrame& frame, const std::vector<std::uint8_t>& free,
                                     const std::vector<std::uint8_t>& occupied,
                                     const MapWallsConfig& config = {});

}  // namespace tsgraphs::rooms
