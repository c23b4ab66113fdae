#pragma once
/// The traversable ground of one scan (DESIGN.md step 4): the tri-grid field
/// (tri_grid_ground.hpp), the breadth-first traversable search from the robot
/// (traversable_search.hpp), BGK smoothing (bgk_smoothing.hpp) and the point labels. This
/// header is the facade the pipeline calls; each step has its own file.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::ground {

/// Label of each input point.
enum class GroundLabel : std::uint8_t {
  kOther = 0,   ///< not classified: out of range, no ground under it, below the ground, or above th_obstacle
  kGround = 1,  ///< on traversable ground
  kObstacle = 2,  ///< above traversable ground by more than the ground band and at most th_obstacle, or the
                  ///< foot of such an obstacle
};

/// Every parameter of the ground layer (TRAVEL's names where they exist). Defaults are for
/// an indoor 64-beam sensor on a ground robot; see per_sensor_preset().
struct GroundConfig {
  double sensor_height = 0.55;  ///< height of the sensor above the floor under the robot (m); the pipeline
                                ///< sets it from the platform (pipeline/platform.hpp)
  double resolution = 0.5;
  double min_range = 0.5;
  double max_range = 15.0;
  int num_iter = 3;
  int num_lpr = 5;
  int num_min_pts = 10;
  int sparse_min_pts = 1;
  double th_seeds = 0.5;
  double th_dist = 0.06;
  double th_outlier = 0.3;
  double fit_column = 0.02;
  double plane_prior_spread = 0.02;
  double th_normal = 0.94;
  double th_lcc_normal = 0.12;
  double th_lcc_planar = 0.2;
  double th_obstacle = 2.0;
  double foot_radius = 0.02;
  double foot_height = 0.3;
  double foot_rings = 2.0;
  double seed_radius = 3.0;  ///< the search starts at ground-like nodes within this of the robot (m; the
                             ///< pipeline sets it from the platform)...
  double seed_height_tolerance = 0.2;
  double seed_max_slope = 0.21;
  double max_gap = 2.0;
  double ring_spacing_deg =
      45.0 / 63.0;  ///< angle between neighbouring beams (deg; the pipeline sets it from the platform): far
                    ///< floor rings are this far apart in elevation
  double bgk_length_scale = 1.0;
  double bgk_prior = 0.5;
  double th_traversable = 0.4;
  double bgk_max_height_gap = 0.25;

  /// Every field but sensor_height and seed_radius, which belong to the platform (the
  /// pipeline's `platform` section measures or takes them).
  template <class V>
  void visit(V& v) {
    v("resolution", resolution, between(0.05, 10.0),
      "m; tri-grid cell, split into 4 triangles by its diagonals");
    v("min_range", min_range, between(0.0, 1000.0), "m; nearer points are not used");
    v("max_range", max_range, above(0.0, 1000.0),
      "m; nor farther ones (ground precision / recall are scored over this range)");
    v.require(max_range > min_range, "max_range", "must be > min_range");
    v("num_iter", num_iter, between(1, 100), "PCA rounds per node");
    v("num_lpr", num_lpr, between(1, 10000), "points averaged for the lowest-point representative");
    v("num_min_pts", num_min_pts, between(3, 1000000), "fewer points: the node is unknown");
    v("sparse_min_pts", sparse_min_pts, between(1, 1000000),
      "a node not joined by its plane joins the ground reaching it with this many points at that ground's "
      "level, none below (far rings)");
    v("th_seeds", th_seeds, between(0.0, 100.0),
      "m; seeds lie within this above the lowest-point representative");
    v("th_dist", th_dist, above(0.0, 10.0),
      "m; plane inliers and ground points lie within this of the node plane");
    v("th_outlier", th_outlier, between(0.0, 100.0),
      "m; points this far below the node's robust lowest level are rejected");
    v("fit_column", fit_column, between(0.001, 10.0),
      "m; planes are fitted to the lowest point of each column this wide (a wall adds only its foot)");
    v("plane_prior_spread", plane_prior_spread, between(0.0, 10.0),
      "m; horizontal spread added to each node's PCA (points on one scan ring get the flattest plane)");
    v("th_normal", th_normal, between(0.0, 1.0), "ground-like: normal z at least this");
    v("th_lcc_normal", th_lcc_normal, between(0.0, 2.0),
      "local convexity/concavity, normal term (TRAVEL's 0.03 is for 2 m cells)");
    v("th_lcc_planar", th_lcc_planar, between(0.0, 3.2),
      "rad; local convexity/concavity, plane distance term");
    v("th_obstacle", th_obstacle, above(0.0, 100.0),
      "m; obstacle points lie at most this above the local ground");
    v("foot_radius", foot_radius, between(0.0, 10.0),
      "m; a ground-band point with obstacle points this near (horizontally)...");
    v("foot_height", foot_height, between(0.0, 100.0),
      "m; ...and up to this above the band is a wall's or a box's foot: an obstacle");
    v("foot_rings", foot_rings, between(0.0, 1000.0),
      "...or as high as this many rings above it reach on a wall at its range (far rings are farther apart)");
    v("seed_height_tolerance", seed_height_tolerance, above(0.0, 100.0),
      "m; the search starts at ground-like nodes within platform.seed_radius whose plane passes this near "
      "the floor under the robot");
    v("seed_max_slope", seed_max_slope, above(0.0, 100.0),
      "rise per m; ...whose plane is no steeper, nor its height farther from that floor than the tolerance "
      "plus this per metre (a robot's steepest ramp, 12 deg)");
    v("max_gap", max_gap, between(0.0, 100.0),
      "m; the search links nodes across empty or unknown nodes up to this far (far rings are sparse)");
    v("bgk_length_scale", bgk_length_scale, above(0.0, 100.0), "m; support of BGK's sparse kernel");
    v("bgk_prior", bgk_prior, between(0.0, 1e6),
      "BGK prior weight (pseudo-observations at traversability 0.5)");
    v("th_traversable", th_traversable, between(0.0, 1.0),
      "a node is traversable when its smoothed probability is at least this...");
    v("bgk_max_height_gap", bgk_max_height_gap, above(0.0, 100.0),
      "m; ...and its own height is within this of the smoothed surface");
  }
};

/// Defaults adjusted for a sensor preset name ("os1-64", "os0-128", "vlp-16", "hesai-xt32");
/// unknown names get the defaults.
GroundConfig per_sensor_preset(const std::string& preset);
/// The fields per_sensor_preset() sets (the ones that follow the floor rings' density), copied
/// from `from` to `to` unless `keep(name)` says the caller gave that field itself.
template <class Keep>
void copy_ring_density_fields(const GroundConfig& from, GroundConfig* to, Keep keep) {
  if (!keep("num_min_pts")) to->num_min_pts = from.num_min_pts;
  if (!keep("max_gap")) to->max_gap = from.max_gap;
  to->ring_spacing_deg = from.ring_spacing_deg;  // the sensor's, not a setting
}
/// The preset whose beams are nearest `spacing_deg` apart (nearest by ratio): "vlp-16" (2 deg),
/// "hesai-xt32" (1 deg), "os1-64" (0.7 deg, as the os0-128's); "" when spacing_deg <= 0. The
/// ground's presets differ only in how sparse the floor's rings are, which the spacing decides.
std::string preset_for_ring_spacing(double spacing_deg);

/// One node of the tri-grid field after search and smoothing, in the level frame: origin at
/// the sensor, z up (gravity), x along the sensor's heading.
struct GroundNode {
  /// Traversable nodes: the mean (x, y) of the node's ground points, at the ground plane's
  /// height there (a node cut by a wall or a railing has its ground on one side). Others: the
  /// triangle's centroid at the node plane's height (or its lowest level when unmodelled).
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< smoothed plane normal (z up)
  float probability = 0.0f;                           ///< smoothed traversability in [0, 1]
  int num_points = 0;
  bool ground_like = false;  ///< the plane test alone
  bool reached = false;      ///< reached by the search from the robot
  bool traversable = false;  ///< the final decision: smoothed probability, height and link to the robot
                             ///< (bgk_smoothing.hpp), with ground points
};

/// The result for one scan.
struct GroundScan {
  Eigen::Matrix3d R_level_sensor =
      Eigen::Matrix3d::Identity();  ///< rotates sensor-frame vectors into the level frame
  std::vector<GroundNode> nodes;    ///< every node with points (unknown ones too)
  std::vector<GroundLabel> labels;  ///< one per input point
};

/// Segments `cloud` (sensor frame, NaN points allowed: labelled kOther). `R_map_sensor` is
/// the sensor's orientation; only its roll and pitch are used, to find the gravity direction.
/// Deterministic. Thread-safe: each thread reuses its own working buffers from call to call.
GroundScan segment_ground(const PointCloud& cloud, const Eigen::Matrix3d& R_map_sensor,
                          const GroundConfig& config);

}  // namespace tsgraphs::ground
