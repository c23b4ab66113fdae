#pragma once
/// The adaptive correspondence threshold of KISS-ICP (Vizzo et al., RA-L 2023): how far a scan
/// point may be from its map neighbour to count, learnt from how wrong the constant-velocity
/// prediction has been so far, so that no fixed gate has to be tuned per sensor and platform.
#include <cstddef>

#include "tsgraphs/core/pose.hpp"

namespace tsgraphs::odometry {

/// Displacement (m) that pose change `delta` causes at worst to a point at `max_range`: the
/// chord its rotation sweeps plus the translation.
double pose_displacement(const Pose3& delta, double max_range);

class AdaptiveThreshold {
 public:
  /// `initial_threshold` (m) is used until a scan moved by at least `min_motion` (m, as
  /// pose_displacement); `max_range` (m) converts rotations to displacements. Bad values
  /// (non-positive threshold or range, negative min_motion) are std::invalid_argument.
  AdaptiveThreshold(double initial_threshold, double min_motion, double max_range);

  /// Records how far the registered pose was from the prediction (`model_deviation` =
  /// prediction^-1 * registered) when the scan's own motion (`motion` = previous^-1 * current)
  /// was large enough: standing still says nothing about the prediction's error. `range` (m,
  /// > 0) converts the deviation's rotation where the scan's points are (their median range);
  /// 0: at max_range, KISS-ICP's bound. Indoors the points are a few metres away, and a
  /// hand-held sensor's sway of a few degrees taken at 50 m made the threshold 5-9 m.
  void update(const Pose3& model_deviation, const Pose3& motion, double range = 0.0);
  /// The current threshold (m): the root mean square of the recorded deviations, or the
  /// initial value before any was recorded.
  double threshold() const;
  std::size_t num_samples() const { return num_samples_; }

 private:
  double initial_threshold_;
  double min_motion_;
  double max_range_;
  double sum_sq_ = 0.0;
  std::size_t num_samples_ = 0;
};

}  // namespace tsgraphs::odometry
