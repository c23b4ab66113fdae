#pragma once
/// Spaces as the parts of the walkable area that only narrowings join: a watershed of the
/// clearance (the distance to the nearest cell one cannot stand on). Every local maximum of the
/// clearance starts a space; the cells are flooded from the highest clearance down, and where
/// two spaces first meet (a saddle, clearance s) they stay apart only if s is a doorway's
/// half-width at most and at most `narrowing` times the clearance of the smaller space's
/// widest point: a door between two rooms, a room's door on a corridor. A corridor's run, a
/// room's bay or the gap between a pillar and a wall is no narrowing of the space around it, so
/// those meet and merge. This is the distance-transform segmentation of ipa_room_segmentation,
/// with the threshold chosen per saddle instead of once per map. An obstacle the walkable area
/// surrounds and smaller than `max_island_area` (a desk, a pillar, a pocket nothing saw) is
/// flooded over like floor, so it neither narrows nor splits a room; its cells get no label.
#include <cstdint>
#include <vector>

#include "tsgraphs/core/grid_frame.hpp"

namespace tsgraphs::rooms {

/// Labels the cells of `walkable` (per cell of `frame`) by space, 0..n-1 in the order of their
/// first cell, -1 elsewhere; returns n. `max_half_width` (m), `narrowing` (0-1) and
/// `max_island_area` (m^2) as above.
int split_at_narrowings(const GridFrame& frame, const std::vector<std::uint8_t>& walkable,
                        double max_half_width, double narrowing, double max_island_area,
                        std::vector<int>* label);

}  // namespace tsgraphs::rooms
