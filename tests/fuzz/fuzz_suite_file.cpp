/// Fuzz target: suite files (docs/suite.md) through load_suite, as `tsgraphs suite` reads them,
/// in a folder holding what the seeds' cases name: a map and its room labels (import cases, only
/// checked to exist here) and a sequence folder; scene cases name built-in scenes.
#include <filesystem>
#include <fstream>

#include "fuzz_support.hpp"
#include "suite_file.hpp"

namespace {

const std::filesystem::path& suite_folder() {
  static const std::filesystem::path folder = [] {
    const std::filesystem::path dir = tsgraphs::fuzz::scratch_dir() / "suite";
    std::filesystem::create_directories(dir / "seq" / "scans");
    for (const char* name : {"map.yaml", "rooms.png", "seq/times.txt", "seq/odom.txt"})
      std::ofstream(dir / name);
    return dir;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  suite_folder();
  const std::string file = fuzz::input_file(data, size, "suite/suite.yaml");
  fuzz::only_input_errors("load_suite", [&] { app::load_suite(file); });
  return 0;
}
