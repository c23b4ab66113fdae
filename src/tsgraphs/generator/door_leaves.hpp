#pragma once
/// `generate --realistic`: doors as they are in use, left open. Every door gets a realistic
/// width (one leaf 0.85-1.2 m, now and then a double door) and its leaf (or two): a thin box
/// as high as the door, hinged at a jamb and open 30-120 degrees into a room, or into a
/// corridor or hall wide enough to take it. A leaf never narrows its doorway below the
/// passage the survey path needs, never closes a way round it, and stays off every other
/// door's approach; a door where no leaf fits is left without one. Leaves are boxes labelled
/// "door": furniture to the ground truth (docs/generator.md, "Realistic buildings").
#include <vector>

#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/generator/random.hpp"

namespace tsgraphs::generator {

/// Draws the width of every door the plan wants anew: one leaf, or (now and then) two.
void draw_door_widths(FloorPlan* plan, Rng& rng);

/// Hangs leaves in the doors add_floor_plan made for `plan` on `level` (`result`), appended to
/// scene->boxes. `passage` (m) is the least width a walker needs between a leaf and what is
/// across from it. Returns the leaves' footprints.
std::vector<OrientedRect> hang_door_leaves(const FloorPlan& plan, const PlanResult& result, int level,
                                           double passage, Rng& rng, scene::Scene* scene);

}  // namespace tsgraphs::generator
