#pragma once
/// `generate --realistic`: windows. Facade walls get rows of windows, a band from about 0.9 m
/// to 2.1 m above the floor, glazed (a pane the LiDAR partly sees through, as a glass
/// railing's: Opening::transmission) or, now and then, open; some walls between a room and a
/// corridor get a glazed band (a meeting room's glass front). A wall with windows still bounds
/// its room (docs/generator.md, "Realistic buildings").
#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/generator/random.hpp"

namespace tsgraphs::generator {

/// Adds window openings to the walls add_floor_plan made for `plan` (`result`), keeping
/// clear of their doors. Returns the number of windows made.
int add_windows(const FloorPlan& plan, const PlanResult& result, Rng& rng, scene::Scene* scene);

}  // namespace tsgraphs::generator
