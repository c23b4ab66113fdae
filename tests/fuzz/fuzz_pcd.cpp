/// Fuzz target: PCD files (ASCII, binary, binary_compressed) through read_pcd.
#include "fuzz_support.hpp"
#include "tsgraphs/io/pcd.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = tsgraphs::fuzz::input_file(data, size, "scan.pcd");
  tsgraphs::fuzz::only_input_errors("read_pcd", [&] { tsgraphs::io::read_pcd(file); });
  return 0;
}
