#pragma once
/// Furniture for a storey's spaces once their walls and doors exist: desks, shelves and
/// cabinets against the walls of offices, rows of free-standing shelves in library halls,
/// desk clusters with partitions lower than the ceiling and pillars in open-plan halls. A
/// door's approach stays clear on both sides. None of it bounds a room (docs/generator.md).
#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/generator/random.hpp"

#include <vector>

#include "tsgraphs/core/rect.hpp"

namespace tsgraphs::generator {

/// Adds boxes (and low partitions, as walls) to `scene` for the spaces of `plan` on `level`,
/// whose faces and doors add_floor_plan has already put there (`result`). Nothing is placed
/// over `keep_clear` (door leaves) or within the furniture's spacing of it.
void furnish(const FloorPlan& plan, const PlanResult& result, int level, Rng& rng, scene::Scene* scene,
             const std::vector<OrientedRect>& keep_clear = {});

/// The floor kept free round a door so that one can walk up to it from either side: a disc
/// round the opening's centre.
struct DoorApproach {
  Vec2 center = Vec2::Zero();
  double radius = 0.0;
};
/// The approaches of every door (an opening from the floor) of `level`.
std::vector<DoorApproach> door_approaches(const scene::Scene& scene, int level);

}  // namespace tsgraphs::generator
