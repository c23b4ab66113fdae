#pragma once
/// Outputs kept apart from inputs: no command writes over, into or round what it reads.
#include <string>
#include <vector>

#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::app {

/// Refuses `output` (given by `option`) with an InputError naming it and the input when it is
/// one of `inputs`, lies inside one (an input folder) or holds one (an output folder that would
/// replace its own input). Paths are compared resolved (symbolic links, `..`); empty names are
/// skipped.
void check_output_apart(const std::string& option, const std::string& output,
                        const std::vector<std::string>& inputs);

/// The files a scene reads: the scene file (none for a built-in scene) and its voxel maps.
std::vector<std::string> scene_inputs(const scene::Scene& scene);

/// The files an occupancy map reads: its YAML and the image it names.
std::vector<std::string> map_inputs(const std::string& map_yaml);

}  // namespace tsgraphs::app
