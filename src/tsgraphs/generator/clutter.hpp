#pragma once
/// `generate --realistic`: the clutter of a building in use. Against the walls of rooms, halls
/// and corridors, runs of furniture (cabinets, shelves, sideboards, radiators, printers, bins,
/// stacked boxes) that hide the walls' feet, so that a sensor sees a wall above them and
/// between them, in pieces; chairs at desks; free-standing chairs, tables, bins, boxes and
/// plants. Every piece keeps a walker's passage in front of it (a free-standing one, all
/// round it) and keeps off the doors' approaches, so the survey path still reaches every
/// room. All of it is furniture to the ground truth (docs/generator.md, "Realistic buildings").
#include "tsgraphs/generator/floor_plan.hpp"
#include "tsgraphs/generator/random.hpp"

namespace tsgraphs::generator {

/// Adds clutter (boxes) to the walkable spaces of `plan` on `level` (their faces in `result`),
/// clear of everything already there. `passage` (m) is the least width a walker needs.
/// Returns the number of pieces placed.
int add_clutter(const FloorPlan& plan, const PlanResult& result, int level, double passage, Rng& rng,
                scene::Scene* scene);

}  // namespace tsgraphs::generator
