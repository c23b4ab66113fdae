/// Fuzz target: the run folder's files that eval and report read back, each reader on the
/// same bytes: scene_graph.json, rooms_events.jsonl, timings.csv and run_info.json.
#include "fuzz_support.hpp"
#include "tsgraphs/io/run_folder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  const std::string file = fuzz::input_file(data, size, "run_file");
  fuzz::only_input_errors("read_scene_graph", [&] { io::read_scene_graph(file); });
  fuzz::only_input_errors("read_room_events", [&] { io::read_room_events(file); });
  fuzz::only_input_errors("read_timings", [&] { io::read_timings(file); });
  fuzz::only_input_errors("read_run_summary", [&] { io::read_run_summary(file); });
  return 0;
}
