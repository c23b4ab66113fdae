/// Fuzz target: parameter files (config/params.yaml) through load_pipeline_config.
#include "fuzz_support.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = tsgraphs::fuzz::input_file(data, size, "params.yaml");
  tsgraphs::fuzz::only_input_errors("load_pipeline_config",
                                    [&] { tsgraphs::pipeline::load_pipeline_config(file); });
  return 0;
}
