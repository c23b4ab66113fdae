#pragma once
/// The indoor LiDAR simulator: a scene in, a sequence of labelled scans with true and
/// drifting poses out. The platform (scene `platform:`) adds its gait to the path's motion; a
/// swept scan's columns are each fired from the pose of their time, and carry that time.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/sim/people.hpp"
#include "tsgraphs/sim/ray_caster.hpp"
#include "tsgraphs/scene/scene.hpp"
#include "tsgraphs/scene/trajectory.hpp"

namespace tsgraphs::sim {

/// Relative reflectivity of each surface class, for the simulated intensity
/// (intensity = reflectivity * |cos incidence|, in [0, 1]).
struct Reflectivity {
  static constexpr float kFloor = 0.35f;
  static constexpr float kRamp = 0.35f;
  static constexpr float kCeiling = 0.6f;
  static constexpr float kWall = 0.7f;
  static constexpr float kRailing = 0.25f;
  static constexpr float kBox = 0.5f;
  static constexpr float kPerson = 0.3f;  ///< clothing
  static float of(std::uint32_t label);
};

class Simulator {
 public:
  /// Builds the geometry (reading voxel maps) and plans the path. `seed` drives the range
  /// noise, the dropout and the odometry drift.
  Simulator(scene::Scene scene, std::uint64_t seed);
  ~Simulator();

  const scene::Scene& scene() const { return scene_; }
  const scene::Trajectory& trajectory() const { return *trajectory_; }
  const RayCaster& ray_caster() const { return *caster_; }
  std::size_t num_triangles() const { return num_triangles_; }

  /// One scan every 1 / record_hz (else rate_hz) seconds from t = 0 to the end of the path: the last scan is
  /// taken at the path's end, the motion running at the scene's speed times time_scale().
  std::size_t num_scans() const { return times_.size(); }
  const std::vector<double>& times() const { return times_; }
  /// Path time per scan time, within half a scan period over the path's duration of 1.
  double time_scale() const { return time_scale_; }
  /// True sensor poses (with mount height, tilt and the platform's gait), one per scan, at the
  /// scan's stamp (a swept scan's start).
  const std::vector<Pose3>& true_poses() const { return truth_; }
  /// Drifting odometry poses, one per scan; the first equals the truth.
  const std::vector<Pose3>& odometry_poses() const { return odom_; }

  /// Scan k in the sensor frame, with intensity and labels; the same for the same seed and k
  /// whatever the number of threads. Swept (platform.motion_distortion): each column in the
  /// sensor's frame at its own time, with per-point times from the scan's stamp. People
  /// (scene `people:`) stand where they are at each column's time.
  PointCloud scan(std::size_t k) const;
  /// The true sensor pose at time t (s, scan time), between and beyond the scans'.
  Pose3 sensor_pose_at(double t) const;
  /// The same for any sensor pose (noise drawn as for scan `noise_index`): the static scene,
  /// without people.
  PointCloud scan_at(const Pose3& sensor_pose, std::uint64_t noise_index) const;

 private:
  /// Noise, dropout and range limits applied to cast rays, as points in the frame they left
  /// from; `column_time` (empty or one per column) fills the points' times.
  PointCloud points_of(const std::vector<RayHit>& hits, std::uint64_t noise_index,
                       const std::vector<float>& column_time) const;
  /// Puts the people in front of what the rays hit: column c's rays leave from column_poses[c]
  /// (or all from column_poses[0]) at stamp + column_time[c] (or stamp).
  void add_people(const std::vector<Pose3>& column_poses, double stamp, const std::vector<float>& column_time,
                  std::vector<RayHit>* hits) const;
  scene::Scene scene_;
  std::uint64_t seed_;
  std::unique_ptr<scene::Trajectory> trajectory_;
  std::unique_ptr<RayCaster> caster_;
  std::unique_ptr<People> people_;
  BeamPattern beams_;
  std::size_t num_triangles_ = 0;
  std::vector<double> times_;
  double time_scale_ = 1.0;
  std::vector<Pose3> truth_;
  Pose3 tilt_ = Pose3::Identity();
  std::vector<Pose3> odom_;
};

/// Writes the sequence folder (docs/scene-format.md) of the whole run to `out_dir`, under a
/// temporary name renamed into place at the end. `progress(done, total)` after each scan.
void write_sequence(const Simulator& sim, const std::string& out_dir,
                    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace tsgraphs::sim
