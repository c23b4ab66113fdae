// The library without the command line: a sequence folder in (docs/scene-format.md; what
// `tsgraphs simulate` and `tsgraphs convert` write), its rooms and corridors out, one a line.
// Usage: rooms_from_sequence SEQ_DIR [PARAMS.yaml]
#include <cstdio>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/pipeline/pipeline.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/pipeline/sequence_runner.hpp"

using namespace tsgraphs;

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s SEQ_DIR [PARAMS.yaml]\n", argv[0]);
    return 2;
  }
  try {
    // The scans, their times and odometry poses, checked against each other.
    const io::SequenceReader sequence(argv[1]);
    // Every parameter has a default; a file overrides some (config/params.yaml lists them).
    const pipeline::PipelineConfig config =
        argc == 3 ? pipeline::load_pipeline_config(argv[2]) : pipeline::PipelineConfig{};
    pipeline::Pipeline pipeline(config);
    // Every scan through the pipeline (read ahead in parallel), then the final optimisation.
    const pipeline::RunInfo info = pipeline::run_sequence(sequence, pipeline);
    // The rooms as mapped, in the input's frame (the pipeline's map frame is offset by map_origin).
    std::printf("%zu scans, %zu keyframes, %zu rooms\n", info.num_scans, pipeline.graph().keyframes().size(),
                pipeline.room_map().rooms().size());
    for (const auto& [id, room] : pipeline.room_map().rooms()) {
      const Vec2 center = room.center() + info.map_origin.head<2>();
      std::printf("%s %d: level %d, centre (%.2f, %.2f) m, %.1f m^2, %zu walls\n",
                  to_string(room.kind).c_str(), id, room.level, center.x(), center.y(),
                  area(room.footprint()), room.wall_ids.size());
    }
  } catch (const InputError& e) {  // bad input: names the file and the place
    std::fprintf(stderr, "rooms_from_sequence: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rooms_from_sequence: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
