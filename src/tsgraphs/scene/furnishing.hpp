#pragma once
/// Furniture for a storey's spaces once their walls and doors exist: desks, shelves and
/// cabinets against the walls of offices, rows of free-standing shelves in library halls,
/// desk clusters with partitions lower than the ceiling and pillars in open-plan halls. A
/// door's approach stays clear on both sides. None of it bounds a room (docs/generator.md).
#include "tsgraphs/scene/floor_plan.hpp"
#include "tsgraphs/scene/random.hpp"

namespace tsgraphs::scene {

/// Adds boxes (and low partitions, as walls) to `scene` for the spaces of `plan` on `level`,
/// whose faces and doors add_floor_plan has already put there (`result`).
void furnish(const FloorPlan& plan, const PlanResult& result, int level, Rng& rng, Scene* scene);

}  // namespace tsgraphs::scene
