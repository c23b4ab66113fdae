// LiDAR odometry over a whole sequence folder: drift against groundtruth.txt and speed.
//   bench_odometry SEQ_DIR [--threads N] [--voxel-size M] [--convergence X] [--max-iterations N]
//                  [--point-to-point 1] [--out-tum FILE] [--every N] [--yaw-search DEG]
//                  [--fine-threshold M] [--recovery-search M] [--tilt hold|repeat|auto]
//                  [--yaw-candidates N] [--sweep-motion 0|1] [--turn-from-sweep 0|1]
// --every N: every N-th scan only (a 10 Hz sequence seen at 10 / N Hz). --yaw-search DEG: the
// initial guess's search (lidar_odometry.yaw_search_deg; 0: the constant-velocity prediction alone).
// --fine-threshold, --recovery-search: lidar_odometry.fine_threshold and recovery_search_m (0: off).
// --tilt, --yaw-candidates, --sweep-motion, --turn-from-sweep: lidar_odometry.tilt_prediction,
// yaw_search_candidates, sweep_motion, turn_from_sweep.
// The odometry is the one `run --odometry lidar` and `convert` estimate with, started where they
// start it (pipeline/odometry_choice.hpp): its ATE is the run's `eval` odometry ATE_rmse.
// --every N keeps the scans' stamps, as a sequence recorded at 10 / N Hz.
// ATE: the RMS position error over every scan, the estimate anchored at the first ground-truth
// pose (no further alignment: drift counts). Drift: the estimate is anchored at the first ground-truth pose;
// the position error is given as a share of the path length travelled so far (at the end of lap 1, and its
// maximum over the run once the path is at least kMinPathForRatio long, so the first metres do not divide by
// ~0). Segment drift: the KITTI benchmark's relative translation error (eval::segment_drift) over
// kSegmentLengths.
// Step error: each scan's motion from the one before against the truth's (RPE over one scan).
// Speed: wall time of the whole run (reading included) against the scans' time span.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <memory>
#include <string>
#include <vector>

#include "tsgraphs/eval/trajectory_metrics.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/io/subsampled_sequence.hpp"
#include "tsgraphs/pipeline/odometry_sequence.hpp"
#include "tsgraphs/pipeline/odometry_choice.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"

using namespace tsgraphs;

namespace {
constexpr double kMinPathForRatio = 10.0;  // m
constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kFailedStepDeg = 5.0;  // a step this far off in rotation is a failure, not noise
constexpr double kWrongTurnDeg = 15.0;  // a heading this far off is a wrong turn taken, not drift
// Segment drift's lengths: KITTI's 100-800 m are longer than a floor's walk; these span a room
// to a lap of a floor.
const std::vector<double> kSegmentLengths = {10.0, 20.0, 50.0, 100.0, 200.0};

odometry::TiltPrediction tilt_prediction(const std::string& word) {
  const auto value = odometry::kTiltPredictions.parse(word);
  if (!value) {
    std::fprintf(stderr, "bench_odometry: --tilt %s\n", odometry::kTiltPredictions.describe().c_str());
    std::exit(2);
  }
  return *value;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s SEQ_DIR [--threads N] [--voxel-size M] [--convergence X] [--max-iterations N] "
                 "[--point-to-point 1] [--out-tum FILE] [--every N] [--yaw-search DEG] [--fine-threshold M] "
                 "[--recovery-search M]\n",
                 argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  int threads = 0;
  std::size_t every = 1;
  std::string out_tum;
  // The odometry `run` and `convert` estimate with (pipeline/odometry_choice.hpp), its fields
  // changed by the options below.
  pipeline::PipelineConfig config;
  odometry::LidarOdometryConfig& lidar = config.lidar_odometry;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (a == "--voxel-size")
      lidar.voxel_size = std::atof(argv[i + 1]);
    else if (a == "--convergence")
      lidar.convergence_criterion = std::atof(argv[i + 1]);
    else if (a == "--max-iterations")
      lidar.max_iterations = std::atoi(argv[i + 1]);
    else if (a == "--point-to-point")
      lidar.point_to_plane = std::atoi(argv[i + 1]) == 0;
    else if (a == "--out-tum")
      out_tum = argv[i + 1];
    else if (a == "--yaw-search")
      lidar.yaw_search_deg = std::atof(argv[i + 1]);
    else if (a == "--recovery-search")
      lidar.recovery_search_m = std::atof(argv[i + 1]);
    else if (a == "--fine-threshold")
      lidar.fine_threshold = std::atof(argv[i + 1]);
    else if (a == "--sweep-motion")
      lidar.sweep_motion = std::atoi(argv[i + 1]) != 0;
    else if (a == "--yaw-candidates")
      lidar.yaw_search_candidates = std::atoi(argv[i + 1]);
    else if (a == "--tilt")
      lidar.tilt_prediction = tilt_prediction(argv[i + 1]);
    else if (a == "--turn-from-sweep")
      lidar.turn_from_sweep = std::atoi(argv[i + 1]) != 0;
    else if (a == "--every")
      every = static_cast<std::size_t>(std::max(1, std::atoi(argv[i + 1])));
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

  const io::SequenceReader full(dir);
  const io::SubsampledSequence seq(full, every);
  const auto& info = seq.info();
  const bool has_truth = info.groundtruth.size() == seq.size();
  // The odometry starts where `run --odometry lidar` starts it (the input's first pose, else level
  // with the floor under the first scan) and is anchored at the truth as `eval` anchors it.
  const pipeline::OdometryChoice choice =
      pipeline::choose_odometry(seq, "lidar", std::nullopt, config.floor_levelling);
  odometry::LidarOdometry lidar_odometry = pipeline::make_lidar_odometry(config, choice.options.initial_pose);

  using Clock = std::chrono::steady_clock;
  std::vector<double> scan_ms;
  auto last = Clock::now();
  const auto start = last;
  std::vector<std::size_t> lost;
  std::vector<double> overlaps;
  std::vector<Pose3> poses = pipeline::estimate_odometry(
      seq, lidar_odometry,
      [&](std::size_t, std::size_t) {
        const auto now = Clock::now();
        scan_ms.push_back(std::chrono::duration<double, std::milli>(now - last).count());
        last = now;
      },
      &lost, &overlaps);
  if (has_truth) {
    const Pose3 to_anchor = info.groundtruth.front() * poses.front().inverse();
    for (Pose3& pose : poses) pose = to_anchor * pose;
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  const double span_s = info.times.back() - info.times.front();

  std::vector<double> sorted = scan_ms;
  std::sort(sorted.begin(), sorted.end());
  double mean_ms = 0.0;
  for (double v : scan_ms) mean_ms += v;
  mean_ms /= static_cast<double>(scan_ms.size());
  const double p95_ms = sorted[static_cast<std::size_t>(0.95 * static_cast<double>(sorted.size() - 1))];

  std::printf("sequence        %s\n", dir.c_str());
  std::printf("scans           %zu over %.1f s (every %zu of %zu)\n", seq.size(), span_s, every, full.size());
  std::printf("threads         %s\n", threads > 0 ? std::to_string(threads).c_str() : "all");
  std::printf("wall time       %.2f s  (%.1f ms/scan mean, %.1f p95)\n", wall_s, mean_ms, p95_ms);
  std::printf("odometry RTF    %.1f\n", span_s / wall_s);
  std::sort(overlaps.begin(), overlaps.end());
  const auto pct = [&overlaps](double q) {
    return overlaps[static_cast<std::size_t>(q * static_cast<double>(overlaps.size() - 1))];
  };
  std::printf("lost scans      %zu (voxel overlap min %.2f, p1 %.2f, median %.2f)\n", lost.size(),
              overlaps.front(), pct(0.01), pct(0.5));

  if (!out_tum.empty()) {
    std::ofstream out(out_tum);
    out << std::setprecision(17);
    for (std::size_t k = 0; k < poses.size(); ++k) {
      const Eigen::Quaterniond q(poses[k].linear());
      const Eigen::Vector3d t = poses[k].translation();
      out << info.times[k] << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y()
          << ' ' << q.z() << ' ' << q.w() << '\n';
    }
  }
  if (!has_truth) return 0;

  double path = 0.0, max_ratio = 0.0, max_ratio_at = 0.0;
  double lap1_ratio = -1.0, lap1_err = 0.0, lap1_path = 0.0;
  const double lap2_start = info.lap_starts.size() >= 2 ? info.lap_starts[1] : -1.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (k > 0) path += (info.groundtruth[k].translation() - info.groundtruth[k - 1].translation()).norm();
    const double err = (poses[k].translation() - info.groundtruth[k].translation()).norm();
    if (path >= kMinPathForRatio && err / path > max_ratio) {
      max_ratio = err / path;
      max_ratio_at = path;
    }
    // The last scan of lap 1: the next one is at or after lap 2's start.
    if (lap2_start > 0.0 && lap1_ratio < 0.0 && k + 1 < poses.size() && info.times[k + 1] >= lap2_start) {
      lap1_err = err;
      lap1_path = path;
      lap1_ratio = err / path;
    }
  }
  const double final_err = (poses.back().translation() - info.groundtruth.back().translation()).norm();
  const double final_yaw =
      std::abs(wrap_angle(yaw_of(poses.back()) - yaw_of(info.groundtruth.back()))) * kRadToDeg;
  std::printf("path length     %.1f m\n", path);
  std::printf("ATE rmse        %.3f m (anchored at the first pose, no alignment: eval's odometry ATE_rmse)\n",
              eval::ate_rmse(poses, info.groundtruth));
  if (lap1_ratio >= 0.0) {
    std::printf("end of lap 1    %.3f m over %.1f m = %.3f %%\n", lap1_err, lap1_path, 100.0 * lap1_ratio);
  }
  std::printf("max drift       %.3f %% (at %.1f m; ratios from %.0f m on)\n", 100.0 * max_ratio, max_ratio_at,
              kMinPathForRatio);
  const double seg = eval::segment_drift(poses, info.groundtruth, kSegmentLengths);
  std::printf("segment drift   %.3f %% (KITTI-style: mean over segments of 10, 20, 50, 100, 200 m)\n",
              100.0 * seg);
  std::printf("final error     %.3f m = %.3f %%, yaw %.3f deg\n", final_err, 100.0 * final_err / path,
              final_yaw);
  // Step error (RPE over one scan): each scan's motion from the one before against the truth's.
  // Unlike ATE it does not hang on the first failure of a walk, so it compares odometries
  // step by step.
  std::vector<double> step_deg, step_m;
  for (std::size_t k = 1; k < poses.size(); ++k) {
    const Pose3 e = (info.groundtruth[k - 1].inverse() * info.groundtruth[k]).inverse() *
                    (poses[k - 1].inverse() * poses[k]);
    step_deg.push_back(Eigen::AngleAxisd(e.linear()).angle() * kRadToDeg);
    step_m.push_back(e.translation().norm());
  }
  if (!step_deg.empty()) {
    const auto quantile = [](std::vector<double> v, double q) {
      std::sort(v.begin(), v.end());
      return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
    };
    const auto over =
        std::count_if(step_deg.begin(), step_deg.end(), [](double d) { return d > kFailedStepDeg; });
    // The path walked before the heading first went wrong by kWrongTurnDeg: after a wrong turn
    // the map holds a turned copy of the building, and every later figure depends on how it failed.
    double before_failure = 0.0;
    for (std::size_t k = 1; k < poses.size(); ++k) {
      if (std::abs(wrap_angle(yaw_of(poses[k]) - yaw_of(info.groundtruth[k]))) * kRadToDeg > kWrongTurnDeg)
        break;
      before_failure += (info.groundtruth[k].translation() - info.groundtruth[k - 1].translation()).norm();
    }
    std::printf(
        "step error      %.3f / %.3f deg, %.3f / %.3f m (median / p95); %zu of %zu steps over %.0f deg\n",
        quantile(step_deg, 0.5), quantile(step_deg, 0.95), quantile(step_m, 0.5), quantile(step_m, 0.95),
        static_cast<std::size_t>(over), step_deg.size(), kFailedStepDeg);
    std::printf("first wrong turn %.1f m of %.1f m (the path before the heading is %.0f deg off)\n",
                before_failure, path, kWrongTurnDeg);
  }
  return 0;
}
