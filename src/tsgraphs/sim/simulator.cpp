#include "tsgraphs/sim/simulator.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/sim/odometry_drift.hpp"

namespace tsgraphs::sim {
namespace {

// Counter-based random numbers (splitmix64): every ray's noise depends only on the seed,
// the scan and the ray, so threads cannot change the output.
std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

double to_unit(std::uint64_t x) { return static_cast<double>(x >> 11) * (1.0 / 9007199254740992.0); }

// The platform's gait at time t, in the body frame: a bob and a vibration up and down, roll
// over a stride (half the step rate), pitch with each step, and the heading wandering on two
// slow incommensurate waves, so no two laps sway alike. Smooth in t: a swept scan sees it
// change within its period.
Pose3 gait(const scene::PlatformSpec& p, double t) {
  constexpr double kDeg = M_PI / 180.0;
  const double step = 2.0 * M_PI * p.step_hz * t;
  const double roll = p.sway_deg * kDeg * std::sin(0.5 * step);
  const double pitch = 0.5 * p.sway_deg * kDeg * std::sin(step + M_PI / 3.0);
  const double yaw =
      p.yaw_jitter_deg * kDeg *
      (0.6 * std::sin(2.0 * M_PI * 0.23 * t + 0.4) + 0.4 * std::sin(2.0 * M_PI * 0.61 * t + 1.9));
  const double z = p.bob * std::sin(step) + p.vibration * std::sin(2.0 * M_PI * p.vibration_hz * t + 0.8);
  Pose3 T = Pose3::Identity();
  T.linear() =
      (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.0, 0.0, z);
  return T;
}

}  // namespace

float Reflectivity::of(std::uint32_t label) {
  switch (static_cast<PointLabel>(label)) {
    case PointLabel::kFloor:
      return kFloor;
    case PointLabel::kRamp:
      return kRamp;
    case PointLabel::kCeiling:
      return kCeiling;
    case PointLabel::kWall:
      return kWall;
    case PointLabel::kRailing:
      return kRailing;
    case PointLabel::kBox:
      return kBox;
    case PointLabel::kPerson:
      return kPerson;
    default:
      return 0.5f;
  }
}

Simulator::Simulator(scene::Scene scene, std::uint64_t seed) : scene_(std::move(scene)), seed_(seed) {
  trajectory_ = std::make_unique<scene::Trajectory>(scene_);
  const LabelledMesh mesh = build_scene_mesh(scene_);
  num_triangles_ = mesh.triangles.size();
  caster_ = std::make_unique<RayCaster>(mesh);
  people_ = std::make_unique<People>(scene_);
  beams_ = BeamPattern::from_sensor(scene_.sensor);
  // Scans every 1 / record_hz s (a recording may keep only every n-th sweep); each sweeps for
  // 1 / rate_hz.
  const double dt = 1.0 / (scene_.sensor.record_hz > 0.0 ? scene_.sensor.record_hz : scene_.sensor.rate_hz);
  // The last scan is taken at the end of the path (so a closed path's sequence ends where it
  // starts, as ATE_loop assumes): the motion runs at speed * time_scale_, within half a scan
  // period over the whole path of the scene's speed.
  const std::size_t intervals = static_cast<std::size_t>(std::llround(trajectory_->duration() / dt));
  const std::size_t n = intervals + 1;
  time_scale_ = intervals > 0 ? trajectory_->duration() / (intervals * dt) : 1.0;
  tilt_ = make_pose(Eigen::Vector3d::Zero(), 0.0, scene_.sensor.tilt_deg * M_PI / 180.0);
  std::vector<Pose3> body(n);
  times_.resize(n);
  truth_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    times_[k] = k * dt;
    body[k] = trajectory_->body_pose(k == intervals ? trajectory_->duration() : times_[k] * time_scale_);
    truth_[k] = body[k] * gait(scene_.platform, times_[k]) * tilt_;
  }
  // The odometry drifts along the path; the gait it follows (as an odometry with an IMU would).
  odom_ = drift_odometry(body, scene_.odometry, seed_);
  for (std::size_t k = 0; k < n; ++k) odom_[k] = odom_[k] * gait(scene_.platform, times_[k]) * tilt_;
}

Simulator::~Simulator() = default;

Pose3 Simulator::sensor_pose_at(double t) const {
  const double path_time = std::clamp(t * time_scale_, 0.0, trajectory_->duration());
  return trajectory_->body_pose(path_time) * gait(scene_.platform, t) * tilt_;
}

PointCloud Simulator::scan(std::size_t k) const {
  if (!scene_.platform.motion_distortion) {
    const scene::SensorSpec& s = scene_.sensor;
    std::vector<RayHit> hits;
    caster_->cast_scan(truth_.at(k), beams_, static_cast<float>(s.min_range), static_cast<float>(s.max_range),
                       &hits);
    add_people({truth_.at(k)}, times_.at(k), {}, &hits);
    return points_of(hits, k, {});
  }
  // Column c fires c / columns of a period after the stamp, from where the sensor is then.
  const scene::SensorSpec& s = scene_.sensor;
  const double period = 1.0 / s.rate_hz;
  std::vector<Pose3> poses(static_cast<std::size_t>(beams_.cols));
  std::vector<float> column_time(poses.size());
  for (int c = 0; c < beams_.cols; ++c) {
    column_time[c] = static_cast<float>(period * c / beams_.cols);
    poses[c] = c == 0 ? truth_.at(k) : sensor_pose_at(times_.at(k) + column_time[c]);
  }
  std::vector<RayHit> hits;
  caster_->cast_sweep(poses, beams_, static_cast<float>(s.min_range), static_cast<float>(s.max_range), &hits);
  add_people(poses, times_.at(k), column_time, &hits);
  return points_of(hits, k, column_time);
}

PointCloud Simulator::scan_at(const Pose3& sensor_pose, std::uint64_t noise_index) const {
  const scene::SensorSpec& s = scene_.sensor;
  std::vector<RayHit> hits;
  caster_->cast_scan(sensor_pose, beams_, static_cast<float>(s.min_range), static_cast<float>(s.max_range),
                     &hits);
  return points_of(hits, noise_index, {});
}

void Simulator::add_people(const std::vector<Pose3>& column_poses, double stamp,
                           const std::vector<float>& column_time, std::vector<RayHit>* hits) const {
  if (people_->empty()) return;
  const scene::SensorSpec& s = scene_.sensor;
  tbb::parallel_for(0, beams_.rows, [&](int r) {
    for (int c = 0; c < beams_.cols; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * beams_.cols + c;
      const Pose3& pose = column_poses.size() == 1 ? column_poses[0] : column_poses[c];
      const double t = stamp + (column_time.empty() ? 0.0 : column_time[c]);
      people_->occlude(pose.translation(), pose.linear() * beams_.dirs[i].cast<double>(), t,
                       static_cast<float>(s.min_range), static_cast<float>(s.max_range), &(*hits)[i]);
    }
  });
}

PointCloud Simulator::points_of(const std::vector<RayHit>& hits, std::uint64_t noise_index,
                                const std::vector<float>& column_time) const {
  const scene::SensorSpec& s = scene_.sensor;
  const bool timed = !column_time.empty();
  const std::uint64_t scan_key = splitmix(seed_ ^ splitmix(noise_index + 0x5CA11ULL));
  // Noise row by row in parallel; rows are joined in order, so threads change nothing.
  std::vector<PointCloud> rows(static_cast<std::size_t>(beams_.rows));
  tbb::parallel_for(0, beams_.rows, [&](int r) {
    PointCloud& row = rows[r];
    row.reserve(beams_.cols, true, true, timed);
    for (std::size_t i = static_cast<std::size_t>(r) * beams_.cols, end = i + beams_.cols; i < end; ++i) {
      const RayHit& h = hits[i];
      if (h.range < 0.0f) continue;
      const std::uint64_t r1 = splitmix(scan_key + 2 * i);
      const std::uint64_t r2 = splitmix(scan_key + 2 * i + 1);
      if (s.dropout > 0.0 && to_unit(splitmix(r1 ^ r2)) < s.dropout) continue;
      // Box-Muller from two independent uniforms.
      const double u1 = std::max(to_unit(r1), 1e-300);
      const double gauss = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * to_unit(r2));
      const double range = h.range + s.range_noise_std * gauss;
      if (range < s.min_range || range > s.max_range) continue;
      row.points.push_back(beams_.dirs[i] * static_cast<float>(range));
      row.intensity.push_back(Reflectivity::of(h.label) * h.cos_incidence);
      row.labels.push_back(h.label);
      if (timed) row.times.push_back(column_time[i % beams_.cols]);
    }
  });
  std::size_t total = 0;
  for (const PointCloud& row : rows) total += row.size();
  PointCloud cloud;
  cloud.reserve(total, true, true, timed);
  for (const PointCloud& row : rows) cloud.append(row);
  return cloud;
}

void write_sequence(const Simulator& sim, const std::string& out_dir,
                    const std::function<void(std::size_t, std::size_t)>& progress) {
  io::SequenceWriter writer(out_dir);
  const std::size_t n = sim.num_scans();
  for (std::size_t k = 0; k < n; ++k) {
    writer.write_scan(k, sim.scan(k));
    if (progress) progress(k + 1, n);
  }
  const scene::Scene& scene = sim.scene();
  io::SequenceInfo info;
  info.times = sim.times();
  info.odometry = sim.odometry_poses();
  info.groundtruth = sim.true_poses();
  info.lap_starts = sim.trajectory().lap_starts();
  for (double& t : info.lap_starts) t /= sim.time_scale();  // path time -> scan time
  info.has_rooms = !scene.rooms.empty();
  for (const scene::Room& r : scene.rooms) {
    const scene::Level& l = scene.levels[r.level];
    info.rooms.push_back({r.name, l.name, r.polygon, l.elevation});
  }
  info.scene_yaml = scene.source_text;
  // A scene's voxel maps travel with its sequence: copied into voxel_maps/, and the copy of
  // the scene names them there, so the folder can move (or the scene's folder go) and still run.
  if (!scene.voxel_maps.empty()) {
    scene::Scene copy = scene;
    for (std::size_t i = 0; i < copy.voxel_maps.size(); ++i) {
      const std::string inside = "voxel_maps/" + std::to_string(i) + "_" +
                                 std::filesystem::path(copy.voxel_maps[i].file).filename().string();
      info.attached_files.emplace_back(copy.voxel_maps[i].file, inside);
      copy.voxel_maps[i].file = inside;
    }
    info.scene_yaml = scene::scene_yaml(copy, "The scene " + scene.file +
                                                  " as simulated into this sequence, its voxel maps "
                                                  "copied into voxel_maps/ (written by tsgraphs simulate).");
  }
  writer.commit(info);
}

}  // namespace tsgraphs::sim
