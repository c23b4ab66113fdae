#include "tsgraphs/odometry/lidar_odometry.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tsl/robin_set.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "tsgraphs/core/voxel_grid.hpp"
#include "tsgraphs/odometry/se3.hpp"

namespace tsgraphs::odometry {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
constexpr double kDegToRad = M_PI / 180.0;

template <class Config>
const Config& validated(const Config& c) {
  check_config(c, "LidarOdometryConfig");
  return c;
}

/// Normal equations of one Gauss-Newton step, summed over correspondences.
struct NormalEquations {
  Matrix6d JtJ = Matrix6d::Zero();
  Vector6d Jtr = Vector6d::Zero();
  std::size_t count = 0;

  void join(const NormalEquations& o) {
    JtJ += o.JtJ;
    Jtr += o.Jtr;
    count += o.count;
  }
};

}  // namespace

std::vector<std::size_t> first_per_voxel(const std::vector<Eigen::Vector3d>& points, double voxel_size) {
  const double inv = 1.0 / voxel_size;
  tsl::robin_set<std::uint64_t, KeyHash> seen;
  seen.reserve(points.size());
  std::vector<std::size_t> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (seen.insert(voxel_key(points[i].cast<float>(), inv)).second) out.push_back(i);
  }
  return out;
}

namespace {

/// The in-range points of `cloud`, one per voxel of `voxel_size`, with their times (empty when
/// the cloud has none).
void first_points_in_range(const PointCloud& cloud, double min_range, double max_range, double voxel_size,
                           std::vector<Eigen::Vector3d>& points, std::vector<double>& times) {
  std::vector<Eigen::Vector3d> all;
  std::vector<std::size_t> index;
  for (const std::size_t i : in_range(cloud, min_range, max_range)) {
    all.push_back(cloud.points[i].cast<double>());
    index.push_back(i);
  }
  points.clear();
  times.clear();
  for (const std::size_t j : first_per_voxel(all, voxel_size)) {
    points.push_back(all[j]);
    if (cloud.has_times()) times.push_back(cloud.times[index[j]]);
  }
}

/// The first of each voxel of `voxel_size` among `points`, with its time when there are times.
void thin(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& times, double voxel_size,
          std::vector<Eigen::Vector3d>& kept, std::vector<double>& kept_times) {
  kept.clear();
  kept_times.clear();
  for (const std::size_t j : first_per_voxel(points, voxel_size)) {
    kept.push_back(points[j]);
    if (!times.empty()) kept_times.push_back(times[j]);
  }
}

/// The median of `values` (0 when empty).
double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

/// The median distance of `points` from the sensor (0 when there are none).
double median_range(const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> r;
  r.reserve(points.size());
  for (const Eigen::Vector3d& p : points) r.push_back(p.norm());
  return median(std::move(r));
}

/// Whether the times are all finite and span a sweep (a scan taken at one instant has nothing
/// to de-skew).
bool spans_time(const std::vector<double>& times) {
  if (times.empty() || !std::all_of(times.begin(), times.end(), [](double t) { return std::isfinite(t); }))
    return false;
  const auto [lo, hi] = std::minmax_element(times.begin(), times.end());
  return *hi > *lo;
}

}  // namespace

std::vector<std::size_t> in_range(const PointCloud& cloud, double min_range, double max_range) {
  std::vector<std::size_t> out;
  out.reserve(cloud.size());
  const double min_sq = min_range * min_range, max_sq = max_range * max_range;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    if (!p.allFinite()) continue;
    const double r_sq = p.squaredNorm();
    if (r_sq >= min_sq && r_sq <= max_sq) out.push_back(i);
  }
  return out;
}

IcpResult align_to_map(const std::vector<Eigen::Vector3d>& source, const VoxelHashMap& map,
                       const Pose3& initial_guess, double max_correspondence_distance, double kernel_scale,
                       const LidarOdometryConfig& config) {
  IcpResult result;
  result.pose = initial_guess;
  if (source.empty() || map.empty()) return result;
  const double kernel_sq = kernel_scale * kernel_scale;
  // Geman-McClure: the weight falls as 1 / e^4 far beyond the kernel scale, so the pairs of
  // moved objects and wrong neighbours barely pull.
  const auto weight = [kernel_sq](double e_sq) {
    const double denom = kernel_sq + e_sq;
    return kernel_sq * kernel_sq / (denom * denom);
  };
  const std::size_t grain = static_cast<std::size_t>(config.reduction_grain);

  Pose3 T = initial_guess;
  for (int iteration = 1; iteration <= config.max_iterations; ++iteration) {
    // parallel_deterministic_reduce splits the range the same way every time and joins the
    // blocks in a fixed tree, so the floating-point sums (and the poses) do not depend on the
    // number of threads or on scheduling.
    const NormalEquations eq = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, source.size(), grain), NormalEquations{},
        [&](const tbb::blocked_range<std::size_t>& range, NormalEquations acc) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Eigen::Vector3d p = T * source[i];
            const Neighbour nb = map.nearest(p);
            if (!nb.found || nb.distance > max_correspondence_distance) continue;
            const Eigen::Vector3d r = p - nb.point;
            if (config.point_to_plane && nb.surface == Surface::planar) {
              // Residual e(xi) = n . (exp(xi) * p - q): d e / d xi = [n, p x n] at xi = 0.
              const double e = nb.normal.dot(r);
              Vector6d J;
              J.head<3>() = nb.normal;
              J.tail<3>() = p.cross(nb.normal);
              const double w = weight(e * e);
              acc.JtJ.noalias() += w * J * J.transpose();
              acc.Jtr.noalias() += w * e * J;
            } else if (!config.point_to_plane || nb.surface == Surface::scattered) {
              // Residual r(xi) = exp(xi) * p - q: d r / d xi = [I, -[p]x] at xi = 0.
              Eigen::Matrix<double, 3, 6> J;
              J.leftCols<3>().setIdentity();
              J.rightCols<3>() = -skew(p);
              const double w = weight(r.squaredNorm());
              acc.JtJ.noalias() += w * J.transpose() * J;
              acc.Jtr.noalias() += w * J.transpose() * r;
            } else {
              continue;  // a line or too few points: no direction to trust
            }
            ++acc.count;
          }
          return acc;
        },
        [](NormalEquations a, const NormalEquations& b) {
          a.join(b);
          return a;
        });
    result.iterations = iteration;
    result.num_correspondences = eq.count;
    if (eq.count < static_cast<std::size_t>(config.min_correspondences)) {
      result.pose = initial_guess;  // too little overlap to trust any update
      result.converged = false;
      return result;
    }
    const Vector6d dx = eq.JtJ.ldlt().solve(-eq.Jtr);
    if (!dx.allFinite()) break;
    T = se3_exp(dx) * T;
    if (dx.norm() < config.convergence_criterion) {
      result.converged = true;
      break;
    }
  }
  // Keep the rotation orthonormal after many small updates.
  T.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  result.pose = T;
  return result;
}

LidarOdometry::LidarOdometry(LidarOdometryConfig config, const Pose3& first_pose,
                             SweepRegistrationConfig sweep)
    : config_(validated(config)),
      sweep_(validated(sweep)),
      first_pose_(first_pose),
      map_(config_.voxel_size, static_cast<std::size_t>(config_.max_points_per_voxel), config_.surface()),
      threshold_(config_.initial_threshold, config_.min_motion, config_.max_range) {}

double LidarOdometry::threshold() const { return std::max(threshold_.threshold(), config_.min_threshold); }

Pose3 LidarOdometry::last_motion() const {
  if (poses_.size() < 2) return Pose3::Identity();
  return poses_[poses_.size() - 2].inverse() * poses_.back();
}

Pose3 LidarOdometry::predict(double seconds) const { return predict_with(repeats_tilt(), seconds); }

bool LidarOdometry::repeats_tilt() const {
  if (config_.tilt_prediction != TiltPrediction::automatic)
    return config_.tilt_prediction == TiltPrediction::repeat;
  if (tilt_errors_.size() < static_cast<std::size_t>(config_.tilt_window)) return false;
  double held = 0.0, repeated = 0.0;
  for (const auto& [h, r] : tilt_errors_) {
    held += h;
    repeated += r;
  }
  return repeated < held;
}

Pose3 LidarOdometry::predict_with(bool repeat_tilt, double seconds) const {
  if (poses_.empty()) return first_pose_;
  if (poses_.size() == 1) return poses_.back();
  const Pose3& last = poses_.back();
  const Pose3& before = poses_[poses_.size() - 2];
  if (repeat_tilt) return last * (before.inverse() * last);  // repeat the last motion
  // The last turn in the map's frame, reduced to its twist about z (swing-twist decomposition);
  // or the turn at the last sweep's rate about the map's z over the time to the next stamp.
  const Eigen::Quaterniond turn(last.linear() * before.linear().transpose());
  double angle = 2.0 * std::atan2(turn.z(), turn.w());
  if (config_.turn_from_sweep && last_sweep_.registered && seconds > 0.0 && std::isfinite(seconds))
    angle = (last.linear() * last_sweep_.turn_rate).z() * seconds;
  const Eigen::AngleAxisd yaw(angle, Eigen::Vector3d::UnitZ());
  Pose3 next = last;
  next.linear() = yaw * last.linear();
  next.translation() = last.translation() + yaw * (last.translation() - before.translation());
  return next;
}

void LidarOdometry::score_tilt_predictions(const Pose3& pose) {
  if (poses_.size() < 2) return;
  // The tilt is where the map's up points in the sensor's frame: the turn about z drops out.
  const auto up = [](const Pose3& T) -> Eigen::Vector3d {
    return T.linear().transpose() * Eigen::Vector3d::UnitZ();
  };
  const auto error = [&](const Pose3& predicted) {
    return std::acos(std::clamp(up(predicted).dot(up(pose)), -1.0, 1.0));
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();  // the tilt does not depend on the turn
  tilt_errors_.emplace_back(error(predict_with(false, nan)), error(predict_with(true, nan)));
  if (tilt_errors_.size() > static_cast<std::size_t>(config_.tilt_window)) tilt_errors_.pop_front();
}

double voxel_overlap(const std::vector<Eigen::Vector3d>& source, const VoxelHashMap& map, const Pose3& pose,
                     std::size_t stride) {
  if (source.empty() || stride == 0) return 0.0;
  std::size_t hits = 0, tried = 0;
  for (std::size_t i = 0; i < source.size(); i += stride, ++tried)
    hits += map.voxel_points(map.voxel_of(pose * source[i])).empty() ? 0 : 1;
  return static_cast<double>(hits) / static_cast<double>(tried);
}

std::vector<LidarOdometry::Start> LidarOdometry::initial_guesses(const std::vector<Eigen::Vector3d>& source,
                                                                 const Pose3& prediction) const {
  if (config_.yaw_search_deg <= 0.0 || poses_.empty()) return {{prediction, 0.0}};
  const std::size_t stride = overlap_stride(source);
  const double predicted = voxel_overlap(source, map_, prediction, stride);
  struct Scored {
    Start start;
    double score;
  };
  std::vector<Scored> tried;
  const int steps = static_cast<int>(std::floor(config_.yaw_search_deg / config_.yaw_search_step_deg + 1e-9));
  // Turns about the map's z at the sensor's place, from the prediction and from standing
  // still, nearest turns first so that ties keep the smaller turn.
  for (int k = 0; k <= steps; ++k) {
    for (const int sign : {1, -1}) {
      if (k == 0 && sign < 0) continue;
      const double turn = sign * k * config_.yaw_search_step_deg;
      const Eigen::Matrix3d R =
          Eigen::AngleAxisd(turn * kDegToRad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Pose3& still = poses_.back();
      for (const Pose3* base : {&prediction, &still}) {
        if (k == 0 && base == &prediction) continue;
        Pose3 guess = *base;
        guess.linear() = R * base->linear();
        tried.push_back({{guess, turn}, voxel_overlap(source, map_, guess, stride)});
      }
    }
  }
  // Best first; stable, so that of equal scores the smaller turn comes first.
  std::stable_sort(tried.begin(), tried.end(),
                   [](const Scored& a, const Scored& b) { return a.score > b.score; });
  if (tried.empty() || tried.front().score < predicted + config_.yaw_search_margin)
    return {{prediction, 0.0}};
  // The search's best, the prediction, then the next best turns that are more than two steps
  // from every turn already taken (a neighbour of a taken turn converges to the same pose).
  std::vector<Start> starts{tried.front().start};
  if (config_.yaw_search_candidates >= 2) starts.push_back({prediction, 0.0});
  for (const Scored& s : tried) {
    if (starts.size() >= static_cast<std::size_t>(config_.yaw_search_candidates)) break;
    if (s.score < predicted + config_.yaw_search_margin) break;
    const bool apart = std::all_of(starts.begin(), starts.end(), [&](const Start& t) {
      return std::abs(t.turn_deg - s.start.turn_deg) > 2.0 * config_.yaw_search_step_deg;
    });
    if (apart) starts.push_back(s.start);
  }
  return starts;
}

std::pair<LidarOdometry::Start, Pose3> LidarOdometry::choose_start(const std::vector<Eigen::Vector3d>& source,
                                                                   const Pose3& prediction,
                                                                   double sigma) const {
  const std::vector<Start> starts = initial_guesses(source, prediction);
  if (starts.size() == 1) return {starts.front(), starts.front().pose};
  // Each start gets a few ICP iterations; the one whose result overlaps the map most (the
  // first of equals) is registered to the end from there.
  LidarOdometryConfig quick = config_;
  quick.max_iterations = config_.yaw_search_candidate_iterations;
  const double distance = config_.correspondence_factor * sigma, kernel = sigma / config_.kernel_divisor;
  const std::size_t stride = overlap_stride(source);
  double best = -1.0;
  std::pair<Start, Pose3> chosen{starts.front(), starts.front().pose};
  for (const Start& s : starts) {
    const IcpResult result = align_to_map(source, map_, s.pose, distance, kernel, quick);
    const double overlap = voxel_overlap(source, map_, result.pose, stride);
    if (overlap > best) {
      best = overlap;
      chosen = {s, result.pose};
    }
  }
  return chosen;
}

double LidarOdometry::usual_overlap() const {
  return median(std::vector<double>(recent_overlaps_.begin(), recent_overlaps_.end()));
}

IcpResult LidarOdometry::register_from(const std::vector<Eigen::Vector3d>& source, const Pose3& start,
                                       double sigma) const {
  IcpResult result = align_to_map(source, map_, start, config_.correspondence_factor * sigma,
                                  sigma / config_.kernel_divisor, config_);
  // The threshold is the prediction's uncertainty: at 2 Hz, or swaying, metres, so the kernel
  // first lets in pairs of wrong neighbours, and they bias the pose they helped to reach.
  // From there ICP continues with fine_threshold's narrow kernel.
  if (config_.fine_threshold > 0.0 && sigma > config_.fine_threshold &&
      result.num_correspondences >= static_cast<std::size_t>(config_.min_correspondences)) {
    const double fine = config_.fine_threshold;
    const IcpResult refined = align_to_map(source, map_, result.pose, config_.correspondence_factor * fine,
                                           fine / config_.kernel_divisor, config_);
    if (refined.num_correspondences >= static_cast<std::size_t>(config_.min_correspondences)) {
      result.pose = refined.pose;
      result.iterations += refined.iterations;
      result.num_correspondences = refined.num_correspondences;
      result.converged = refined.converged;
    }
  }
  result.num_source = source.size();
  result.overlap = voxel_overlap(source, map_, result.pose, overlap_stride(source));
  result.lost = result.overlap < config_.min_overlap;
  return result;
}

std::size_t LidarOdometry::overlap_stride(const std::vector<Eigen::Vector3d>& source) const {
  return std::max<std::size_t>(1, source.size() / static_cast<std::size_t>(config_.yaw_search_points));
}

Pose3 LidarOdometry::recovery_start(const std::vector<Eigen::Vector3d>& source,
                                    const Pose3& prediction) const {
  const std::size_t stride =
      std::max<std::size_t>(1, source.size() / static_cast<std::size_t>(config_.recovery_points));
  double best = -1.0;
  int best_size = 0;  // of equal scores the smallest turn and shift wins: along a corridor every shift fits
  Pose3 best_pose = prediction;
  const double step = config_.voxel_size;  // a shift by less changes which voxels the points fall in little
  const int reach = static_cast<int>(std::floor(config_.recovery_search_m / step + 1e-9));
  const int turns =
      static_cast<int>(std::floor(config_.yaw_search_deg / config_.recovery_turn_step_deg + 1e-9));
  const Pose3& still = poses_.back();
  for (const Pose3* base : {&prediction, &still}) {
    for (int t = -turns; t <= turns; ++t) {
      Pose3 turned = *base;
      turned.linear() =
          Eigen::AngleAxisd(t * config_.recovery_turn_step_deg * kDegToRad, Eigen::Vector3d::UnitZ()) *
          base->linear();
      for (int i = -reach; i <= reach; ++i) {
        for (int j = -reach; j <= reach; ++j) {
          if (i * i + j * j > reach * reach) continue;
          Pose3 guess = turned;
          guess.translation() += Eigen::Vector3d(i * step, j * step, 0.0);
          const double score = voxel_overlap(source, map_, guess, stride);
          const int size = t * t + i * i + j * j;
          if (score > best || (score == best && size < best_size)) {  // then the first in this fixed order
            best = score;
            best_size = size;
            best_pose = guess;
          }
        }
      }
    }
  }
  return best_pose;
}

Pose3 LidarOdometry::register_scan(const PointCloud& scan) {
  return register_scan(scan, std::numeric_limits<double>::quiet_NaN());
}

Pose3 LidarOdometry::register_scan(const PointCloud& scan, double stamp) {
  const double last_interval = last_interval_;  // NaN without stamps
  last_interval_ = stamp - last_stamp_;
  const Pose3 prediction = predict(last_interval_);
  last_stamp_ = stamp;
  last_icp_ = IcpResult{};
  last_icp_.pose = prediction;
  last_sweep_ = SweepMotion{};
  last_sweep_.pose = prediction;

  // Two resolutions: a finer one keeps the map detailed, a coarser one makes ICP cheap.
  std::vector<Eigen::Vector3d> frame, source;
  std::vector<double> frame_times, source_times;
  first_points_in_range(scan, config_.min_range, config_.max_range,
                        config_.voxel_size * config_.map_voxel_factor, frame, frame_times);
  if (frame.empty()) {
    poses_.push_back(prediction);
    return prediction;
  }
  thin(frame, frame_times, config_.voxel_size * config_.registration_voxel_factor, source, source_times);
  const bool swept = config_.sweep_motion && spans_time(frame_times);

  const Pose3 pose =
      map_.empty() ? prediction : register_to_map(source, source_times, prediction, last_interval, swept);
  if (last_icp_.lost) {
    lost_.push_back(poses_.size());
    poses_.push_back(pose);
    return pose;
  }
  add_to_map(frame, frame_times, pose, swept && last_sweep_.registered);
  score_tilt_predictions(pose);
  poses_.push_back(pose);
  return pose;
}

Pose3 LidarOdometry::register_to_map(const std::vector<Eigen::Vector3d>& source,
                                     const std::vector<double>& source_times, const Pose3& prediction,
                                     double last_interval, bool swept) {
  const double sigma = threshold();
  const Pose3 start = register_rigid(source, prediction, sigma);
  Pose3 pose = last_icp_.pose;
  if (swept && !last_icp_.lost) {
    // The rigid pose fits the sweep as a whole; the sweep's own motion, found from there,
    // gives the pose at the stamp and straightens the points the map takes.
    last_sweep_ = align_sweep_to_map(source, source_times, map_, sweep_prior(pose, last_interval), sweep_);
    if (last_sweep_.registered) pose = last_sweep_.pose;
  }
  const Pose3 motion = poses_.back().inverse() * pose;
  // The threshold learns what ICP bridged: from the start it was given (a turn the search
  // found is no deviation of the motion model to widen every later search for) to its own
  // rigid result (the sweep's stamp pose lies a sweep's motion away from what ICP can fit).
  threshold_.update(start.inverse() * last_icp_.pose, motion, median_range(source));
  last_icp_.lost = last_icp_.overlap < config_.min_overlap;
  return pose;
}

Pose3 LidarOdometry::register_rigid(const std::vector<Eigen::Vector3d>& source, const Pose3& prediction,
                                    double sigma) {
  const auto [start_of_search, from] = choose_start(source, prediction, sigma);
  Pose3 start = start_of_search.pose;
  last_icp_ = register_from(source, from, sigma);
  last_icp_.turn_searched_deg = start_of_search.turn_deg;
  // Far below the usual overlap ICP ran into a wrong minimum, even above min_overlap (a
  // walker's turn and step both off the prediction).
  const double usual = usual_overlap();
  const bool suspect =
      last_icp_.overlap < config_.min_overlap || last_icp_.overlap < config_.recovery_overlap_ratio * usual;
  if (suspect && config_.recovery_search_m > 0.0) {
    const Pose3 again = recovery_start(source, prediction);
    const IcpResult retry = register_from(source, again, sigma);
    if (retry.overlap > last_icp_.overlap) {
      last_icp_ = retry;
      last_icp_.recovered = true;
      start = again;
    }
  }
  recent_overlaps_.push_back(last_icp_.overlap);
  if (recent_overlaps_.size() > static_cast<std::size_t>(config_.recovery_window))
    recent_overlaps_.pop_front();
  return start;
}

SweepMotion LidarOdometry::sweep_prior(const Pose3& pose, double last_interval) const {
  SweepMotion prior;
  prior.pose = pose;
  // The velocity's prior is the last interval's, between the last two stamps' poses: a
  // sweep hardly sees its velocity (deskew.velocity_sigma) and a carrier keeps it.
  if (last_interval > 0.0 && poses_.size() >= 2) {
    const Eigen::Vector3d moved = poses_.back().translation() - poses_[poses_.size() - 2].translation();
    prior.velocity = pose.linear().transpose() * moved / last_interval;
  }
  return prior;
}

void LidarOdometry::add_to_map(std::vector<Eigen::Vector3d>& frame, const std::vector<double>& frame_times,
                               const Pose3& pose, bool deskew) {
  if (deskew) {
    for (std::size_t i = 0; i < frame.size(); ++i)
      frame[i] = pose * (last_sweep_.after(frame_times[i]) * frame[i]);
  } else {
    for (Eigen::Vector3d& p : frame) p = pose * p;  // to the world, in place: not needed after
  }
  map_.add_points(frame);
  map_.remove_far(pose.translation(), config_.max_range);
}

}  // namespace tsgraphs::odometry
