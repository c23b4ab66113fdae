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

RunInfo run_sequence(const io::ScanSequence& sequence, Pipeline& pipeline, const RunCallbacks& callbacks,
                     const OdometryOptions& odometry) {
  const auto start = std::chrono::steady_clock::now();
  const io::SequenceInfo& info = sequence.info();
  if (!odometry.estimate && info.odometry.size() != sequence.size())
    throw std::invalid_argument("run_sequence: " + sequence.dir() + " has " +
                                std::to_string(info.odometry.size()) + " odometry poses for " +
                                std::to_string(sequence.size()) + " scans; estimate them");
  RunInfo run;
  run.sequence = sequence.dir();
  run.num_scans = sequence.size();
  run.lap_starts = info.lap_starts;
  run.estimated_odometry = odometry.estimate;
  if (odometry.estimate || !info.odometry.empty())
    run.map_origin = map_origin_of(odometry.estimate ? odometry.initial_pose : info.odometry.front());
  // Input poses into the map frame (relative motions, as the de-skewing's, need no change).
  const auto in_map = [origin = run.map_origin](Pose3 pose) {
    pose.translation() -= origin;
    return pose;
  };
  if (!pipeline.platform()) {
    measure_platform(sequence, odometry.estimate, pipeline);
    if (callbacks.note) callbacks.note(describe(*pipeline.platform()));
  }
  std::size_t warnings_told = 0;
  const auto tell_warnings = [&] {
    for (; warnings_told < pipeline.warnings().size(); ++warnings_told)
      if (callbacks.warning) callbacks.warning(pipeline.warnings()[warnings_told]);
  };
  tell_warnings();
  std::optional<odometry::LidarOdometry> lidar_odometry;
  if (odometry.estimate)
    lidar_odometry.emplace(make_lidar_odometry(pipeline.config(), in_map(odometry.initial_pose)));
  // Reading and the keyframe steps (prefilter, ground, planes of keyframe candidates) run in
  // parallel on the next scans; the odometry and the pipeline take them in order, so the
  // result is the same as one scan at a time.
  std::size_t next = 0;
  KeyframeSelector candidates(pipeline.config().keyframes);  // guesses the keyframes from odometry alone
  const DeskewConfig& deskew = pipeline.config().deskew;
  std::optional<odometry::SweepDeskewer> sweeps;  // made at the first sweep it registers
  // Registration, or the poses' motion: auto registers when scans are farther apart than the
  // sweep lasts by max_interval_ratio, as then the poses miss the motion inside a sweep.
  const auto register_sweep = [&](std::size_t i, const PointCloud& scan) {
    if (deskew.motion != "auto") return deskew.motion == "registration";
    if (info.times.size() < 2) return false;
    const std::size_t a = i + 1 < info.times.size() ? i : i - 1;
    const double interval = info.times[a + 1] - info.times[a];
    const auto [lo, hi] = std::minmax_element(scan.times.begin(), scan.times.end());
    const double sweep = static_cast<double>(*hi - *lo);
    return sweep > 0.0 && interval > deskew.max_interval_ratio * sweep;
  };
  // With the odometry given, a scan is first asked only whether it holds points where the
  // source tells that cheaply: most scans are no keyframe, and that is all the run needs of
  // them (read whole, they were 9 % of the built-in atrium's CPU). The LiDAR odometry needs
  // every scan whole.
  const bool presence_first = !odometry.estimate && sequence.presence_is_cheap();
  const std::size_t tokens =
      (presence_first ? kTokensPerThreadPresenceFirst : kTokensPerThread) *
      static_cast<std::size_t>(std::max(1, static_cast<int>(tbb::global_control::active_value(
                                               tbb::global_control::max_allowed_parallelism))));
  const auto read_whole = [&](Loaded& l) {
    l.scan = sequence.scan(l.index);
    l.loaded = true;
    l.presence.empty = l.scan.empty();
    l.presence.has_finite = l.scan.has_finite_point();
    l.presence.has_times = l.scan.has_times();
  };
  // A scan not read whole: what process() says of it comes from its presence.
  const auto tell_presence = [](Loaded& l) {
    l.prepared.input_empty = !l.presence.has_finite;
    l.prepared.input_no_points = l.presence.empty;
  };
  tbb::parallel_pipeline(
      tokens, tbb::make_filter<void, Loaded>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) {
                Loaded l;
                if (next >= sequence.size()) {
                  fc.stop();
                  return l;
                }
                l.index = next++;
                return l;
              }) & tbb::make_filter<Loaded, Loaded>(tbb::filter_mode::parallel, [&](Loaded l) {
                try {
                  if (presence_first) {
                    l.presence = sequence.presence(l.index);
                    if (l.presence.has_times) read_whole(l);  // de-skewed in order
                  } else {
                    read_whole(l);
                  }
                } catch (const std::exception& e) {
                  l.error = e.what();
                }
                return l;
              }) & tbb::make_filter<Loaded, Loaded>(tbb::filter_mode::serial_in_order, [&](Loaded l) {
                // An unreadable scan is empty here: the odometry keeps its prediction.
                l.odom = lidar_odometry ? lidar_odometry->register_scan(l.scan, info.times[l.index])
                                        : in_map(info.odometry[l.index]);
                // De-skewed after the odometry: with the motion its sweep
                // registration found, else with the poses' motion or a
                // registration of the sweep's own (deskew.hpp, sweep_motion).
                if (deskew.enabled && l.scan.has_times() && lidar_odometry &&
                    lidar_odometry->last_sweep().registered) {
                  l.scan = odometry::deskew(l.scan, lidar_odometry->last_sweep().after(1.0), 1.0);
                } else if (deskew.enabled && l.scan.has_times()) {
                  const auto [motion, interval] = odometry::sweep_motion(
                      l.index, info.times, info.odometry, lidar_odometry ? &*lidar_odometry : nullptr);
                  if (register_sweep(l.index, l.scan)) {
                    if (!sweeps) sweeps.emplace(pipeline.config().lidar_odometry, deskew.registration);
                    l.scan = sweeps->deskew(l.scan, l.odom, motion, interval);
                  } else {
                    l.scan = odometry::deskew(l.scan, motion, interval);
                  }
                }
                if (lidar_odometry && lidar_odometry->last_icp().lost) {
                  const odometry::IcpResult& icp = lidar_odometry->last_icp();
                  l.odometry_warning = "scan " + std::to_string(l.index) + ": LiDAR odometry lost: " +
                                       std::to_string(static_cast<int>(std::lround(100.0 * icp.overlap))) +
                                       " % of its points fall in the map (below lidar_odometry.min_overlap)"
                                       "; its pose is kept, its points stay out of the odometry's map";
                }
                // As Pipeline::process: a scan without a finite point is no keyframe.
                l.keyframe_candidate = l.presence.has_finite && candidates.is_keyframe(l.odom);
                if (l.keyframe_candidate) candidates.accept(l.odom);
                return l;
              }) & tbb::make_filter<Loaded, Loaded>(tbb::filter_mode::parallel, [&](Loaded l) {
                const std::size_t i = l.index;
                if (l.keyframe_candidate && !l.loaded) {
                  try {
                    read_whole(l);
                  } catch (const std::exception& e) {
                    l.error = e.what();
                    l.keyframe_candidate = false;
                  }
                }
                l.prepared = pipeline.prepare(i, info.times[i], l.scan, l.odom, l.keyframe_candidate);
                if (!l.loaded && l.error.empty()) tell_presence(l);
                return l;
              }) & tbb::make_filter<Loaded, void>(tbb::filter_mode::serial_in_order, [&](Loaded l) {
                const std::size_t i = l.index;
                // A keyframe the guess missed (after a scan without points) is read whole now.
                if (!l.loaded && l.error.empty() && pipeline.would_be_keyframe(l.odom)) {
                  try {
                    read_whole(l);
                  } catch (const std::exception& e) {
                    l.error = e.what();
                    l.prepared.input_empty = l.prepared.input_no_points = true;  // as an unreadable scan
                  }
                }
                const ScanRecord& rec = pipeline.process(std::move(l.prepared), l.scan);
                if (!l.odometry_warning.empty()) {
                  ++run.num_odometry_lost;
                  if (callbacks.warning && run.num_odometry_lost <= kLostScansTold)
                    callbacks.warning(l.odometry_warning);
                }
                if (!l.error.empty()) {
                  ++run.num_skipped;
                  if (callbacks.warning)
                    callbacks.warning(l.error + ": scan skipped, its pose taken from odometry");
                } else if (!rec.warning.empty()) {
                  ++run.num_skipped;
                  if (callbacks.warning) callbacks.warning("scan " + std::to_string(i) + ": " + rec.warning);
                }
                tell_warnings();
                if (callbacks.progress) callbacks.progress(i + 1, sequence.size());
              }));
  pipeline.finish();
  tell_warnings();
  if (callbacks.warning && run.num_odometry_lost > kLostScansTold)
    callbacks.warning("LiDAR odometry lost " + std::to_string(run.num_odometry_lost) + " scans in all");
  if (info.times.size() >= 2) {
    const double period =
        (info.times.back() - info.times.front()) / static_cast<double>(info.times.size() - 1);
    run.sequence_duration_s = info.times.back() - info.times.front() + period;
  }
  run.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.peak_rss_mb = peak_rss_mb();
  return run;
}

}  // namespace tsgraphs::pipeline
