/// Fuzz target: a rosbag2 bag folder's metadata.yaml through read_rosbag2_metadata, the first
/// thing `run`, `convert` and `bag-info` read of a bag folder, in a folder holding the files
/// the seeds list (empty: only their names are read here) and a link to one of them.
#include <filesystem>
#include <fstream>

#include "fuzz_support.hpp"
#include "tsgraphs/ros2_bag/rosbag2.hpp"

namespace {

const std::filesystem::path& bag_folder() {
  static const std::filesystem::path folder = [] {
    const std::filesystem::path dir = tsgraphs::fuzz::scratch_dir() / "bag";
    std::filesystem::create_directories(dir);
    for (const char* name : {"bag_0.db3", "bag_1.db3", "bag_0.mcap", "bag_0.db3.zstd", "bag_0.mcap.zstd"}) {
      std::ofstream(dir / name);
    }
    std::error_code ec;  // a second spelling of bag_0.db3, for the repeats' check
    std::filesystem::create_symlink("bag_0.db3", dir / "link_0.db3", ec);
    return dir;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  const std::string folder = bag_folder().string();
  fuzz::input_file(data, size, "bag/metadata.yaml");
  fuzz::only_input_errors("read_rosbag2_metadata", [&] { ros2_bag::read_rosbag2_metadata(folder); });
  return 0;
}
