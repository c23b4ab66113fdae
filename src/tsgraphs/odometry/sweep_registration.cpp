#include "tsgraphs/odometry/sweep_registration.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tsgraphs/odometry/se3.hpp"

namespace tsgraphs::odometry {
namespace {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

/// Normal equations of one step; unknowns: the pose's (translation, rotation) update in the
/// map frame, then the velocity's and the turn rate's.
struct Equations {
  Matrix12d H = Matrix12d::Zero();
  Vector12d g = Vector12d::Zero();
  std::size_t count = 0;
};

Eigen::Matrix3d turn(const Eigen::Vector3d& rotation_vector) {
  const double angle = rotation_vector.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rotation_vector / angle).toRotationMatrix();
}

}  // namespace

Pose3 SweepMotion::after(double seconds) const {
  Pose3 out = Pose3::Identity();
  out.linear() = turn(turn_rate * seconds);
  out.translation() = velocity * seconds;
  return out;
}

SweepMotion SweepMotion::from_motion(const Pose3& pose, const Pose3& motion, double seconds) {
  if (!(seconds > 0.0)) throw std::invalid_argument("SweepMotion::from_motion: seconds must be > 0");
  SweepMotion m;
  m.pose = pose;
  const Eigen::AngleAxisd aa(motion.linear());
  m.turn_rate = aa.axis() * aa.angle() / seconds;
  m.velocity = motion.translation() / seconds;
  return m;
}

namespace {

/// The inverse variances of the point residuals and of the priors.
struct Weights {
  double point, turn, velocity, turn_pose, pose;
};

Weights weights_of(const SweepRegistrationConfig& config) {
  Weights w;
  w.point = 1.0 / (config.point_sigma * config.point_sigma);
  w.turn = 1.0 / (config.turn_rate_sigma * config.turn_rate_sigma);
  w.velocity = 1.0 / (config.velocity_sigma * config.velocity_sigma);
  w.turn_pose = std::pow(config.pose_sigma_deg * M_PI / 180.0, -2);
  w.pose = std::pow(config.pose_sigma, -2);
  return w;
}

/// Adds the point's residual (stamped t, at motion m) against its nearest map point within
/// `distance` to `acc`; false when it has none to trust.
bool add_point(const Eigen::Vector3d& point, double t, const VoxelHashMap& map, const SweepMotion& m,
               const Eigen::Matrix3d& R, double distance, double kernel_sq, double inv_point_var,
               Equations& acc) {
  const Eigen::Vector3d turned = turn(m.turn_rate * t) * point;
  const Eigen::Vector3d x = m.pose * (turned + m.velocity * t);
  const Neighbour nb = map.nearest(x);
  if (!nb.found || nb.distance > distance) return false;
  const Eigen::Vector3d r = x - nb.point;
  // d x: [I, -[x]x] for the pose (left update), R t for the velocity, -t R [turned]x
  // for the turn rate (a small change of rate turns the point about the stamp frame).
  Eigen::Matrix<double, 3, 12> J;
  J.block<3, 3>(0, 0).setIdentity();
  J.block<3, 3>(0, 3) = -skew(x);
  J.block<3, 3>(0, 6) = R * t;
  J.block<3, 3>(0, 9) = -t * R * skew(turned);
  if (nb.surface == Surface::planar) {
    const double e = nb.normal.dot(r);
    const Eigen::Matrix<double, 12, 1> Jn = J.transpose() * nb.normal;
    const double w = kernel_sq * kernel_sq / std::pow(kernel_sq + e * e, 2) * inv_point_var;
    acc.H.noalias() += w * Jn * Jn.transpose();
    acc.g.noalias() += w * e * Jn;
  } else if (nb.surface == Surface::scattered) {
    const double w = kernel_sq * kernel_sq / std::pow(kernel_sq + r.squaredNorm(), 2) * inv_point_var;
    acc.H.noalias() += w * J.transpose() * J;
    acc.g.noalias() += w * J.transpose() * r;
  } else {
    return false;  // a line or too few points: no direction to trust
  }
  return true;
}

/// The points' normal equations at motion `m`, over correspondences within `distance`.
Equations point_equations(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& times,
                          const VoxelHashMap& map, const SweepMotion& m, double distance,
                          const SweepRegistrationConfig& config, double inv_point_var) {
  const double kernel_sq = std::pow(distance / config.kernel_divisor, 2);
  const Eigen::Matrix3d R = m.pose.linear();
  const std::size_t grain = static_cast<std::size_t>(config.reduction_grain);
  // Deterministic reduction: the same split and join order whatever the threads (see align_to_map).
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, points.size(), grain), Equations{},
      [&](const tbb::blocked_range<std::size_t>& range, Equations acc) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          if (add_point(points[i], times[i], map, m, R, distance, kernel_sq, inv_point_var, acc)) ++acc.count;
        }
        return acc;
      },
      [](Equations a, const Equations& b) {
        a.H += b.H;
        a.g += b.g;
        a.count += b.count;
        return a;
      });
}

/// Adds the priors on the velocity, the turn rate and the pose to `H` and `g`.
void add_priors(const SweepMotion& m, const SweepMotion& prior, const Weights& w, Matrix12d& H,
                Vector12d& g) {
  H.block<3, 3>(6, 6).diagonal().array() += w.velocity;
  H.block<3, 3>(9, 9).diagonal().array() += w.turn;
  g.segment<3>(6) += w.velocity * (m.velocity - prior.velocity);
  g.segment<3>(9) += w.turn * (m.turn_rate - prior.turn_rate);
  // The pose's prior, in the same left-update coordinates: log(pose * prior^-1) to first order.
  const Pose3 off = m.pose * prior.pose.inverse();
  const Eigen::AngleAxisd off_turn(off.linear());
  H.block<3, 3>(0, 0).diagonal().array() += w.pose;
  H.block<3, 3>(3, 3).diagonal().array() += w.turn_pose;
  g.segment<3>(0) += w.pose * off.translation();
  g.segment<3>(3) += w.turn_pose * off_turn.axis() * off_turn.angle();
}

/// The prior, unregistered, after `iterations` with `count` correspondences (too few).
SweepMotion not_registered(const SweepMotion& prior, int iterations, std::size_t count) {
  SweepMotion kept = prior;
  kept.registered = false;
  kept.iterations = iterations;
  kept.num_correspondences = count;
  return kept;
}

}  // namespace

SweepMotion align_sweep_to_map(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& times,
                               const VoxelHashMap& map, const SweepMotion& prior,
                               const SweepRegistrationConfig& config) {
  if (points.size() != times.size()) throw std::invalid_argument("align_sweep_to_map: one time per point");
  SweepMotion m = prior;
  m.registered = false;
  m.iterations = 0;
  m.num_correspondences = 0;
  if (points.empty() || map.empty()) return m;
  const Weights weights = weights_of(config);

  double distance = config.initial_distance;
  for (int iteration = 0;;) {
    ++iteration;
    ++m.iterations;
    const Equations eq = point_equations(points, times, map, m, distance, config, weights.point);
    m.num_correspondences = eq.count;
    if (eq.count < static_cast<std::size_t>(config.min_correspondences))
      return not_registered(prior, m.iterations, eq.count);
    Matrix12d H = eq.H;
    Vector12d g = eq.g;
    add_priors(m, prior, weights, H, g);
    const Vector12d dx = H.ldlt().solve(-g);
    if (!dx.allFinite()) break;
    m.pose = se3_exp(dx.head<6>()) * m.pose;
    m.velocity += dx.segment<3>(6);
    m.turn_rate += dx.segment<3>(9);
    const bool converged = dx.norm() < config.convergence_criterion;
    // Each distance until converged or out of iterations, halving down to final_distance.
    if (converged || iteration >= config.max_iterations) {
      if (distance <= config.final_distance) break;
      distance = std::max(config.final_distance, 0.5 * distance);
      iteration = 0;
    }
  }
  m.pose.linear() = Eigen::Quaterniond(m.pose.linear()).normalized().toRotationMatrix();
  m.registered = true;
  return m;
}

}  // namespace tsgraphs::odometry
