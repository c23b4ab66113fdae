#include "tsgraphs/pipeline/sequence_runner.hpp"

#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <chrono>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::pipeline {
namespace {

// Scans in flight at once: each holds a raw scan (about 1 MB) while it is read and prepared.
constexpr std::size_t kTokensPerThread = 2;

struct Loaded {
  std::size_t index = 0;
  bool keyframe_candidate = false;
  PreparedScan prepared;
  std::string error;  ///< why the scan file could not be read
};

}  // namespace

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

RunInfo run_sequence(const io::ScanSequence& sequence, Pipeline& pipeline, const RunCallbacks& callbacks) {
  const auto start = std::chrono::steady_clock::now();
  const io::SequenceInfo& info = sequence.info();
  RunInfo run;
  run.sequence = sequence.dir();
  run.num_scans = sequence.size();
  run.lap_starts = info.lap_starts;
  // Reading and the per-scan steps (prefilter, ground) run in parallel on the next scans;
  // the pipeline takes them in order, so the result is the same as one scan at a time.
  const std::size_t tokens = kTokensPerThread * static_cast<std::size_t>(std::max(
      1, static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism))));
  std::size_t next = 0;
  KeyframeSelector candidates(pipeline.config().keyframes);  // guesses the keyframes from odometry alone
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, Loaded>(tbb::filter_mode::serial_in_order,
                                     [&](tbb::flow_control& fc) {
                                       Loaded l;
                                       if (next >= sequence.size()) {
                                         fc.stop();
                                         return l;
                                       }
                                       l.index = next++;
                                       l.keyframe_candidate = candidates.is_keyframe(info.odometry[l.index]);
                                       if (l.keyframe_candidate) candidates.accept(info.odometry[l.index]);
                                       return l;
                                     }) &
          tbb::make_filter<Loaded, Loaded>(tbb::filter_mode::parallel,
                                           [&](Loaded l) {
                                             const std::size_t i = l.index;
                                             PointCloud scan;
                                             try {
                                               scan = sequence.scan(i);
                                             } catch (const std::exception& e) {
                                               l.error = e.what();
                                             }
                                             l.prepared =
                                                 pipeline.prepare(i, info.times[i], scan, info.odometry[i], l.keyframe_candidate);
                                             return l;
                                           }) &
          tbb::make_filter<Loaded, void>(tbb::filter_mode::serial_in_order, [&](Loaded l) {
            const std::size_t i = l.index;
            const ScanRecord& rec = pipeline.process(std::move(l.prepared));
            if (!l.error.empty()) {
              ++run.num_skipped;
              if (callbacks.warning) callbacks.warning(l.error + ": scan skipped, its pose taken from odometry");
            } else if (!rec.warning.empty()) {
              ++run.num_skipped;
              if (callbacks.warning) callbacks.warning("scan " + std::to_string(i) + ": " + rec.warning);
            }
            if (callbacks.progress) callbacks.progress(i + 1, sequence.size());
          }));
  pipeline.finish();
  if (info.times.size() >= 2) {
    const double period = (info.times.back() - info.times.front()) / static_cast<double>(info.times.size() - 1);
    run.sequence_duration_s = info.times.back() - info.times.front() + period;
  }
  run.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.peak_rss_mb = peak_rss_mb();
  return run;
}

}  // namespace tsgraphs::pipeline
