#pragma once
/// A point cloud with optional per-point intensity, class label and time.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace tsgraphs {

/// Point classes shared by the simulator, the sequence folder and ground-truth scoring.
enum class PointLabel : std::uint32_t {
  kUnlabelled = 0,
  kFloor = 1,
  kRamp = 2,
  kCeiling = 3,
  kWall = 4,
  kRailing = 5,
  kBox = 6,
  kPerson = 7,  ///< someone walking through (scene `people:`)
};

struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<float> intensity;       ///< empty or one per point
  std::vector<std::uint32_t> labels;  ///< empty or one per point (PointLabel values)
  /// Empty or one per point: when it was measured, seconds after the scan's stamp (a spinning
  /// sensor sweeps its scan over its period while it moves; negative: before the stamp).
  std::vector<float> times;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_intensity() const { return !intensity.empty(); }
  bool has_labels() const { return !labels.empty(); }
  bool has_times() const { return !times.empty(); }
  /// Whether any point is finite: an empty or all-NaN scan is skipped with a warning (and is no
  /// keyframe), whether or not it is prefiltered.
  bool has_finite_point() const {
    return std::any_of(points.begin(), points.end(), [](const Eigen::Vector3f& p) { return p.allFinite(); });
  }
  void reserve(std::size_t n, bool with_intensity, bool with_labels, bool with_times = false) {
    points.reserve(n);
    if (with_intensity) intensity.reserve(n);
    if (with_labels) labels.reserve(n);
    if (with_times) times.reserve(n);
  }
  /// Appends every point of `other`; both must carry the same optional channels.
  void append(const PointCloud& other) {
    points.insert(points.end(), other.points.begin(), other.points.end());
    intensity.insert(intensity.end(), other.intensity.begin(), other.intensity.end());
    labels.insert(labels.end(), other.labels.begin(), other.labels.end());
    times.insert(times.end(), other.times.begin(), other.times.end());
  }
};

}  // namespace tsgraphs
