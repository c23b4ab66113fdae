#pragma once
/// LiDAR ray casting against a labelled mesh with Embree 3 (16-ray packets, rows of the
/// scan in parallel with TBB).
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/sim/scene_mesh.hpp"

namespace tsgraphs::sim {

/// Unit beam directions in the sensor frame, row-major: rows are beams (top to bottom),
/// columns are firings (azimuth 0 = sensor x axis, counter-clockwise).
struct BeamPattern {
  int rows = 0;
  int cols = 0;
  std::vector<Eigen::Vector3f> dirs;

  static BeamPattern from_sensor(const scene::SensorSpec& sensor);
};

/// Result of one ray: range < 0 means no return within range.
struct RayHit {
  float range = -1.0f;
  std::uint32_t label = 0;     ///< PointLabel of the surface
  float cos_incidence = 0.0f;  ///< |cos| of the angle between ray and surface normal
};

class RayCaster {
 public:
  explicit RayCaster(const LabelledMesh& mesh);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Casts every beam from `sensor_pose`; hits closer than `min_range` or beyond
  /// `max_range` are lost. `out` gets rows * cols entries in the pattern's order.
  void cast_scan(const Pose3& sensor_pose, const BeamPattern& beams, float min_range, float max_range,
                 std::vector<RayHit>* out) const;

  /// The same with column c's rays leaving from column_poses[c] (one per column): a sensor
  /// that moves while it sweeps.
  void cast_sweep(const std::vector<Pose3>& column_poses, const BeamPattern& beams, float min_range,
                  float max_range, std::vector<RayHit>* out) const;

  /// One ray in the world frame (for probes and tests).
  RayHit cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float max_range) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tsgraphs::sim
