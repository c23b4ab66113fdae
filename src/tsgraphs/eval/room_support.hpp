#pragma once
/// Unsupported rooms (docs/metrics.md, "Against ground truth"): final footprints that lie
/// largely where one cannot walk, on a void, outside the building or inside walls.
#include <optional>
#include <vector>

#include "tsgraphs/eval/footprint_raster.hpp"
#include "tsgraphs/io/sequence_info.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::eval {

/// A room is unsupported when more than this share of its footprint is not walkable: a room
/// may reach a little into its walls (a footprint bounded by wall faces, a measured plane a few
/// centimetres off), not over a void (metrics.md).
constexpr double kMaxUnwalkableShare = 0.20;

/// For each footprint, the share of its cells (raster_cells) that are not walkable in `scene`:
/// off the walkable surface of its level (scene::walkable_height: slab minus voids, plus the
/// ramps joining the level) or inside a wall piece that starts at the floor (thickness wide) or
/// a railing. Footprints name their level by the scene's level names; an unknown name has no
/// walkable cell. A footprint without cells has share 0. Throws std::invalid_argument for a
/// footprint too large to rasterise.
std::vector<double> unwalkable_shares(const std::vector<LevelFootprint>& rooms, const scene::Scene& scene);

/// The same without a scene: a cell is not walkable when it lies in no ground-truth room of the
/// footprint's level.
std::vector<double> unwalkable_shares(const std::vector<LevelFootprint>& rooms,
                                      const std::vector<io::RoomTruth>& truth);

struct RoomSupport {
  int unsupported = 0;                         ///< rooms with a share above kMaxUnwalkableShare
  std::optional<double> max_unwalkable_share;  ///< empty without rooms
};
RoomSupport room_support(const std::vector<double>& unwalkable_shares);

}  // namespace tsgraphs::eval
