#pragma once
/// `generate --realistic`: rooms that are not rectangles. A room or hall gives a piece of
/// itself to a closed shaft (a duct, a column's casing, a closet without a door; walls all
/// round, SpaceKind::kShaft): a notch at a corner (the room becomes an L), a notch in the
/// middle of a wall (a pilaster or a riser), or a chamfered corner (a diagonal wall across
/// it). Pieces are taken only where the room meets the facade or another room, never along a
/// corridor or hall it opens onto, and the room keeps most of its area. docs/generator.md,
/// "Realistic buildings".
#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/generator/random.hpp"

namespace tsgraphs::generator {

/// Reshapes some of the plan's rooms and halls (before its doors are joined up); returns the
/// number reshaped. Only right-angled corners and straight walls are cut.
int shape_rooms(FloorPlan* plan, Rng& rng);

}  // namespace tsgraphs::generator
