#pragma once
/// Pictures of one run (read_run_view), each a standalone SVG document in a metric scale
/// with y (or z) up. The same run always gives the same bytes. Every element a reader or a
/// test may count carries a class; dots merged into one path carry their number in a
/// data-count attribute. Style rules are scoped to the picture's root class, so several
/// pictures can be inlined in one HTML page.
#include <string>

#include "tsgraphs/report/run_view.hpp"

namespace tsgraphs::report {

/// Bird's-eye of level `level` (an index of run.levels; 0 when the run has none): the
/// scene's walls and railings in light grey (when run.scene is set), mapped walls
/// ("wall"), traversable nodes ("node"), each room's free space ("free-space"), room and
/// corridor rectangles ("room", "corridor") labelled "id · lap N" ("room-label"),
/// ground-truth rooms dashed ("truth-room") with their names, the estimated and true
/// trajectories ("trajectory-estimated", "trajectory-true"), a legend and a scale bar.
/// Points are drawn on the level their height belongs to (level_of_height).
/// Throws std::invalid_argument for a level the run does not have.
std::string birdseye_svg(const RunView& run, int level);

/// Side view (x horizontal, z up, every y projected): the scene's floor slabs per level
/// with their voids as gaps ("scene-slab"), the run's levels, traversable nodes, rooms'
/// free space and the height of the true and estimated trajectories.
std::string side_view_svg(const RunView& run);

/// Time plot: the front-end's time per scan ("frontend", a polyline) and below it each
/// optimisation's wall time (one marker each: "solve local" or "solve full").
std::string timing_svg(const RunView& run);

}  // namespace tsgraphs::report
