/// Fuzz target: what import-map reads: PNG and PGM images (maps, and room labels in either
/// convention), and the ROS map_server map.yaml.
#include "fuzz_support.hpp"
#include "tsgraphs/io/image.hpp"
#include "tsgraphs/io/occupancy_map.hpp"
#include "tsgraphs/io/room_labels.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  fuzz::only_input_errors("room_labels", [&] { io::room_labels(io::decode_image(bytes, "map.png")); });
  fuzz::only_input_errors("parse_map_yaml", [&] {
    io::parse_map_yaml(bytes, "map.yaml", (fuzz::scratch_dir() / "none").string());
  });
  return 0;
}
