/// Fuzz target: MCAP files through mcap::Reader: the structure, the summary's index (or the
/// scan from the start), and every message read back (chunks decompressed, CRCs checked).
#include "fuzz_support.hpp"
#include "tsgraphs/mcap/mcap.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = tsgraphs::fuzz::input_file(data, size, "bag.mcap");
  tsgraphs::fuzz::only_input_errors("mcap::Reader", [&] {
    const tsgraphs::mcap::Reader reader(file);
    for (const auto& ref : reader.messages()) reader.read(ref);
  });
  return 0;
}
