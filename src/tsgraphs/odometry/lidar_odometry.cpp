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

#include "tsgraphs/core/voxel_grid.hpp"
#include "tsgraphs/odometry/se3.hpp"

namespace tsgraphs::odometry {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
constexpr double kDegToRad = M_PI / 180.0;

const LidarOdometryConfig& validated(const LidarOdometryConfig& c) {
  c.validate();
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
  tsl::robin_set<std::uint64_t, VoxelKeyHash> seen;
  seen.reserve(points.size());
  std::vector<std::size_t> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (seen.insert(voxel_key(points[i].cast<float>(), inv)).second) out.push_back(i);
  }
  return out;
}

namespace {

std::vector<Eigen::Vector3d> first_point_per_voxel(const std::vector<Eigen::Vector3d>& points, double voxel_size) {
  std::vector<Eigen::Vector3d> out;
  for (const std::size_t i : first_per_voxel(points, voxel_size)) out.push_back(points[i]);
  return out;
}

std::vector<Eigen::Vector3d> crop(const PointCloud& cloud, double min_range, double max_range) {
  std::vector<Eigen::Vector3d> out;
  for (const std::size_t i : in_range(cloud, min_range, max_range)) out.push_back(cloud.points[i].cast<double>());
  return out;
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

void LidarOdometryConfig::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("LidarOdometryConfig: " + what); };
  if (!(min_range >= 0.0)) fail("min_range must be >= 0");
  if (!(max_range > min_range) || !std::isfinite(max_range)) fail("max_range must be finite and > min_range");
  if (!(voxel_size > 0.0) || !std::isfinite(voxel_size)) fail("voxel_size must be positive and finite");
  if (!(map_voxel_factor > 0.0)) fail("map_voxel_factor must be > 0");
  if (!(registration_voxel_factor > 0.0)) fail("registration_voxel_factor must be > 0");
  if (max_points_per_voxel < 1) fail("max_points_per_voxel must be >= 1");
  if (plane_min_points < 3) fail("plane_min_points must be >= 3");
  if (!(plane_min_spread_factor > 0.0)) fail("plane_min_spread_factor must be > 0");
  if (!(plane_max_thickness_ratio > 0.0)) fail("plane_max_thickness_ratio must be > 0");
  if (!(initial_threshold > 0.0)) fail("initial_threshold must be > 0");
  if (!(min_threshold >= 0.0)) fail("min_threshold must be >= 0");
  if (!(fine_threshold >= 0.0) || !std::isfinite(fine_threshold)) fail("fine_threshold must be finite and >= 0");
  if (!(min_motion >= 0.0)) fail("min_motion must be >= 0");
  if (!(correspondence_factor > 0.0)) fail("correspondence_factor must be > 0");
  if (!(kernel_divisor > 0.0)) fail("kernel_divisor must be > 0");
  if (max_iterations < 1) fail("max_iterations must be >= 1");
  if (!(convergence_criterion > 0.0)) fail("convergence_criterion must be > 0");
  if (min_correspondences < 6) fail("min_correspondences must be >= 6 (six unknowns)");
  if (reduction_grain < 1) fail("reduction_grain must be >= 1");
  if (!(yaw_search_deg >= 0.0 && yaw_search_deg <= 180.0)) fail("yaw_search_deg must be in [0, 180]");
  if (!(yaw_search_step_deg >= 0.5 && yaw_search_step_deg <= 90.0)) fail("yaw_search_step_deg must be in [0.5, 90]");
  if (yaw_search_points < 10 || yaw_search_points > 1000000) fail("yaw_search_points must be in [10, 1000000]");
  if (!(yaw_search_margin >= 0.0 && yaw_search_margin <= 1.0)) fail("yaw_search_margin must be in [0, 1]");
  if (!(min_overlap >= 0.0 && min_overlap <= 1.0)) fail("min_overlap must be in [0, 1]");
  if (!(recovery_search_m >= 0.0 && recovery_search_m <= 10.0)) fail("recovery_search_m must be in [0, 10]");
  if (!(recovery_turn_step_deg >= 0.5 && recovery_turn_step_deg <= 90.0))
    fail("recovery_turn_step_deg must be in [0.5, 90]");
  if (recovery_points < 10 || recovery_points > 1000000) fail("recovery_points must be in [10, 1000000]");
}

IcpResult align_to_map(const std::vector<Eigen::Vector3d>& source, const VoxelHashMap& map, const Pose3& initial_guess,
                       double max_correspondence_distance, double kernel_scale, const LidarOdometryConfig& config) {
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

LidarOdometry::LidarOdometry(LidarOdometryConfig config)
    : config_(validated(config)),
      map_(config_.voxel_size, static_cast<std::size_t>(config_.max_points_per_voxel), config_.surface()),
      threshold_(config_.initial_threshold, config_.min_motion, config_.max_range) {}

double LidarOdometry::threshold() const { return std::max(threshold_.threshold(), config_.min_threshold); }

Pose3 LidarOdometry::last_motion() const {
  if (poses_.size() < 2) return Pose3::Identity();
  return poses_[poses_.size() - 2].inverse() * poses_.back();
}

Pose3 LidarOdometry::predict() const {
  if (poses_.empty()) return Pose3::Identity();
  if (poses_.size() == 1) return poses_.back();
  const Pose3& last = poses_.back();
  const Pose3& before = poses_[poses_.size() - 2];
  return last * (before.inverse() * last);  // constant velocity: repeat the last motion
}

double voxel_overlap(const std::vector<Eigen::Vector3d>& source, const VoxelHashMap& map, const Pose3& pose,
                     std::size_t stride) {
  if (source.empty() || stride == 0) return 0.0;
  std::size_t hits = 0, tried = 0;
  for (std::size_t i = 0; i < source.size(); i += stride, ++tried)
    hits += map.voxel_points(map.voxel_of(pose * source[i])).empty() ? 0 : 1;
  return static_cast<double>(hits) / static_cast<double>(tried);
}

Pose3 LidarOdometry::initial_guess(const std::vector<Eigen::Vector3d>& source, const Pose3& prediction) {
  if (config_.yaw_search_deg <= 0.0 || poses_.empty()) return prediction;
  const std::size_t stride = overlap_stride(source);
  const double predicted = voxel_overlap(source, map_, prediction, stride);
  double best = predicted;
  Pose3 best_pose = prediction;
  double best_turn = 0.0;
  const int steps = static_cast<int>(std::floor(config_.yaw_search_deg / config_.yaw_search_step_deg + 1e-9));
  // Turns about the map's z at the sensor's place, from the prediction and from standing
  // still, nearest turns first so that ties keep the smaller turn.
  for (int k = 0; k <= steps; ++k) {
    for (const int sign : {1, -1}) {
      if (k == 0 && sign < 0) continue;
      const double turn = sign * k * config_.yaw_search_step_deg;
      const Eigen::Matrix3d R = Eigen::AngleAxisd(turn * kDegToRad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Pose3& still = poses_.back();
      for (const Pose3* base : {&prediction, &still}) {
        if (k == 0 && base == &prediction) continue;
        Pose3 guess = *base;
        guess.linear() = R * base->linear();
        const double score = voxel_overlap(source, map_, guess, stride);
        if (score > best) {
          best = score;
          best_pose = guess;
          best_turn = turn;
        }
      }
    }
  }
  if (best < predicted + config_.yaw_search_margin) return prediction;
  last_icp_.turn_searched_deg = best_turn;
  return best_pose;
}

IcpResult LidarOdometry::register_from(const std::vector<Eigen::Vector3d>& source, const Pose3& start,
                                       double sigma) const {
  IcpResult result = align_to_map(source, map_, start, config_.correspondence_factor * sigma,
                                  sigma / config_.kernel_divisor, config_);
  // The threshold is the prediction's uncertainty: at 2 Hz, or swaying, metres, so the kernel
  // first lets in pairs of wrong neighbours, and they bias the pose they helped to reach.
  // From there ICP continues with a kernel as narrow as the threshold ever gets.
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

Pose3 LidarOdometry::recovery_start(const std::vector<Eigen::Vector3d>& source, const Pose3& prediction) const {
  const std::size_t stride =
      std::max<std::size_t>(1, source.size() / static_cast<std::size_t>(config_.recovery_points));
  double best = -1.0;
  Pose3 best_pose = prediction;
  const double step = config_.voxel_size;  // a shift by less changes which voxels the points fall in little
  const int reach = static_cast<int>(std::floor(config_.recovery_search_m / step + 1e-9));
  const int turns = static_cast<int>(std::floor(config_.yaw_search_deg / config_.recovery_turn_step_deg + 1e-9));
  const Pose3& still = poses_.back();
  for (const Pose3* base : {&prediction, &still}) {
    for (int t = -turns; t <= turns; ++t) {
      Pose3 turned = *base;
      turned.linear() =
          Eigen::AngleAxisd(t * config_.recovery_turn_step_deg * kDegToRad, Eigen::Vector3d::UnitZ()) * base->linear();
      for (int i = -reach; i <= reach; ++i) {
        for (int j = -reach; j <= reach; ++j) {
          if (i * i + j * j > reach * reach) continue;
          Pose3 guess = turned;
          guess.translation() += Eigen::Vector3d(i * step, j * step, 0.0);
          const double score = voxel_overlap(source, map_, guess, stride);
          if (score > best) {  // strict: the first of equals in this fixed order wins
            best = score;
            best_pose = guess;
          }
        }
      }
    }
  }
  return best_pose;
}

Pose3 LidarOdometry::register_scan(const PointCloud& scan) {
  const Pose3 prediction = predict();
  last_icp_ = IcpResult{};
  last_icp_.pose = prediction;

  // Two resolutions: a finer one keeps the map detailed, a coarser one makes ICP cheap.
  std::vector<Eigen::Vector3d> frame = first_point_per_voxel(
      crop(scan, config_.min_range, config_.max_range), config_.voxel_size * config_.map_voxel_factor);
  if (frame.empty()) {
    poses_.push_back(prediction);
    return prediction;
  }
  const std::vector<Eigen::Vector3d> source =
      first_point_per_voxel(frame, config_.voxel_size * config_.registration_voxel_factor);

  Pose3 pose = prediction;
  if (!map_.empty()) {
    const double sigma = threshold();
    Pose3 start = initial_guess(source, prediction);
    const double turn = last_icp_.turn_searched_deg;
    last_icp_ = register_from(source, start, sigma);
    last_icp_.turn_searched_deg = turn;
    if (last_icp_.overlap < config_.min_overlap && config_.recovery_search_m > 0.0) {
      const Pose3 again = recovery_start(source, prediction);
      const IcpResult retry = register_from(source, again, sigma);
      if (retry.overlap > last_icp_.overlap) {
        last_icp_ = retry;
        last_icp_.recovered = true;
        start = again;
      }
    }
    pose = last_icp_.pose;
    const Pose3 motion = poses_.back().inverse() * pose;
    // The threshold learns from the start ICP was given: a turn the search found is no
    // deviation of the motion model to widen every later search for.
    threshold_.update(start.inverse() * pose, motion);
    last_icp_.lost = last_icp_.overlap < config_.min_overlap;
  }
  if (last_icp_.lost) {
    lost_.push_back(poses_.size());
    poses_.push_back(pose);
    return pose;
  }

  for (Eigen::Vector3d& p : frame) p = pose * p;  // to the world, in place: not needed after
  map_.add_points(frame);
  map_.remove_far(pose.translation(), config_.max_range);
  poses_.push_back(pose);
  return pose;
}

}  // namespace tsgraphs::odometry
