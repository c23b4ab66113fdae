#pragma once
/// How scans that carry per-point times are de-skewed (deskew.hpp, sweep_registration.hpp).
#include "tsgraphs/core/config_fields.hpp"
#include "tsgraphs/odometry/sweep_registration.hpp"

namespace tsgraphs::odometry {

/// Where the motion during a sweep comes from.
enum class DeskewMotion {
  poses,         ///< the poses around the scan (or the LiDAR odometry's last motion)
  registration,  ///< each sweep registered to a map of the ones before, the motion among the unknowns
  automatic      ///< registration when scans lie farther apart than max_interval_ratio sweeps
};
inline const Choices<DeskewMotion> kDeskewMotions{{DeskewMotion::automatic, "auto"},
                                                  {DeskewMotion::poses, "poses"},
                                                  {DeskewMotion::registration, "registration"}};

struct DeskewConfig {
  bool enabled = true;
  DeskewMotion motion = DeskewMotion::automatic;
  /// Beyond this many sweeps' duration between scans the poses do not sample the motion inside
  /// a sweep (a 10 Hz sensor recorded at 2 Hz).
  double max_interval_ratio = 1.5;
  SweepRegistrationConfig registration;  ///< the sweep registration's fields

  template <class V>
  void visit(V& v) {
    v("enabled", enabled, "each point moved into the sensor's frame at the scan's stamp");
    v("motion", motion, kDeskewMotions,
      "poses: the motion from the poses around the scan (or the LiDAR odometry's last); registration: each "
      "sweep registered to a map of those before, its motion among the unknowns; auto: registration when "
      "scans are farther apart than max_interval_ratio sweeps");
    v("max_interval_ratio", max_interval_ratio, between(1.0, 1000.0),
      "beyond it the poses do not sample the motion inside a sweep (a 10 Hz sensor recorded at 2 Hz)");
    registration.visit(v);
  }
};

}  // namespace tsgraphs::odometry
