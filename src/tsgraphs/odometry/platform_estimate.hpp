#pragma once
/// The sensor on its platform, measured from scans rather than asked of the user: its height
/// above the floor and its tilt, and its beam layout (how many rings, how far apart, the lowest
/// one), which decide where the ground search can start and how sparse the floor's rings are.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/odometry/floor_levelling.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::odometry {

struct PlatformEstimateConfig {
  int scans = 30;
  double floor_bin = 0.02;
  double ring_gap_deg = 0.2;
  double ring_min_range =
      1.0;  ///< returns nearer than this are not used for rings (m): a beam's offset from the
            ///< sensor's axis (about 1.5 cm) bends a nearer return's elevation by more than
            ///< ring_gap_deg; farther, the floor's nearest rings of a low sensor still count
  int ring_min_points = 10;

  template <class V>
  void visit(V& v) {
    v("scans", scans, between(1, 1000),
      "scans measured, spread evenly over the run (a median: a hand-held sensor bobs and tilts within a "
      "sweep, a room may show little floor)");
    v("floor_bin", floor_bin, between(0.001, 1.0),
      "m; height bins of each scan's lowest returns: the fullest is the floor");
    v("ring_gap_deg", ring_gap_deg, above(0.0, 10.0),
      "returns whose elevations are this close belong to one ring");
    v("ring_min_range", ring_min_range, between(0.0, 1000.0),
      "m; nearer returns are not used for rings (a beam's offset bends their elevation)");
    v("ring_min_points", ring_min_points, between(1, 1000000), "a ring holds at least this many returns");
  }
};

/// The rings of a spinning LiDAR: the elevations of its beams as seen in a scan's returns.
struct BeamLayout {
  int rings = 0;             ///< rings found (0: no layout, e.g. an empty scan)
  double lowest_deg = 0.0;   ///< elevation of the lowest ring (sensor frame, negative below the horizon)
  double highest_deg = 0.0;  ///< ...and of the highest
  double spacing_deg = 0.0;  ///< the median angle between neighbouring rings
};

/// The rings of `scan` (sensor frame): its returns beyond ring_min_range grouped by elevation.
/// Rings that returned nothing (beams into the sky, into a window) are not counted.
BeamLayout measure_beam_layout(const PointCloud& scan, const PlatformEstimateConfig& config = {});

/// The floor under one scan.
struct FloorHeight {
  bool found = false;
  double height = 0.0;        ///< the sensor above the floor, along the floor's normal (m)
  double tilt_deg = 0.0;      ///< the angle between the sensor's z and the floor's normal
  std::size_t num_cells = 0;  ///< grid cells whose lowest return lies on it
};

/// The floor under `scan` given `up`, the gravity's up in the sensor frame: the height at
/// which most grid cells (levelling.cell_size) have their lowest return, below
/// levelling.min_depth and within [levelling.min_range, levelling.max_range], then the mean of
/// those returns; with `fit_tilt` (an `up` only roughly known) the plane through them, refitted,
/// gives the up. At least levelling.min_cells cells, or not found. A room's floor holds more
/// cells than any other level a sensor sees below it (a desk top, a storey through a void), and
/// the lowest returns of walls, spread over heights, make no such level; a plane fitted to all
/// lowest returns (floor_levelling.hpp) leans towards them where little floor is seen.
FloorHeight floor_height(const PointCloud& scan, const Eigen::Vector3d& up, bool fit_tilt,
                         const FloorLevellingConfig& levelling = {},
                         const PlatformEstimateConfig& config = {});

/// What the scans say about the platform.
struct PlatformEstimate {
  std::size_t scans_measured = 0;  ///< scans looked at
  std::size_t floors_found = 0;    ///< ...with a floor under the sensor
  bool height_found = false;       ///< at least one floor was found
  double height = 0.0;             ///< median height of the sensor above the floor (m)
  double height_spread = 0.0;      ///< max - min of the per-scan heights (m)
  double tilt_deg = 0.0;           ///< median angle between the sensor's z and the floor's normal
  BeamLayout beams;                ///< from the scan with the most rings
};

/// Measures the platform from `scans` (sensor frames; at most config.scans of them are used).
/// `ups` (empty, or one per scan): the gravity's up in each scan's frame when the poses give it;
/// otherwise each scan's own floor levelling (floor_levelling.hpp) gives it. The height and
/// tilt are the medians over the scans with a floor. Deterministic.
PlatformEstimate estimate_platform(const std::vector<PointCloud>& scans,
                                   const FloorLevellingConfig& levelling = {},
                                   const PlatformEstimateConfig& config = {},
                                   const std::vector<Eigen::Vector3d>& ups = {});

}  // namespace tsgraphs::odometry
