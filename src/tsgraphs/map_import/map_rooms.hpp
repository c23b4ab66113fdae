#pragma once
/// The ground-truth rooms of an imported occupancy map (docs/import-map.md, "Rooms"): the
/// cells a label image gives each room (io/room_labels.hpp) made one region per room that a
/// polygon without holes holds, no two regions touching. A label image marks only what the
/// laser saw: furniture and clutter leave holes, and a room seen only through a door is a fan
/// of rays in pieces. The regions cover each room's extent instead:
///
/// 1. Closing: each room is closed with a disc (`closing_radius`), together: an unlabelled cell
///    within the radius of rooms goes to the nearest (ties: the lower index), and stays with it
///    when no cell of another room's share, nor any cell farther than the radius from every
///    room, lies within the radius of it. Labelled cells keep their room.
/// 2. Contact: where two rooms touch (8-neighbours), the later room gives up its cells along the
///    contact, so that their outlines stay a cell apart.
/// 3. Pieces: a room keeps its largest 8-connected piece; pieces the closing did not join to it
///    are left out (counted).
/// 4. Holes: a hole of a room (4-connected) that holds no cell of another room is filled; one
///    that does (a ring corridor round a block of rooms) is opened by a slit one cell wide, the
///    shortest cut through the room from the hole to its outside, so that the room's polygon
///    leaves the rooms inside out. Pieces a slit cuts off are left out like those of step 3.
///
/// No file I/O; raster cells, index r * cols + c.
#include <cstddef>
#include <vector>

namespace tsgraphs::map_import {

struct MapRoomRegions {
  std::vector<int> region;                ///< per cell: the room whose region holds it, or -1
  std::vector<std::size_t> cells;         ///< per room: its region's cells
  std::vector<std::size_t> labelled_out;  ///< per room: labelled cells its region does not hold
  int slits = 0;                          ///< holes opened because they hold other rooms
};

/// The regions of `count` rooms given per cell by `room_of_cell` (-1 none; cols x rows).
/// `closing_radius` is in cells (>= 0). Throws std::invalid_argument on sizes that disagree or
/// a room index out of range.
MapRoomRegions room_regions(const std::vector<int>& room_of_cell, int count, int cols, int rows,
                            double closing_radius);

}  // namespace tsgraphs::map_import
