// How straight the de-skewed sweeps are, on scene files (issue 16's hand-held scans kept at
// 2 Hz): each scan of the scene swept as the simulator takes it, de-skewed three ways (not at
// all; with the motion between the scan's pose and the next one's, as `deskew.motion: poses`;
// by sweep registration, as `deskew.motion: registration`, from that motion and the true
// poses), and then compared with the scene seen at an instant from the scan's true pose: the
// distance of each de-skewed point to the surface the instant scans sampled there (beside the
// same for a scan taken at an instant from the stamp's pose, with other noise: the floor of
// this figure), and the
// turn rate found against the true one (tilt: about the sensor's x and y; turn: about z).
// A fifth row de-skews with the true motion over the sweep at a constant rate: what the model
// of a sweep (one turn rate, one velocity) can give at best.
//   ./build/bench/bench_sweep_deskew [--config params.yaml] DIR/cases/*-hand2/scene.yaml
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "tsgraphs/eval/suite_table.hpp"
#include "tsgraphs/odometry/deskew.hpp"
#include "tsgraphs/odometry/sweep_deskewer.hpp"
#include "tsgraphs/odometry/voxel_hash_map.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/sim/simulator.hpp"

using namespace tsgraphs;

namespace {

constexpr double kReferenceVoxel = 0.5;  // m; voxels of the instant scans' map, planes fitted in each
constexpr std::size_t kReferencePoints = 40;
constexpr int kReferenceScans = 5;  // instant scans spread over the sweep's duration
constexpr double kCap = 0.2;        // m; a point farther from the reference counts as this (a surface
                                    // the instant scans missed)

struct Errors {
  double distance = 0.0;  // summed over points
  std::size_t points = 0;
  std::vector<double> sweep_mean;       // per sweep
  double sq_tilt = 0.0, sq_turn = 0.0;  // (deg/s)^2, summed over sweeps
  double sq_velocity = 0.0;             // (m/s)^2, summed over sweeps
  std::size_t sweeps = 0;

  void add_rates(const Eigen::Vector3d& found_deg, const Eigen::Vector3d& truth_deg,
                 const Eigen::Vector3d& found_v, const Eigen::Vector3d& truth_v) {
    const Eigen::Vector3d d = found_deg - truth_deg;
    sq_tilt += d.head<2>().squaredNorm();
    sq_turn += d.z() * d.z();
    sq_velocity += (found_v - truth_v).squaredNorm();
    ++sweeps;
  }
};

Eigen::Vector3d rates_deg(const Pose3& motion, double seconds) {
  const Eigen::AngleAxisd aa(motion.linear());
  return aa.axis() * aa.angle() / seconds * 180.0 / M_PI;
}

// Distance of the scan's points (placed by `pose`) to the reference: to the plane of a planar
// voxel's points, else to the nearest point.
void score(const PointCloud& scan, const Pose3& pose, const odometry::VoxelHashMap& reference,
           const odometry::LidarOdometryConfig& range, Errors& e) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double r = scan.points[i].norm();
    if (!(r >= range.min_range && r <= range.max_range)) continue;
    const Eigen::Vector3d x = pose * scan.points[i].cast<double>();
    const odometry::Neighbour nb = reference.nearest(x);
    double d = kCap;
    if (nb.found)
      d = std::min(kCap, nb.surface == odometry::Surface::planar ? std::abs(nb.normal.dot(x - nb.point))
                                                                 : nb.distance);
    sum += d;
    ++n;
  }
  e.distance += sum;
  e.points += n;
  e.sweep_mean.push_back(n ? sum / static_cast<double>(n) : 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  int first = 1;
  pipeline::PipelineConfig defaults;
  try {
    if (argc > 2 && std::string(argv[1]) == "--config") {
      defaults = pipeline::load_pipeline_config(argv[2]);
      first = 3;
    }
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "%s\n", ex.what());
    return 2;
  }
  if (argc <= first) {
    std::fprintf(stderr, "usage: %s [--config params.yaml] SCENE.yaml...\n", argv[0]);
    return 2;
  }
  const odometry::LidarOdometryConfig& range = defaults.lidar_odometry;
  const char* names[5] = {"none", "poses", "registration", "(taken at an instant)", "(true constant rates)"};
  std::printf(
      "| scene | sweeps | de-skew | points' mean distance (m) | worst decile sweep (m) | tilt rate err "
      "(deg/s) | turn rate err (deg/s) | velocity err (m/s) |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (int a = first; a < argc; ++a) {
    try {
      const scene::Scene scene = scene::load_scene(argv[a]);
      const sim::Simulator sim(scene, scene.seed);
      odometry::SweepDeskewer deskewer(range, defaults.deskew.registration);
      Errors errors[5];
      for (std::size_t k = 0; k + 1 < sim.num_scans(); ++k) {
        const PointCloud swept = sim.scan(k);
        if (!swept.has_times() || swept.empty()) continue;
        const double sweep = *std::max_element(swept.times.begin(), swept.times.end());
        const double t = sim.times()[k], interval = sim.times()[k + 1] - t;
        if (!(sweep > 0.0)) continue;
        const Pose3& stamp = sim.true_poses()[k];
        const Pose3 between = stamp.inverse() * sim.true_poses()[k + 1];
        odometry::VoxelHashMap reference(kReferenceVoxel, kReferencePoints);
        for (int j = 0; j < kReferenceScans; ++j) {
          const Pose3 at = sim.sensor_pose_at(t + sweep * j / (kReferenceScans - 1));
          const PointCloud still = sim.scan_at(at, k);
          std::vector<Eigen::Vector3d> world;
          world.reserve(still.size());
          for (const auto& p : still.points) world.push_back(at * p.cast<double>());
          reference.add_points(world);
        }
        const Pose3 during = stamp.inverse() * sim.sensor_pose_at(t + sweep);
        const Eigen::Vector3d truth = rates_deg(during, sweep);
        const PointCloud from_poses = odometry::deskew(swept, between, interval);
        const PointCloud registered = deskewer.deskew(swept, stamp, between, interval);
        score(swept, stamp, reference, range, errors[0]);
        score(from_poses, stamp, reference, range, errors[1]);
        score(registered, stamp, reference, range, errors[2]);
        score(sim.scan_at(stamp, k + 1), stamp, reference, range, errors[3]);
        score(odometry::deskew(swept, during, sweep), stamp, reference, range, errors[4]);
        const Eigen::Vector3d velocity = during.translation() / sweep, zero = Eigen::Vector3d::Zero();
        errors[0].add_rates(zero, truth, zero, velocity);
        errors[1].add_rates(rates_deg(between, interval), truth, between.translation() / interval, velocity);
        errors[2].add_rates(deskewer.last().turn_rate * 180.0 / M_PI, truth, deskewer.last().velocity,
                            velocity);
        errors[3].add_rates(truth, truth, velocity, velocity);
        errors[4].add_rates(truth, truth, velocity, velocity);
      }
      for (int m = 0; m < 5; ++m) {
        const Errors& e = errors[m];
        const double n = static_cast<double>(std::max<std::size_t>(1, e.sweeps));
        std::printf("| %s | %zu | %s | %.4f | %.4f | %.1f | %.1f | %.3f |\n", argv[a], e.sweeps, names[m],
                    e.distance / static_cast<double>(std::max<std::size_t>(1, e.points)),
                    e.sweep_mean.empty() ? NAN : eval::percentile(e.sweep_mean, 90.0),
                    std::sqrt(e.sq_tilt / n), std::sqrt(e.sq_turn / n), std::sqrt(e.sq_velocity / n));
      }
      std::fflush(stdout);
    } catch (const std::exception& ex) {
      std::fprintf(stderr, "%s: %s\n", argv[a], ex.what());
      return 2;
    }
  }
  return 0;
}
