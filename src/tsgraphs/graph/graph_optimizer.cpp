#include "tsgraphs/graph/graph_optimizer.hpp"

#include <ceres/ceres.h>
#include <ceres/product_manifold.h>
#include <ceres/sphere_manifold.h>

#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

namespace tsgraphs::graph {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// Keyframe block: translation then an Eigen-ordered quaternion (x, y, z, w), map <- keyframe.
constexpr int kPoseSize = 7;
constexpr int kQuaternionOffset = 3;
// Plane block: unit normal then offset, map frame.
constexpr int kPlaneSize = 4;
constexpr int kOffsetIndex = 3;

using PoseBlock = std::array<double, kPoseSize>;
using PlaneBlock = std::array<double, kPlaneSize>;
using PoseManifold =
    ceres::ProductManifold<ceres::EuclideanManifold<3>, ceres::EigenQuaternionManifold>;
using PlaneManifold = ceres::ProductManifold<ceres::SphereManifold<3>, ceres::EuclideanManifold<1>>;

// Relative pose T_ab between keyframes a and b minus its measurement: translation in a's
// frame and twice the vector part of the rotation error (the angle, for small errors).
struct BetweenResidual {
  BetweenResidual(const Pose3& T_ab, double sigma_trans, double sigma_rot)
      : t_ab(T_ab.translation()),
        q_ab_inv(Eigen::Quaterniond(T_ab.linear()).normalized().conjugate()),
        inv_sigma_trans(1.0 / sigma_trans),
        inv_sigma_rot(1.0 / sigma_rot) {}

  template <class T>
  bool operator()(const T* a, const T* b, T* residual) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t_a(a), t_b(b);
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(a + kQuaternionOffset),
        q_b(b + kQuaternionOffset);
    const Eigen::Quaternion<T> q_a_inv = q_a.conjugate();
    const Eigen::Matrix<T, 3, 1> t_ab_est = q_a_inv * (t_b - t_a);
    const Eigen::Quaternion<T> q_err = q_ab_inv.template cast<T>() * (q_a_inv * q_b);
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r.template head<3>() = (t_ab_est - t_ab.template cast<T>()) * T(inv_sigma_trans);
    r.template tail<3>() = q_err.vec() * T(2.0 * inv_sigma_rot);
    return true;
  }

  static ceres::CostFunction* create(const Pose3& T_ab, double sigma_trans, double sigma_rot) {
    return new ceres::AutoDiffCostFunction<BetweenResidual, 6, kPoseSize, kPoseSize>(
        new BetweenResidual(T_ab, sigma_trans, sigma_rot));
  }

  Eigen::Vector3d t_ab;
  Eigen::Quaterniond q_ab_inv;
  double inv_sigma_trans, inv_sigma_rot;
};

// The map plane seen from the keyframe minus the measured plane. For map plane (n, d) and
// keyframe pose (R, t): n_kf = R^T n, d_kf = n.t + d. The normal residual is the chord
// n_kf - n_meas (the angle for small errors); it keeps the sign, so a flipped normal costs.
struct PlaneResidual {
  PlaneResidual(const Plane& measured, double sigma_angle, double sigma_distance)
      : n_meas(measured.n.normalized()),
        d_meas(measured.d),
        inv_sigma_angle(1.0 / sigma_angle),
        inv_sigma_distance(1.0 / sigma_distance) {}

  template <class T>
  bool operator()(const T* pose, const T* plane, T* residual) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t(pose);
    const Eigen::Map<const Eigen::Quaternion<T>> q(pose + kQuaternionOffset);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> n(plane);
    const Eigen::Matrix<T, 3, 1> n_kf = q.conjugate() * n;
    const T d_kf = n.dot(t) + plane[kOffsetIndex];
    Eigen::Map<Eigen::Matrix<T, 4, 1>> r(residual);
    r.template head<3>() = (n_kf - n_meas.template cast<T>()) * T(inv_sigma_angle);
    r[3] = (d_kf - T(d_meas)) * T(inv_sigma_distance);
    return true;
  }

  static ceres::CostFunction* create(const Plane& measured, double sigma_angle,
                                     double sigma_distance) {
    return new ceres::AutoDiffCostFunction<PlaneResidual, 4, kPoseSize, kPlaneSize>(
        new PlaneResidual(measured, sigma_angle, sigma_distance));
  }

  Eigen::Vector3d n_meas;
  double d_meas;
  double inv_sigma_angle, inv_sigma_distance;
};

ceres::Solver::Options solver_options(const GraphOptimizerConfig& config, bool full) {
  ceres::Solver::Options options;
  if (!ceres::StringToLinearSolverType(config.linear_solver, &options.linear_solver_type))
    throw std::invalid_argument("GraphOptimizer: unknown linear_solver '" + config.linear_solver +
                                "'");
  if (!ceres::StringToSparseLinearAlgebraLibraryType(config.sparse_library,
                                                     &options.sparse_linear_algebra_library_type) ||
      !ceres::IsSparseLinearAlgebraLibraryTypeAvailable(options.sparse_linear_algebra_library_type))
    throw std::invalid_argument("GraphOptimizer: unknown or unavailable sparse_library '" +
                                config.sparse_library + "'");
  options.max_num_iterations = full ? config.max_iterations_full : config.max_iterations;
  options.num_threads = config.num_threads;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("GraphOptimizer: " + why);
  return options;
}

void check_config(const GraphOptimizerConfig& c) {
  solver_options(c, false);
  solver_options(c, true);
  const bool positive = c.odometry_sigma_trans > 0 && c.odometry_sigma_rot_deg > 0 &&
                        c.loop_sigma_trans > 0 && c.loop_sigma_rot_deg > 0 &&
                        c.plane_sigma_angle_deg > 0 && c.plane_sigma_distance > 0 &&
                        c.huber_plane > 0 && c.huber_loop > 0 && c.local_window > 0;
  if (!positive)
    throw std::invalid_argument(
        "GraphOptimizer: sigmas, Huber deltas and local_window must be > 0");
}

PoseBlock to_block(const Pose3& pose) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(pose.linear()).normalized();
  return {pose.translation().x(),
          pose.translation().y(),
          pose.translation().z(),
          q.x(),
          q.y(),
          q.z(),
          q.w()};
}

Pose3 from_block(const PoseBlock& b) {
  Pose3 pose = Pose3::Identity();
  pose.translation() = Eigen::Vector3d(b[0], b[1], b[2]);
  pose.linear() = Eigen::Quaterniond(b[6], b[3], b[4], b[5]).normalized().toRotationMatrix();
  return pose;
}

PlaneBlock to_block(const Plane& plane) {
  const Eigen::Vector3d n = plane.n.normalized();
  return {n.x(), n.y(), n.z(), plane.d};
}

// The estimate as a plane with a unit normal on the side of `previous` (same plane either way).
Plane from_block(const PlaneBlock& b, const Plane& previous) {
  Plane plane;
  const Eigen::Vector3d n(b[0], b[1], b[2]);
  const double norm = n.norm();
  plane.n = n / norm;
  plane.d = b[kOffsetIndex] / norm;
  if (plane.n.dot(previous.n) < 0.0) {
    plane.n = -plane.n;
    plane.d = -plane.d;
  }
  return plane;
}

// The Ceres problem and its blocks, made on first use; blocks that are not free are held
// constant. Members the problem borrows (losses, manifolds, block storage) outlive it.
class GraphProblem {
 public:
  GraphProblem(SituationalGraph& graph, const GraphOptimizerConfig& config)
      : graph_(graph),
        loop_loss_(config.huber_loop),
        plane_loss_(config.huber_plane),
        problem_(problem_options()) {}

  ceres::Problem& problem() { return problem_; }
  ceres::LossFunction* loop_loss() { return &loop_loss_; }
  ceres::LossFunction* plane_loss() { return &plane_loss_; }

  double* pose(int id, bool free) {
    auto [it, inserted] = poses_.try_emplace(id);
    if (inserted) {
      it->second = to_block(graph_.keyframes()[static_cast<std::size_t>(id)].pose);
      add(it->second.data(), kPoseSize, &pose_manifold_, free);
    }
    return it->second.data();
  }

  double* plane(int id, bool free) {
    auto [it, inserted] = planes_.try_emplace(id);
    if (inserted) {
      it->second = to_block(graph_.planes().at(id).plane);
      add(it->second.data(), kPlaneSize, &plane_manifold_, free);
    }
    return it->second.data();
  }

  int num_free() const { return num_free_; }

  // Copies the free blocks' estimates into the graph.
  void write_back() {
    for (const auto& [id, block] : poses_)
      if (!problem_.IsParameterBlockConstant(block.data()))
        graph_.keyframes()[static_cast<std::size_t>(id)].pose = from_block(block);
    for (const auto& [id, block] : planes_) {
      if (problem_.IsParameterBlockConstant(block.data())) continue;
      Plane& plane = graph_.planes().at(id).plane;
      plane = from_block(block, plane);
    }
  }

 private:
  static ceres::Problem::Options problem_options() {
    ceres::Problem::Options options;
    options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return options;
  }

  void add(double* block, int size, ceres::Manifold* manifold, bool free) {
    problem_.AddParameterBlock(block, size, manifold);
    if (free)
      ++num_free_;
    else
      problem_.SetParameterBlockConstant(block);
  }

  SituationalGraph& graph_;
  ceres::HuberLoss loop_loss_, plane_loss_;
  PoseManifold pose_manifold_;
  PlaneManifold plane_manifold_;
  std::map<int, PoseBlock> poses_;
  std::map<int, PlaneBlock> planes_;
  int num_free_ = 0;
  ceres::Problem problem_;  // last: destroyed first
};

void check_between(const BetweenEdge& e, int num_keyframes) {
  if (e.from < 0 || e.to < 0 || e.from >= num_keyframes || e.to >= num_keyframes || e.from == e.to)
    throw std::invalid_argument("GraphOptimizer: pose edge with unknown or equal keyframes");
}

}  // namespace

GraphOptimizer::GraphOptimizer(GraphOptimizerConfig config) : config_(std::move(config)) {
  check_config(config_);
}

OptimizationStats GraphOptimizer::optimize(SituationalGraph& graph, bool full) {
  const int num_keyframes = static_cast<int>(graph.keyframes().size());
  if (num_keyframes == 0) throw std::invalid_argument("GraphOptimizer: the graph has no keyframes");
  OptimizationStats stats;
  stats.full = full;

  // Keyframe 0 anchors the map; a local solve frees only the last local_window keyframes.
  const int first_free = full ? 1 : std::max(1, num_keyframes - config_.local_window);
  const auto keyframe_free = [first_free](int id) { return id >= first_free; };
  std::set<int> free_planes;
  for (const PlaneEdge& e : graph.plane_edges()) {
    if (e.keyframe < 0 || e.keyframe >= num_keyframes || !graph.planes().count(e.plane))
      throw std::invalid_argument("GraphOptimizer: plane edge with unknown keyframe or plane");
    if (keyframe_free(e.keyframe)) free_planes.insert(e.plane);
  }
  const auto plane_free = [&free_planes](int id) { return free_planes.count(id) > 0; };

  GraphProblem graph_problem(graph, config_);
  ceres::Problem& problem = graph_problem.problem();

  // Only factors touching a free block enter, so a local problem does not grow with the run.
  const auto add_between = [&](const BetweenEdge& e, double sigma_trans, double sigma_rot_deg,
                               ceres::LossFunction* loss) {
    check_between(e, num_keyframes);
    if (!keyframe_free(e.from) && !keyframe_free(e.to)) return;
    problem.AddResidualBlock(
        BetweenResidual::create(e.measurement, sigma_trans, sigma_rot_deg * kDegToRad), loss,
        graph_problem.pose(e.from, keyframe_free(e.from)),
        graph_problem.pose(e.to, keyframe_free(e.to)));
  };
  for (const BetweenEdge& e : graph.odometry_edges())
    add_between(e, config_.odometry_sigma_trans, config_.odometry_sigma_rot_deg, nullptr);
  for (const BetweenEdge& e : graph.loop_edges())
    add_between(e, config_.loop_sigma_trans, config_.loop_sigma_rot_deg, graph_problem.loop_loss());
  for (const PlaneEdge& e : graph.plane_edges()) {
    if (!keyframe_free(e.keyframe) && !plane_free(e.plane)) continue;
    problem.AddResidualBlock(
        PlaneResidual::create(e.measurement, config_.plane_sigma_angle_deg * kDegToRad,
                              config_.plane_sigma_distance),
        graph_problem.plane_loss(), graph_problem.pose(e.keyframe, keyframe_free(e.keyframe)),
        graph_problem.plane(e.plane, plane_free(e.plane)));
  }

  stats.n_variables = graph_problem.num_free();
  stats.n_factors = problem.NumResidualBlocks();
  if (stats.n_variables == 0) return stats;

  const ceres::Solver::Options options = solver_options(config_, full);
  ceres::Solver::Summary summary;
  const auto start = std::chrono::steady_clock::now();
  ceres::Solve(options, &problem, &summary);
  stats.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!summary.IsSolutionUsable())
    throw std::runtime_error("GraphOptimizer: Ceres failed: " + summary.message);

  stats.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  stats.initial_cost = summary.initial_cost;
  stats.final_cost = summary.final_cost;
  graph_problem.write_back();
  return stats;
}

}  // namespace tsgraphs::graph
