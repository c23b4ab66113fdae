#include "tsgraphs/pipeline/sequence_runner.hpp"

#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/odometry/deskew.hpp"
#include "tsgraphs/odometry/lidar_odometry.hpp"
#include "tsgraphs/pipeline/odometry_choice.hpp"
#include "tsgraphs/odometry/sweep_deskewer.hpp"

namespace tsgraphs::pipeline {
namespace {

// Scans in flight at once, per thread: enough to reach the next keyframe candidate (1 m at
// walking pace is ~10 scans at 10 Hz), so that its keyframe steps run beside the processing of
// the one before; each holds a raw scan (about 1 MB) from reading to processing.
constexpr std::size_t kTokensPerThread = 8;
// The same when scans are asked their presence first: a scan that is no keyframe then holds a
// few bytes in flight, so the look-ahead reaches several keyframe candidates, whose steps fill
// the other core while the in-order stage takes a slow keyframe (a room's segmentation, a loop).
constexpr std::size_t kTokensPerThreadPresenceFirst = 32;
// Lost odometry scans told one by one; more are counted at the end.
constexpr std::size_t kLostScansTold = 5;

struct Loaded {
  std::size_t index = 0;
  bool keyframe_candidate = false;
  Pose3 odom = Pose3::Identity();
  io::ScanPresence presence;
  bool loaded = false;  ///< `scan` read whole (else only its presence: no keyframe is expected)
  PointCloud scan;      ///< as read (de-skewed), until processed
  PreparedScan prepared;
  std::string error;             ///< why the scan file could not be read
  std::string odometry_warning;  ///< the LiDAR odometry lost this scan
};

}  // namespace

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

void measure_platform(const io::ScanSequence& sequence, bool poses_estimated, Pipeline& pipeline) {
  const std::size_t total = sequence.size();
  const std::size_t n = std::min(total, static_cast<std::size_t>(pipeline.config().platform.measure.scans));
  const std::vector<Pose3>& poses = sequence.info().odometry;
  const bool use_poses = !poses_estimated && poses.size() == total;
  std::vector<PointCloud> scans;
  std::vector<Eigen::Vector3d> ups;
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t i = n == 1 ? 0 : j * (total - 1) / (n - 1);
    try {
      scans.push_back(sequence.scan(i));
    } catch (const std::exception&) {
      continue;  // an unreadable scan is skipped with its warning when the run reaches it
    }
    if (use_poses) ups.push_back(poses[i].linear().transpose() * Eigen::Vector3d::UnitZ());
  }
  pipeline.set_platform(scans, ups);
}

Eigen::Vector3d map_origin_of(const Pose3& first) { return float_safe_origin(first.translation()); }

namespace {

/// One run of a sequence through a pipeline: the state its stages share, a method per stage.
class SequenceRun {
 public:
  SequenceRun(const io::ScanSequence& sequence, Pipeline& pipeline, const RunCallbacks& callbacks,
              const OdometryOptions& odometry)
      : sequence_(sequence),
        info_(sequence.info()),
        pipeline_(pipeline),
        callbacks_(callbacks),
        deskew_(pipeline.config().deskew),
        candidates_(pipeline.config().keyframes),
        // With the odometry given, a scan is first asked only whether it holds points where the
        // source tells that cheaply: most scans are no keyframe, and that is all the run needs
        // of them (read whole, they were 9 % of the built-in atrium's CPU). The LiDAR odometry
        // needs every scan whole.
        presence_first_(!odometry.estimate && sequence.presence_is_cheap()) {
    run_.sequence = sequence.dir();
    run_.num_scans = sequence.size();
    run_.lap_starts = info_.lap_starts;
    run_.estimated_odometry = odometry.estimate;
    if (odometry.estimate || !info_.odometry.empty())
      run_.map_origin = map_origin_of(odometry.estimate ? odometry.initial_pose : info_.odometry.front());
    if (!pipeline_.platform()) {
      measure_platform(sequence, odometry.estimate, pipeline_);
      if (callbacks_.note) callbacks_.note(describe(*pipeline_.platform()));
    }
    tell_warnings();
    if (odometry.estimate)
      lidar_odometry_.emplace(make_lidar_odometry(pipeline_.config(), in_map(odometry.initial_pose)));
  }

  /// Scans in flight at once.
  std::size_t tokens() const {
    const auto threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    return (presence_first_ ? kTokensPerThreadPresenceFirst : kTokensPerThread) *
           static_cast<std::size_t>(std::max(1, static_cast<int>(threads)));
  }

  /// Stage 1 (in order): the next scan's index, or the end.
  Loaded next(tbb::flow_control& fc) {
    Loaded l;
    if (next_ >= sequence_.size()) {
      fc.stop();
      return l;
    }
    l.index = next_++;
    return l;
  }

  /// Stage 2 (parallel): the scan read, or only its presence.
  void read(Loaded& l) const {
    try {
      if (presence_first_) {
        l.presence = sequence_.presence(l.index);
        if (l.presence.has_times) read_whole(l);  // de-skewed in order
      } else {
        read_whole(l);
      }
    } catch (const std::exception& e) {
      l.error = e.what();
    }
  }

  /// Stage 3 (in order): the scan's pose, the scan de-skewed, and whether it may be a keyframe.
  void locate(Loaded& l) {
    // An unreadable scan is empty here: the odometry keeps its prediction.
    l.odom = lidar_odometry_ ? lidar_odometry_->register_scan(l.scan, info_.times[l.index])
                             : in_map(info_.odometry[l.index]);
    if (deskew_.enabled && l.scan.has_times()) deskew(l);
    if (lidar_odometry_ && lidar_odometry_->last_icp().lost) {
      const odometry::IcpResult& icp = lidar_odometry_->last_icp();
      l.odometry_warning = "scan " + std::to_string(l.index) + ": LiDAR odometry lost: " +
                           std::to_string(static_cast<int>(std::lround(100.0 * icp.overlap))) +
                           " % of its points fall in the map (below lidar_odometry.min_overlap)"
                           "; its pose is kept, its points stay out of the odometry's map";
    }
    // As Pipeline::process: a scan without a finite point is no keyframe.
    l.keyframe_candidate = l.presence.has_finite && candidates_.is_keyframe(l.odom);
    if (l.keyframe_candidate) candidates_.accept(l.odom);
  }

  /// Stage 4 (parallel): the keyframe steps of a keyframe candidate, read whole first.
  void prepare(Loaded& l) const {
    const std::size_t i = l.index;
    if (l.keyframe_candidate && !l.loaded) {
      try {
        read_whole(l);
      } catch (const std::exception& e) {
        l.error = e.what();
        l.keyframe_candidate = false;
      }
    }
    l.prepared = pipeline_.prepare(i, info_.times[i], l.scan, l.odom, l.keyframe_candidate);
    if (!l.loaded && l.error.empty()) tell_presence(l);
  }

  /// Stage 5 (in order): the scan through the pipeline, its warnings told.
  void process(Loaded& l) {
    const std::size_t i = l.index;
    // A keyframe the guess missed (after a scan without points) is read whole now.
    if (!l.loaded && l.error.empty() && pipeline_.would_be_keyframe(l.odom)) {
      try {
        read_whole(l);
      } catch (const std::exception& e) {
        l.error = e.what();
        l.prepared.input_empty = l.prepared.input_no_points = true;  // as an unreadable scan
      }
    }
    const ScanRecord& rec = pipeline_.process(std::move(l.prepared), l.scan);
    if (!l.odometry_warning.empty()) {
      ++run_.num_odometry_lost;
      if (callbacks_.warning && run_.num_odometry_lost <= kLostScansTold)
        callbacks_.warning(l.odometry_warning);
    }
    if (!l.error.empty()) {
      ++run_.num_skipped;
      if (callbacks_.warning) callbacks_.warning(l.error + ": scan skipped, its pose taken from odometry");
    } else if (!rec.warning.empty()) {
      ++run_.num_skipped;
      if (callbacks_.warning) callbacks_.warning("scan " + std::to_string(i) + ": " + rec.warning);
    }
    tell_warnings();
    if (callbacks_.progress) callbacks_.progress(i + 1, sequence_.size());
  }

  /// The pipeline finished; the run's facts.
  RunInfo finish(std::chrono::steady_clock::time_point start) {
    pipeline_.finish();
    tell_warnings();
    if (callbacks_.warning && run_.num_odometry_lost > kLostScansTold)
      callbacks_.warning("LiDAR odometry lost " + std::to_string(run_.num_odometry_lost) + " scans in all");
    const std::vector<double>& times = info_.times;
    if (times.size() >= 2) {
      const double period = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
      run_.sequence_duration_s = times.back() - times.front() + period;
    }
    run_.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run_.peak_rss_mb = peak_rss_mb();
    return run_;
  }

 private:
  /// Input poses into the map frame (relative motions, as the de-skewing's, need no change).
  Pose3 in_map(Pose3 pose) const {
    pose.translation() -= run_.map_origin;
    return pose;
  }

  void tell_warnings() {
    for (; warnings_told_ < pipeline_.warnings().size(); ++warnings_told_)
      if (callbacks_.warning) callbacks_.warning(pipeline_.warnings()[warnings_told_]);
  }

  void read_whole(Loaded& l) const {
    l.scan = sequence_.scan(l.index);
    l.loaded = true;
    l.presence.empty = l.scan.empty();
    l.presence.has_finite = l.scan.has_finite_point();
    l.presence.has_times = l.scan.has_times();
  }

  /// A scan not read whole: what process() says of it comes from its presence.
  static void tell_presence(Loaded& l) {
    l.prepared.input_empty = !l.presence.has_finite;
    l.prepared.input_no_points = l.presence.empty;
  }

  /// De-skewed after the odometry: with the motion its sweep registration found, else with the
  /// poses' motion or a registration of the sweep's own (deskew.hpp, sweep_motion).
  void deskew(Loaded& l) {
    if (lidar_odometry_ && lidar_odometry_->last_sweep().registered) {
      l.scan = odometry::deskew(l.scan, lidar_odometry_->last_sweep().after(1.0), 1.0);
      return;
    }
    const auto [motion, interval] = odometry::sweep_motion(l.index, info_.times, info_.odometry,
                                                           lidar_odometry_ ? &*lidar_odometry_ : nullptr);
    if (register_sweep(l.index, l.scan)) {
      if (!sweeps_) sweeps_.emplace(pipeline_.config().lidar_odometry, deskew_.registration);
      l.scan = sweeps_->deskew(l.scan, l.odom, motion, interval);
    } else {
      l.scan = odometry::deskew(l.scan, motion, interval);
    }
  }

  /// Registration, or the poses' motion: auto registers when scans are farther apart than the
  /// sweep lasts by max_interval_ratio, as then the poses miss the motion inside a sweep.
  bool register_sweep(std::size_t i, const PointCloud& scan) const {
    if (deskew_.motion != odometry::DeskewMotion::automatic)
      return deskew_.motion == odometry::DeskewMotion::registration;
    if (info_.times.size() < 2) return false;
    const std::size_t a = i + 1 < info_.times.size() ? i : i - 1;
    const double interval = info_.times[a + 1] - info_.times[a];
    const auto [lo, hi] = std::minmax_element(scan.times.begin(), scan.times.end());
    const double sweep = static_cast<double>(*hi - *lo);
    return sweep > 0.0 && interval > deskew_.max_interval_ratio * sweep;
  }

  const io::ScanSequence& sequence_;
  const io::SequenceInfo& info_;
  Pipeline& pipeline_;
  const RunCallbacks& callbacks_;
  const odometry::DeskewConfig& deskew_;
  KeyframeSelector candidates_;  // guesses the keyframes from odometry alone
  const bool presence_first_;
  RunInfo run_;
  std::optional<odometry::LidarOdometry> lidar_odometry_;
  std::optional<odometry::SweepDeskewer> sweeps_;  // made at the first sweep it registers
  std::size_t next_ = 0;
  std::size_t warnings_told_ = 0;
};

}  // namespace

RunInfo run_sequence(const io::ScanSequence& sequence, Pipeline& pipeline, const RunCallbacks& callbacks,
                     const OdometryOptions& odometry) {
  const auto start = std::chrono::steady_clock::now();
  if (!odometry.estimate && sequence.info().odometry.size() != sequence.size())
    throw std::invalid_argument("run_sequence: " + sequence.dir() + " has " +
                                std::to_string(sequence.info().odometry.size()) + " odometry poses for " +
                                std::to_string(sequence.size()) + " scans; estimate them");
  SequenceRun run(sequence, pipeline, callbacks, odometry);
  // Reading and the keyframe steps (prefilter, ground, planes of keyframe candidates) run in
  // parallel on the next scans; the odometry and the pipeline take them in order, so the
  // result is the same as one scan at a time.
  using tbb::filter_mode;
  tbb::parallel_pipeline(
      run.tokens(),
      tbb::make_filter<void, Loaded>(filter_mode::serial_in_order, [&](tbb::flow_control& fc) {
        return run.next(fc);
      }) & tbb::make_filter<Loaded, Loaded>(filter_mode::parallel, [&](Loaded l) {
        run.read(l);
        return l;
      }) & tbb::make_filter<Loaded, Loaded>(filter_mode::serial_in_order, [&](Loaded l) {
        run.locate(l);
        return l;
      }) & tbb::make_filter<Loaded, Loaded>(filter_mode::parallel, [&](Loaded l) {
        run.prepare(l);
        return l;
      }) & tbb::make_filter<Loaded, void>(filter_mode::serial_in_order, [&](Loaded l) { run.process(l); }));
  return run.finish(start);
}

}  // namespace tsgraphs::pipeline
