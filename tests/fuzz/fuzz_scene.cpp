/// Fuzz target: scene files (docs/scene-format.md) through the scene loader, and the length
/// of the path it describes.
#include "fuzz_support.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::only_input_errors("parse_scene", [&] {
    // A base folder that holds nothing: a scene naming a voxel map or floor plan gets the
    // missing-file error, not another fuzz input.
    const scene::Scene loaded =
        scene::parse_scene(text, "scene.yaml", (fuzz::scratch_dir() / "none").string());
    scene::sequence_scans(loaded);
  });
  return 0;
}
