/// Fuzz target: TUM trajectory files (stamp x y z qx qy qz qw) through read_tum.
#include "fuzz_support.hpp"
#include "tsgraphs/io/tum.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = tsgraphs::fuzz::input_file(data, size, "odom.tum");
  tsgraphs::fuzz::only_input_errors("read_tum", [&] { tsgraphs::io::read_tum(file); });
  return 0;
}
