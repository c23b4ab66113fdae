#include "tsgraphs/pipeline/sequence_runner.hpp"

#include <sys/resource.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::pipeline {
namespace {

// Scans read ahead of the pipeline; enough to hide disk latency, small in memory (~1 MB each).
constexpr std::size_t kReadAhead = 8;

struct LoadedScan {
  PointCloud cloud;
  std::string error;  ///< why it could not be read
};

// Reads scans in order on its own thread into a bounded queue.
class ScanPrefetcher {
 public:
  explicit ScanPrefetcher(const io::SequenceReader& seq) : seq_(seq), thread_([this] { loop(); }) {}
  ~ScanPrefetcher() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  LoadedScan next() {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [&] { return !queue_.empty(); });
    LoadedScan s = std::move(queue_.front());
    queue_.pop_front();
    cv_.notify_all();
    return s;
  }

 private:
  void loop() {
    for (std::size_t i = 0; i < seq_.size(); ++i) {
      LoadedScan s;
      try {
        s.cloud = seq_.scan(i);
      } catch (const std::exception& e) {
        s.error = e.what();
      }
      std::unique_lock<std::mutex> lock(mutex_);
      cv_.wait(lock, [&] { return stop_ || queue_.size() < kReadAhead; });
      if (stop_) return;
      queue_.push_back(std::move(s));
      cv_.notify_all();
    }
  }

  const io::SequenceReader& seq_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<LoadedScan> queue_;
  bool stop_ = false;
  std::thread thread_;  // last: started once the members above exist
};

}  // namespace

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

RunInfo run_sequence(const io::SequenceReader& sequence, Pipeline& pipeline, const RunCallbacks& callbacks) {
  const auto start = std::chrono::steady_clock::now();
  const io::SequenceInfo& info = sequence.info();
  RunInfo run;
  run.sequence = sequence.dir();
  run.num_scans = sequence.size();
  {
    ScanPrefetcher prefetcher(sequence);
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      LoadedScan scan = prefetcher.next();
      const ScanRecord& rec = pipeline.process(i, info.times[i], scan.cloud, info.odometry[i]);
      if (!scan.error.empty()) {
        ++run.num_skipped;
        if (callbacks.warning) callbacks.warning(scan.error + ": scan skipped, its pose taken from odometry");
      } else if (!rec.warning.empty()) {
        ++run.num_skipped;
        if (callbacks.warning) callbacks.warning("scan " + std::to_string(i) + ": " + rec.warning);
      }
      if (callbacks.progress) callbacks.progress(i + 1, sequence.size());
    }
  }
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
