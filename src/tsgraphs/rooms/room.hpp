#pragma once
/// What the room layer's extractions produce: rooms and corridor segments with their
/// footprints and the wall planes that bound them, and the walls they are found among.
#include <string>
#include <vector>

#include "tsgraphs/core/plane.hpp"
#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/core/room_kind.hpp"

namespace tsgraphs::rooms {

using tsgraphs::RoomKind;  // core/room_kind.hpp: graph/ sees it without rooms/
using tsgraphs::to_string;

/// A mapped vertical wall plane near the cluster.
struct WallCandidate {
  int id = -1;
  Plane plane;                ///< map frame; normal towards the observers, i.e. into the room (S-Graphs sign)
  Vec2 end_a = Vec2::Zero();  ///< horizontal segment ends of the plane's points, map x-y
  Vec2 end_b = Vec2::Zero();
  double height = 3.0;        ///< vertical extent of the plane's points (m)
  double z0 = 0.0, z1 = 3.0;  ///< ...from z0 to z1, map frame (m)
  bool top_seen =
      true;  ///< rays passed above z1 along it: its top is z1 (false: unseen, it may reach the ceiling)
};

struct ExtractedRoom {
  RoomKind kind = RoomKind::room;
  OrientedRect rect;  ///< footprint, map x-y, or the smallest rectangle round `outline`; rect x axis is the
                      ///< first pair's normal axis
  Polygon2 outline;   ///< a footprint that is no rectangle (counter-clockwise), else empty
  /// Planes of the room factor: room: first pair then second pair (each pair: the plane
  /// whose normal is along the rect's +axis first); corridor: the one pair.
  std::vector<int> wall_ids;
  /// Corridor only: single planes that bound the open direction at one end (0 or 1 per end).
  std::vector<int> end_wall_ids;
  /// Corridor only: one wall along it, the other side bounded by the free space (a railing);
  /// wall_ids then holds that one wall and no room-planes factor can be made from it.
  bool one_sided = false;
};

}  // namespace tsgraphs::rooms
