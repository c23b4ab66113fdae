#pragma once
/// LiDAR odometry from the scans alone: KISS-ICP-style (Vizzo et al., RA-L 2023) ICP of each
/// scan against a local voxel map, from a constant-velocity prediction, with a robust kernel
/// whose scale follows an adaptive threshold. Point-to-plane where the map's voxel is flat,
/// point-to-point where it is scattered: KISS-ICP's point-to-point alone is pulled towards
/// "no motion" by the scan's own rings on the floor, which move with the sensor (on the
/// simulated office it lost 1.2 m in the first 2 m of a corridor).
#include <cstddef>
#include <deque>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/odometry/adaptive_threshold.hpp"
#include "tsgraphs/odometry/sweep_registration.hpp"
#include "tsgraphs/odometry/voxel_hash_map.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::odometry {

/// What the constant-velocity prediction does with roll and pitch (it repeats the last turn
/// about z and the last step).
enum class TiltPrediction {
  hold,      ///< holds them: a carried sensor's tilt swings back at every step (repeating its
             ///< change doubles the error at 2 Hz)
  repeat,    ///< repeats their last change: at 10 Hz the sway goes on between scans
  automatic  ///< whichever predicted the last tilt_window scans' tilt better (hold until it knows)
};
inline const Choices<TiltPrediction> kTiltPredictions{
    {TiltPrediction::automatic, "auto"}, {TiltPrediction::hold, "hold"}, {TiltPrediction::repeat, "repeat"}};

struct LidarOdometryConfig {
  double min_range = 0.5;
  double max_range = 50.0;
  double voxel_size = 0.25;
  double map_voxel_factor = 0.5;
  double registration_voxel_factor = 1.5;
  int max_points_per_voxel = 20;
  bool point_to_plane = true;
  int plane_min_points = 4;
  double plane_min_spread_factor = 0.15;
  double plane_max_thickness_ratio = 0.3;
  double initial_threshold = 2.0;
  double min_threshold = 1.0;
  double fine_threshold = 0.5;
  TiltPrediction tilt_prediction = TiltPrediction::automatic;
  int tilt_window = 10;
  bool turn_from_sweep = true;
  bool sweep_motion = true;
  double min_motion = 0.1;
  double correspondence_factor = 3.0;
  double kernel_divisor = 3.0;
  int max_iterations = 50;
  double convergence_criterion = 1e-3;
  int min_correspondences = 50;
  double yaw_search_deg = 60.0;
  double yaw_search_step_deg = 5.0;
  int yaw_search_points = 1000;
  int yaw_search_candidates = 3;
  int yaw_search_candidate_iterations = 10;
  double yaw_search_margin = 0.1;
  double min_overlap = 0.3;
  double recovery_search_m = 1.5;
  double recovery_turn_step_deg = 10.0;
  double recovery_overlap_ratio = 0.7;
  int recovery_window = 20;
  int recovery_points = 250;
  int reduction_grain = 256;

  template <class V>
  void visit(V& v) {
    v("min_range", min_range, between(0.0, 10000.0),
      "m; nearer returns are dropped (the platform, its operator)");
    v("max_range", max_range, above(0.0, 10000.0),
      "m; farther returns are dropped; also the local map's radius");
    v.require(max_range > min_range, "max_range", "must be > min_range");
    v("voxel_size", voxel_size, between(0.01, 100.0), "m; edge of the local map's voxels");
    v("map_voxel_factor", map_voxel_factor, between(0.1, 10.0),
      "the scan added to the map is downsampled to voxel_size * this");
    v("registration_voxel_factor", registration_voxel_factor, between(0.1, 10.0),
      "the scan registered is downsampled to voxel_size * this (coarser: faster)");
    v("max_points_per_voxel", max_points_per_voxel, between(1, 1000), "local map points kept per voxel");
    v("point_to_plane", point_to_plane,
      "point-to-plane on flat voxels (false: KISS-ICP's point-to-point everywhere)");
    v("plane_min_points", plane_min_points, between(3, 1000), "a voxel with fewer points is not matched");
    v("plane_min_spread_factor", plane_min_spread_factor, above(0.0, 1.0),
      "a flat voxel spreads >= voxel_size * this (sd) both ways; less is a line (one ring)");
    v("plane_max_thickness_ratio", plane_max_thickness_ratio, above(0.0, 1.0),
      "a flat voxel is at most this thick (sd) for its width (sd)");
    v("initial_threshold", initial_threshold, above(0.0, 100.0),
      "m; correspondence threshold until the sensor has moved");
    v("min_threshold", min_threshold, between(0.0, 100.0),
      "m; the adaptive threshold never goes below this: at 2 Hz a carrier 1 m/s off the constant velocity is "
      "0.5 m off the prediction, within the kernel's reach (a third of it)");
    v("fine_threshold", fine_threshold, between(0.0, 100.0),
      "m; once converged, ICP goes on with this threshold when its own was wider (0: off): wrong pairs a "
      "wide start let in stop pulling");
    v("tilt_prediction", tilt_prediction, kTiltPredictions,
      "of roll and pitch the prediction holds (hold: a carried sensor's tilt swings back at every step, at 2 "
      "Hz repeating it doubles the error), repeats the last change (repeat: at 10 Hz the sway goes on), or "
      "does whichever predicted the last tilt_window scans better (auto)");
    v("tilt_window", tilt_window, between(1, 10000), "registered scans whose tilt errors auto compares");
    v("turn_from_sweep", turn_from_sweep,
      "with the scans' stamps and the tilt held, the prediction turns at the last sweep's turn rate until "
      "the next stamp (the turn now) rather than repeating the last turn (half an interval ago)");
    v("sweep_motion", sweep_motion,
      "a scan with per-point times is registered once more with the motion during its sweep (deskew's "
      "registration fields): its pose is the stamp's, the map takes it de-skewed");
    v("min_motion", min_motion, between(0.0, 100.0),
      "m; a scan teaches the threshold only if it moved this much (at max_range)");
    v("correspondence_factor", correspondence_factor, above(0.0, 100.0),
      "pairs farther than threshold * this are ignored");
    v("kernel_divisor", kernel_divisor, above(0.0, 1000.0), "Geman-McClure kernel scale = threshold / this");
    v("max_iterations", max_iterations, between(1, 1000),
      "Gauss-Newton iterations per scan at most (more: it oscillates)");
    v("convergence_criterion", convergence_criterion, above(0.0, 1.0),
      "stop when the update's norm (rad and m) falls below this");
    v("min_correspondences", min_correspondences, between(6, 1000000),
      "fewer pairs: keep the constant-velocity prediction");
    visit_search(v);
  }

  /// The fields of the searches for a start (a turn the prediction missed, a scan lost).
  template <class V>
  void visit_search(V& v) {
    v("yaw_search_deg", yaw_search_deg, between(0.0, 180.0),
      "the start of ICP is searched among turns up to this either side of the prediction and of standing "
      "still (0: off): a hand-held sensor at 2 Hz turns 45 deg between scans");
    v("yaw_search_step_deg", yaw_search_step_deg, between(0.5, 90.0),
      "turns tried this far apart (ICP closes the rest)");
    v("yaw_search_points", yaw_search_points, between(10, 1000000),
      "scan points scored per guess (the share in occupied map voxels)");
    v("yaw_search_candidates", yaw_search_candidates, between(1, 100),
      "when the search moves the start, ICP runs from its best turn, the prediction and the next best turns "
      "apart, this many in all, and goes on from the result that overlaps the map most (1: the best turn "
      "alone)");
    v("yaw_search_candidate_iterations", yaw_search_candidate_iterations, between(1, 1000),
      "ICP iterations each of those starts gets before one is chosen");
    v("yaw_search_margin", yaw_search_margin, between(0.0, 1.0),
      "a guess replaces the prediction when its share is this much larger (at 10 Hz the prediction stays)");
    v("min_overlap", min_overlap, between(0.0, 1.0),
      "a scan with a smaller share of its points in occupied map voxels is reported lost and not added to "
      "the map");
    v("recovery_search_m", recovery_search_m, between(0.0, 10.0),
      "m; a lost scan is registered again from the best-overlapping of turns (up to yaw_search_deg) and "
      "horizontal shifts this far (one voxel apart) of the prediction and the last pose (0: off)");
    v("recovery_turn_step_deg", recovery_turn_step_deg, between(0.5, 90.0),
      "the turns tried there are this far apart (ICP closes the rest)");
    v("recovery_overlap_ratio", recovery_overlap_ratio, between(0.0, 1.0),
      "a scan is searched again too when its overlap ends below this share of the recent scans' median (a "
      "wrong minimum; 0: off)");
    v("recovery_window", recovery_window, between(1, 10000), "scans whose overlaps make that median");
    v("recovery_points", recovery_points, between(10, 1000000),
      "scan points scored per guess there (a few thousand guesses)");
    v("reduction_grain", reduction_grain, between(1, 1000000),
      "points per block of the parallel sums (fixed: same sums whatever the threads)");
  }

  /// The map's surface fit from the plane_* fields.
  SurfaceConfig surface() const {
    return {plane_min_points, plane_min_spread_factor, plane_max_thickness_ratio};
  }
};

/// Outcome of one ICP run (for diagnostics and tests).
struct IcpResult {
  Pose3 pose = Pose3::Identity();  ///< sensor pose in the map frame
  int iterations = 0;
  std::size_t num_correspondences = 0;  ///< in the last iteration
  std::size_t num_source = 0;           ///< points registered
  bool converged = false;               ///< the update fell below convergence_criterion
  double turn_searched_deg = 0.0;  ///< the turn from the prediction that the yaw search chose as the start
  double overlap = 1.0;    ///< share of the points in occupied map voxels at the result (voxel_overlap)
  bool lost = false;       ///< overlap below min_overlap: reported, see LidarOdometry
  bool recovered = false;  ///< registered again from recovery_search_m's search
};

/// Indices of the first point of each voxel of edge `voxel_size`, in input order. Measured
/// points rather than centroids: centroids of sensor-frame voxels sit on a lattice that moves
/// with the sensor, which pulls point-to-point ICP towards "no motion" (on the simulated
/// office, centroids lost track in the corridor where first points did not).
std::vector<std::size_t> first_per_voxel(const std::vector<Eigen::Vector3d>& points, double voxel_size);

/// Indices of the finite points of `cloud` whose range is in [min_range, max_range].
std::vector<std::size_t> in_range(const PointCloud& cloud, double min_range, double max_range);

/// The share of `source` (sensor frame) placed at `pose` whose map voxel holds points, over
/// every `stride`-th point: how well a guess overlaps the map, for a fraction of ICP's cost.
double voxel_overlap(const std::vector<Eigen::Vector3d>& source, const VoxelHashMap& map, const Pose3& pose,
                     std::size_t stride = 1);

/// ICP of `source` (sensor frame) against `map` from `initial_guess`, Gauss-Newton on SE(3) with
/// a Geman-McClure kernel of scale `kernel_scale`, pairs farther than
/// `max_correspondence_distance` ignored; point-to-plane on flat voxels, point-to-point on
/// scattered ones and no pair on unknown ones when `config.point_to_plane`, else point-to-point
/// everywhere. Deterministic for the same inputs and config.
IcpResult align_to_map(const std::vector<Eigen::Vector3d>& source, const VoxelHashMap& map,
                       const Pose3& initial_guess, double max_correspondence_distance, double kernel_scale,
                       const LidarOdometryConfig& config);

class LidarOdometry {
 public:
  /// std::invalid_argument for a config out of range (check_config).
  /// `first_pose`: the first scan's pose in the odometry frame. The frame's z is taken as up
  /// (the yaw search turns about it, the prediction holds the tilt against it), so a caller that
  /// knows the gravity (floor_levelling.hpp, a level mount) passes a pose that levels the map.
  /// `sweep`: the sweep registration's settings (sweep_motion).
  explicit LidarOdometry(LidarOdometryConfig config = {}, const Pose3& first_pose = Pose3::Identity(),
                         SweepRegistrationConfig sweep = {});

  /// Registers the next scan (sensor frame) and returns its sensor pose in the odometry frame
  /// (the first pose is first_pose). A scan with no usable point keeps the prediction and
  /// leaves the map as it is.
  Pose3 register_scan(const PointCloud& scan);
  /// As above, with the scan's stamp (s): the prediction may then use the last sweep's turn
  /// rate (turn_from_sweep), and a swept scan's registration starts from the last interval's
  /// velocity.
  Pose3 register_scan(const PointCloud& scan, double stamp);

  /// The last motion between two registered scans (the constant-velocity model's), in the
  /// earlier scan's frame; the identity before the second scan.
  Pose3 last_motion() const;
  /// The prediction of the next pose from the last two: constant velocity, the tilt held or
  /// repeated as tilt_prediction says (the first pose before any scan, the last pose after one).
  /// `seconds` after the last scan's stamp, the turn about z is the last sweep's turn rate's
  /// when it has one (turn_from_sweep); NaN: the last turn repeated.
  Pose3 predict(double seconds = std::numeric_limits<double>::quiet_NaN()) const;
  /// Whether predict() repeats the change of tilt now (tilt_prediction; "auto" learns it).
  bool repeats_tilt() const;
  /// One pose per registered scan.
  const std::vector<Pose3>& poses() const { return poses_; }
  const VoxelHashMap& local_map() const { return map_; }
  /// The correspondence threshold the next scan will use (m).
  double threshold() const;
  /// ICP details of the last scan (iterations 0 when it was not registered).
  const IcpResult& last_icp() const { return last_icp_; }
  /// The last scan's sweep registration (registered false when it had none: sweep_motion).
  const SweepMotion& last_sweep() const { return last_sweep_; }
  /// Indices (in registration order) of the scans reported lost: too few of their points matched
  /// the map (a degenerate scan, a turn beyond the search). Their pose is kept as registered,
  /// but the map does not take their points, so a wrong pose is not built into it.
  const std::vector<std::size_t>& lost_scans() const { return lost_; }
  const LidarOdometryConfig& config() const { return config_; }

 private:
  struct Start {
    Pose3 pose;
    double turn_deg;  ///< the turn the yaw search gave it (0: the prediction)
  };
  /// The starts for ICP: the prediction alone, or, when a turn of it or of the last pose
  /// (standing still) overlaps the map clearly better (yaw_search_*), that turn, the prediction
  /// and the next best turns apart from it, yaw_search_candidates in all.
  std::vector<Start> initial_guesses(const std::vector<Eigen::Vector3d>& source,
                                     const Pose3& prediction) const;
  /// Of initial_guesses, the start whose result after yaw_search_candidate_iterations of ICP
  /// overlaps the map most, and that result (the pose full ICP goes on from).
  std::pair<Start, Pose3> choose_start(const std::vector<Eigen::Vector3d>& source, const Pose3& prediction,
                                       double sigma) const;
  /// The median overlap of the last recovery_window registered scans (0 before any).
  double usual_overlap() const;
  /// ICP from `start` with threshold `sigma`, then with fine_threshold's; the overlap at the end.
  IcpResult register_from(const std::vector<Eigen::Vector3d>& source, const Pose3& start, double sigma) const;
  /// The start that overlaps the map best among turns and shifts (recovery_search_m).
  Pose3 recovery_start(const std::vector<Eigen::Vector3d>& source, const Pose3& prediction) const;
  /// register_scan's registration against a map that has points: ICP (register_rigid), then
  /// the sweep's motion when `swept`; sets last_icp_ and last_sweep_, updates the threshold.
  Pose3 register_to_map(const std::vector<Eigen::Vector3d>& source, const std::vector<double>& source_times,
                        const Pose3& prediction, double last_interval, bool swept);
  /// The chosen start's ICP, retried from recovery_start when its overlap is suspect; sets
  /// last_icp_, records its overlap and returns the start it came from.
  Pose3 register_rigid(const std::vector<Eigen::Vector3d>& source, const Pose3& prediction, double sigma);
  /// The sweep registration's prior at `pose`: the last interval's velocity.
  SweepMotion sweep_prior(const Pose3& pose, double last_interval) const;
  /// Moves `frame` to the world at `pose` (de-skewed by last_sweep_ when `deskew`) into the map.
  void add_to_map(std::vector<Eigen::Vector3d>& frame, const std::vector<double>& frame_times,
                  const Pose3& pose, bool deskew);
  /// predict() with the tilt held or repeated.
  Pose3 predict_with(bool repeat_tilt, double seconds) const;
  /// Records how far each of the two tilt predictions was from `pose`, the next registered pose.
  void score_tilt_predictions(const Pose3& pose);
  /// Every how many source points voxel_overlap looks at (yaw_search_points of them).
  std::size_t overlap_stride(const std::vector<Eigen::Vector3d>& source) const;

  LidarOdometryConfig config_;
  SweepRegistrationConfig sweep_;
  Pose3 first_pose_;
  VoxelHashMap map_;
  AdaptiveThreshold threshold_;
  std::vector<Pose3> poses_;
  IcpResult last_icp_;
  SweepMotion last_sweep_;
  std::vector<std::size_t> lost_;
  std::deque<double> recent_overlaps_;
  double last_stamp_ = std::numeric_limits<double>::quiet_NaN();     ///< the last registered scan's stamp (s)
  double last_interval_ = std::numeric_limits<double>::quiet_NaN();  ///< between the last two stamps (s)
  std::deque<std::pair<double, double>>
      tilt_errors_;  ///< (held, repeated) tilt error of the last scans (rad)
};

}  // namespace tsgraphs::odometry
