/// Fuzz target: `import-map` on a small map: its map_server YAML and image read, the image as
/// its own room labels too (the map's free regions as rooms), the floor, walls, rooms and survey
/// path built, the scene and its walls written and read back, as the command does. An input is
/// the YAML, a line "...", then the image's bytes (written as map.pgm, whatever its format: the
/// reader goes by the bytes). A scene that does not read back is the command's own bug
/// (std::runtime_error), so a finding here.
#include <filesystem>

#include "fuzz_support.hpp"
#include "scene_commands.hpp"
#include "tsgraphs/io/occupancy_map.hpp"

namespace {

/// Maps of more cells are left out, so that each input runs well under a second.
constexpr long long kMaxCells = 256 * 256;
/// Where the YAML ends and the image begins (YAML's end-of-document marker).
constexpr char kImageStarts[] = "\n...\n";

/// Whether the map reads as one of more than kMaxCells cells; a map that does not read is left
/// for the command to refuse.
bool too_large(const std::string& yaml) {
  try {
    const tsgraphs::io::OccupancyMap map = tsgraphs::io::read_occupancy_map(yaml);
    return static_cast<long long>(map.width) * map.height > kMaxCells;
  } catch (const tsgraphs::InputError&) {
    return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::size_t cut = bytes.find(kImageStarts);
  const std::string yaml = bytes.substr(0, cut);
  const std::string image = cut == std::string::npos ? "" : bytes.substr(cut + sizeof kImageStarts - 1);
  std::filesystem::create_directories(fuzz::scratch_dir() / "map");
  app::ImportMapOptions options;
  options.map =
      fuzz::input_file(reinterpret_cast<const std::uint8_t*>(yaml.data()), yaml.size(), "map/map.yaml");
  options.rooms =
      fuzz::input_file(reinterpret_cast<const std::uint8_t*>(image.data()), image.size(), "map/map.pgm");
  options.out = (fuzz::scratch_dir() / "out" / "scene.yaml").string();
  options.quiet = true;
  if (too_large(options.map)) return 0;
  std::filesystem::create_directories(fuzz::scratch_dir() / "out");
  fuzz::only_input_errors("import-map", [&] { app::import_map(options); });
  return 0;
}
