// Outputs kept apart from inputs (output_checks.hpp).
#include "output_checks.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/occupancy_map.hpp"

namespace tsgraphs::app {

namespace fs = std::filesystem;

namespace {

fs::path resolved(const std::string& name) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(name), ec);
  return ec ? fs::absolute(name).lexically_normal() : p;
}

/// `inner` is `outer` or lies below it.
bool within(const fs::path& inner, const fs::path& outer) {
  const auto [o, i] = std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end());
  // A trailing empty element ("dir/") matches anything.
  return o == outer.end() || (std::next(o) == outer.end() && o->empty());
}

}  // namespace

void check_output_apart(const std::string& option, const std::string& output,
                        const std::vector<std::string>& inputs) {
  if (output.empty()) return;
  const fs::path out = resolved(output);
  for (const std::string& input : inputs) {
    if (input.empty()) continue;
    const fs::path in = resolved(input);
    if (out == in) throw input_error(option, 0, output + " is the command's input " + input);
    if (within(out, in)) throw input_error(option, 0, output + " lies inside the command's input " + input);
    if (within(in, out)) throw input_error(option, 0, output + " holds the command's input " + input);
  }
}

std::vector<std::string> scene_inputs(const scene::Scene& scene) {
  std::vector<std::string> files;
  if (scene.file.rfind("builtin:", 0) != 0) files.push_back(scene.file);
  for (const scene::VoxelMap& v : scene.voxel_maps) files.push_back(v.file);
  return files;
}

std::vector<std::string> map_inputs(const std::string& map_yaml) {
  return {map_yaml, io::read_map_yaml(map_yaml).image};
}

}  // namespace tsgraphs::app
