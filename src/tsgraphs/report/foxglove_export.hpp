#pragma once
/// A run folder as an MCAP file that Foxglove opens with no plug-in (`tsgraphs export RUN_DIR
/// --mcap OUT.mcap`): JSON messages of Foxglove's schemas foxglove.FrameTransform,
/// foxglove.PointCloud and foxglove.SceneUpdate, over the run's time:
///   /tf                 map -> sensor at every scan (trajectory.txt)
///   /map                the thinned map, coloured by layer (map.ply), at the end
///   /traversable_nodes  the traversable nodes (scene_graph.json), at the end
///   /free_space         each room's free space (its latest extraction), at the end
///   /scene              wall planes, the trajectory, floor nodes, at the end
///   /rooms              each room and corridor as it is extracted (rooms_events.jsonl): outline
///                       and label on its level, replaced when it is extracted again
#include <string>

namespace tsgraphs::report {

/// The JSON Schema of one of the Foxglove message types written here ("foxglove.SceneUpdate",
/// "foxglove.PointCloud", "foxglove.FrameTransform"): the fields of Foxglove's published schema
/// that the export writes, each required, no other allowed. std::invalid_argument otherwise.
const std::string& foxglove_schema(const std::string& type);

/// Writes `run_dir` as an MCAP file at `out` (zstd chunks, under a temporary name renamed into
/// place). A run folder missing a file or holding a malformed one is an InputError naming it.
void export_foxglove_mcap(const std::string& run_dir, const std::string& out);

}  // namespace tsgraphs::report
