#include "tsgraphs/graph/graph_optimizer.hpp"

#include <ceres/ceres.h>
#include <ceres/product_manifold.h>
#include <ceres/sphere_manifold.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace tsgraphs::graph {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// Keyframe block: translation then an Eigen-ordered quaternion (x, y, z, w), map <- keyframe.
constexpr int kPoseSize = 7;
constexpr int kQuaternionOffset = 3;
// Plane block: unit normal then offset, map frame.
constexpr int kPlaneSize = 4;
constexpr int kOffsetIndex = 3;

// Room and floor blocks: the centre, map x-y.
constexpr int kCenterSize = 2;

using PoseBlock = std::array<double, kPoseSize>;
using PlaneBlock = std::array<double, kPlaneSize>;
using CenterBlock = std::array<double, kCenterSize>;
using PoseManifold = ceres::ProductManifold<ceres::EuclideanManifold<3>, ceres::EigenQuaternionManifold>;
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
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(a + kQuaternionOffset), q_b(b + kQuaternionOffset);
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

  static ceres::CostFunction* create(const Plane& measured, double sigma_angle, double sigma_distance) {
    return new ceres::AutoDiffCostFunction<PlaneResidual, 4, kPoseSize, kPlaneSize>(
        new PlaneResidual(measured, sigma_angle, sigma_distance));
  }

  Eigen::Vector3d n_meas;
  double d_meas;
  double inv_sigma_angle, inv_sigma_distance;
};

// Signed distance of the x-y point c from a vertical plane's trace on the x-y plane (the
// horizontal part of its normal renormalised, so a slight tilt does not scale it).
template <class T>
T horizontal_distance(const T* plane, const Eigen::Matrix<T, 2, 1>& c) {
  const Eigen::Matrix<T, 2, 1> n(plane[0], plane[1]);
  return (n.dot(c) + plane[kOffsetIndex]) / n.norm();
}

// Offset of c from the mid-plane of two facing walls (normals into the room), along the first
// wall's normal: half the difference of its distances to them, zero halfway between.
template <class T>
T midplane_offset(const T* wall_a, const T* wall_b, const Eigen::Matrix<T, 2, 1>& c) {
  return T(0.5) * (horizontal_distance(wall_a, c) - horizontal_distance(wall_b, c));
}

// Room-4-planes: the centre's offset from the mid-plane of each facing pair.
struct RoomResidual {
  explicit RoomResidual(double sigma) : inv_sigma(1.0 / sigma) {}

  template <class T>
  bool operator()(const T* center, const T* a1, const T* a2, const T* b1, const T* b2, T* residual) const {
    const Eigen::Matrix<T, 2, 1> c(center[0], center[1]);
    residual[0] = midplane_offset(a1, a2, c) * T(inv_sigma);
    residual[1] = midplane_offset(b1, b2, c) * T(inv_sigma);
    return true;
  }

  static ceres::CostFunction* create(double sigma) {
    return new ceres::AutoDiffCostFunction<RoomResidual, 2, kCenterSize, kPlaneSize, kPlaneSize, kPlaneSize,
                                           kPlaneSize>(new RoomResidual(sigma));
  }

  double inv_sigma;
};

// Room-2-planes (a corridor): the centre's offset from the midline of its walls, and its offset
// from the measured cluster centre along the corridor (the walls do not fix that direction).
struct CorridorResidual {
  CorridorResidual(const Eigen::Vector2d& cluster_center, double sigma, double along_sigma)
      : cluster(cluster_center), inv_sigma(1.0 / sigma), inv_along_sigma(1.0 / along_sigma) {}

  template <class T>
  bool operator()(const T* center, const T* a, const T* b, T* residual) const {
    const Eigen::Matrix<T, 2, 1> c(center[0], center[1]);
    const Eigen::Matrix<T, 2, 1> n_a(a[0], a[1]), n_b(b[0], b[1]);
    const Eigen::Matrix<T, 2, 1> across = n_a / n_a.norm() - n_b / n_b.norm();
    const Eigen::Matrix<T, 2, 1> along = Eigen::Matrix<T, 2, 1>(-across.y(), across.x()) / across.norm();
    residual[0] = midplane_offset(a, b, c) * T(inv_sigma);
    residual[1] = along.dot(c - cluster.template cast<T>()) * T(inv_along_sigma);
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector2d& cluster_center, double sigma,
                                     double along_sigma) {
    return new ceres::AutoDiffCostFunction<CorridorResidual, 2, kCenterSize, kPlaneSize, kPlaneSize>(
        new CorridorResidual(cluster_center, sigma, along_sigma));
  }

  Eigen::Vector2d cluster;
  double inv_sigma, inv_along_sigma;
};

// The floor's centre minus the mean of its rooms' centres. Blocks: the floor, then its rooms.
// Linear, so the Jacobians are constant: I / sigma for the floor, -I / (n sigma) per room.
class FloorResidual : public ceres::CostFunction {
 public:
  FloorResidual(int num_rooms, double sigma) : num_rooms_(num_rooms), inv_sigma_(1.0 / sigma) {
    set_num_residuals(kCenterSize);
    mutable_parameter_block_sizes()->assign(static_cast<std::size_t>(num_rooms) + 1, kCenterSize);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double room_weight = 1.0 / num_rooms_;
    for (int i = 0; i < kCenterSize; ++i) {
      double mean = 0.0;
      for (int r = 1; r <= num_rooms_; ++r) mean += parameters[r][i];
      residuals[i] = (parameters[0][i] - mean * room_weight) * inv_sigma_;
    }
    if (!jacobians) return true;
    for (int b = 0; b <= num_rooms_; ++b) {
      if (!jacobians[b]) continue;
      const double diagonal = b == 0 ? inv_sigma_ : -inv_sigma_ * room_weight;
      Eigen::Map<Eigen::Matrix<double, kCenterSize, kCenterSize, Eigen::RowMajor>> jacobian(jacobians[b]);
      jacobian = Eigen::Matrix2d::Identity() * diagonal;
    }
    return true;
  }

 private:
  int num_rooms_;
  double inv_sigma_;
};

// Ceres's own types for the config's solver and library (false: this Ceres lacks the name).
bool to_ceres(const GraphOptimizerConfig& config, ceres::Solver::Options* options) {
  return ceres::StringToLinearSolverType(kLinearSolvers.name(config.linear_solver),
                                         &options->linear_solver_type) &&
         ceres::StringToSparseLinearAlgebraLibraryType(kSparseLibraries.name(config.sparse_library),
                                                       &options->sparse_linear_algebra_library_type);
}

ceres::Solver::Options solver_options(const GraphOptimizerConfig& config, bool full) {
  ceres::Solver::Options options;
  to_ceres(config, &options);
  options.max_num_iterations = full ? config.max_iterations_full : config.max_iterations;
  options.num_threads = config.num_threads;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

PoseBlock to_block(const Pose3& pose) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(pose.linear()).normalized();
  return {pose.translation().x(), pose.translation().y(), pose.translation().z(), q.x(), q.y(), q.z(), q.w()};
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
        room_loss_(config.huber_room),
        floor_loss_(config.huber_floor),
        problem_(problem_options()) {}

  ceres::Problem& problem() { return problem_; }
  ceres::LossFunction* loop_loss() { return &loop_loss_; }
  ceres::LossFunction* plane_loss() { return &plane_loss_; }
  ceres::LossFunction* room_loss() { return &room_loss_; }
  ceres::LossFunction* floor_loss() { return &floor_loss_; }

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

  double* room(int id, bool free) { return center(rooms_, id, graph_.rooms().at(id).center, free); }

  double* floor(int id, bool free) { return center(floors_, id, graph_.floors().at(id).center, free); }

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
    for (const auto& [id, block] : rooms_)
      if (!problem_.IsParameterBlockConstant(block.data()))
        graph_.rooms().at(id).center = Eigen::Vector2d(block[0], block[1]);
    for (const auto& [id, block] : floors_)
      if (!problem_.IsParameterBlockConstant(block.data()))
        graph_.floors().at(id).center = Eigen::Vector2d(block[0], block[1]);
  }

 private:
  static ceres::Problem::Options problem_options() {
    ceres::Problem::Options options;
    options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return options;
  }

  double* center(std::map<int, CenterBlock>& blocks, int id, const Eigen::Vector2d& value, bool free) {
    auto [it, inserted] = blocks.try_emplace(id);
    if (inserted) {
      it->second = {value.x(), value.y()};
      add(it->second.data(), kCenterSize, nullptr, free);
    }
    return it->second.data();
  }

  void add(double* block, int size, ceres::Manifold* manifold, bool free) {
    problem_.AddParameterBlock(block, size, manifold);
    if (free)
      ++num_free_;
    else
      problem_.SetParameterBlockConstant(block);
  }

  SituationalGraph& graph_;
  ceres::HuberLoss loop_loss_, plane_loss_, room_loss_, floor_loss_;
  PoseManifold pose_manifold_;
  PlaneManifold plane_manifold_;
  std::map<int, PoseBlock> poses_;
  std::map<int, PlaneBlock> planes_;
  std::map<int, CenterBlock> rooms_, floors_;
  int num_free_ = 0;
  ceres::Problem problem_;  // last: destroyed first
};

void check_between(const BetweenEdge& e, const SituationalGraph& graph) {
  const int n = static_cast<int>(graph.keyframes().size());
  if (e.from < 0 || e.to < 0 || e.from >= n || e.to >= n || e.from == e.to)
    throw std::invalid_argument("GraphOptimizer: pose edge with unknown or equal keyframes");
  if (graph.keyframes()[e.from].retired || graph.keyframes()[e.to].retired)
    throw std::invalid_argument("GraphOptimizer: pose edge to a retired keyframe");
  if (e.folded > 0 && !(e.sigmas.trans > 0 && e.sigmas.rot_deg > 0))
    throw std::invalid_argument("GraphOptimizer: folded pose edge without positive sigmas");
}

// A room edge names distinct, known, vertical planes, in pairs that face each other (normals
// into the room: opposite sides of it). Ceres also refuses a block named twice in one factor.
void check_room_edge(const RoomPlanesEdge& e, const SituationalGraph& graph) {
  if (!graph.rooms().count(e.room) || e.planes.size() != planes_of(e.kind))
    throw std::invalid_argument(
        "GraphOptimizer: room edge with an unknown room or a plane count "
        "that does not fit its kind");
  for (int id : e.planes) {
    const auto it = graph.planes().find(id);
    if (it == graph.planes().end() || !it->second.vertical)
      throw std::invalid_argument("GraphOptimizer: room edge with an unknown or horizontal plane");
  }
  if (std::set<int>(e.planes.begin(), e.planes.end()).size() != e.planes.size())
    throw std::invalid_argument("GraphOptimizer: room edge naming a plane twice");
  for (std::size_t i = 0; i < e.planes.size(); i += 2) {
    const Eigen::Vector3d& n_a = graph.planes().at(e.planes[i]).plane.n;
    const Eigen::Vector3d& n_b = graph.planes().at(e.planes[i + 1]).plane.n;
    if (n_a.head<2>().dot(n_b.head<2>()) >= 0.0)
      throw std::invalid_argument("GraphOptimizer: room edge with a pair that does not face");
  }
}

/// Which blocks a solve moves. Keyframe 0 anchors the map; a local solve frees only the last
/// local_window keyframes, the planes they see, the rooms of those planes and the floors of
/// those rooms; a full solve frees everything.
struct FreeBlocks {
  int first_free = 1;
  std::set<int> planes;
  std::set<int> rooms;
  std::map<int, std::set<int>> rooms_of_floor;

  bool keyframe(int id) const { return id >= first_free; }
  bool plane(int id) const { return planes.count(id) > 0; }
  bool room(int id) const { return rooms.count(id) > 0; }
};

/// The free blocks of a solve, the edges they hang on checked.
FreeBlocks free_blocks(const SituationalGraph& graph, bool full, int local_window) {
  const int num_keyframes = static_cast<int>(graph.keyframes().size());
  FreeBlocks free;
  free.first_free = full ? 1 : std::max(1, num_keyframes - local_window);
  for (const PlaneEdge& e : graph.plane_edges()) {
    if (e.keyframe < 0 || e.keyframe >= num_keyframes || !graph.planes().count(e.plane) ||
        graph.keyframes()[e.keyframe].retired)
      throw std::invalid_argument(
          "GraphOptimizer: plane edge with an unknown or retired keyframe, or unknown plane");
    if (free.keyframe(e.keyframe)) free.planes.insert(e.plane);
  }
  // A room moves with its walls: free when one of them is (always in a full solve).
  for (const RoomPlanesEdge& e : graph.room_edges()) {
    check_room_edge(e, graph);
    if (full || std::any_of(e.planes.begin(), e.planes.end(), [&](int id) { return free.plane(id); }))
      free.rooms.insert(e.room);
  }
  for (const FloorRoomEdge& e : graph.floor_room_edges()) {
    if (!graph.floors().count(e.floor) || !graph.rooms().count(e.room))
      throw std::invalid_argument("GraphOptimizer: floor edge with unknown floor or room");
    free.rooms_of_floor[e.floor].insert(e.room);
  }
  return free;
}

/// Odometry, loop and plane factors that touch a free block (so that a local problem does not
/// grow with the run).
void add_keyframe_factors(GraphProblem& gp, const SituationalGraph& graph, const FreeBlocks& free,
                          const GraphOptimizerConfig& config) {
  ceres::Problem& problem = gp.problem();
  const auto add_between = [&](const BetweenEdge& e, double sigma_trans, double sigma_rot_deg,
                               ceres::LossFunction* loss) {
    check_between(e, graph);
    if (!free.keyframe(e.from) && !free.keyframe(e.to)) return;
    // An edge that retired keyframes were folded into carries its own, larger noise.
    if (e.folded > 0) {
      sigma_trans = e.sigmas.trans;
      sigma_rot_deg = e.sigmas.rot_deg;
    }
    problem.AddResidualBlock(BetweenResidual::create(e.measurement, sigma_trans, sigma_rot_deg * kDegToRad),
                             loss, gp.pose(e.from, free.keyframe(e.from)),
                             gp.pose(e.to, free.keyframe(e.to)));
  };
  for (const BetweenEdge& e : graph.odometry_edges())
    add_between(e, config.odometry_sigma_trans, config.odometry_sigma_rot_deg, nullptr);
  for (const BetweenEdge& e : graph.loop_edges())
    add_between(e, config.loop_sigma_trans, config.loop_sigma_rot_deg, gp.loop_loss());
  for (const PlaneEdge& e : graph.plane_edges()) {
    if (!free.keyframe(e.keyframe) && !free.plane(e.plane)) continue;
    problem.AddResidualBlock(PlaneResidual::create(e.measurement, config.plane_sigma_angle_deg * kDegToRad,
                                                   config.plane_sigma_distance),
                             gp.plane_loss(), gp.pose(e.keyframe, free.keyframe(e.keyframe)),
                             gp.plane(e.plane, free.plane(e.plane)));
  }
}

/// Room and corridor factors of the free rooms, floor factors of floors with a free room.
void add_room_factors(GraphProblem& gp, const SituationalGraph& graph, const FreeBlocks& free, bool full,
                      const GraphOptimizerConfig& config) {
  ceres::Problem& problem = gp.problem();
  for (const RoomPlanesEdge& e : graph.room_edges()) {
    if (!free.room(e.room)) continue;
    std::vector<double*> walls;
    for (int id : e.planes) walls.push_back(gp.plane(id, free.plane(id)));
    double* center = gp.room(e.room, true);
    if (e.kind == RoomKind::room)
      problem.AddResidualBlock(RoomResidual::create(config.room_sigma), gp.room_loss(), center, walls[0],
                               walls[1], walls[2], walls[3]);
    else
      problem.AddResidualBlock(
          CorridorResidual::create(e.cluster_center, config.corridor_sigma, config.corridor_along_sigma),
          gp.room_loss(), center, walls[0], walls[1]);
  }
  // A floor follows its rooms: free when one of them is (always in a full solve).
  for (const auto& [floor, rooms] : free.rooms_of_floor) {
    if (!full && std::none_of(rooms.begin(), rooms.end(), [&](int id) { return free.room(id); })) continue;
    std::vector<double*> blocks{gp.floor(floor, true)};
    for (int room : rooms) blocks.push_back(gp.room(room, free.room(room)));
    problem.AddResidualBlock(new FloorResidual(static_cast<int>(rooms.size()), config.floor_sigma),
                             gp.floor_loss(), blocks);
  }
}

}  // namespace

bool sparse_library_available(SparseLibrary library) {
  ceres::SparseLinearAlgebraLibraryType type;
  return ceres::StringToSparseLinearAlgebraLibraryType(kSparseLibraries.name(library), &type) &&
         ceres::IsSparseLinearAlgebraLibraryTypeAvailable(type);
}

std::string solver_problem(const GraphOptimizerConfig& config) {
  ceres::Solver::Options options;
  std::string why;
  if (!to_ceres(config, &options) || !sparse_library_available(config.sparse_library) ||
      options.IsValid(&why))
    return "";
  return "is refused by Ceres: " + why;
}

GraphOptimizer::GraphOptimizer(GraphOptimizerConfig config) : config_(std::move(config)) {
  check_config(config_, "GraphOptimizer");
}

OptimizationStats GraphOptimizer::optimize(SituationalGraph& graph, bool full) {
  if (graph.keyframes().empty()) throw std::invalid_argument("GraphOptimizer: the graph has no keyframes");
  OptimizationStats stats;
  stats.full = full;
  const FreeBlocks free = free_blocks(graph, full, config_.local_window);
  GraphProblem graph_problem(graph, config_);
  add_keyframe_factors(graph_problem, graph, free, config_);
  add_room_factors(graph_problem, graph, free, full, config_);
  ceres::Problem& problem = graph_problem.problem();
  stats.n_variables = graph_problem.num_free();
  stats.n_factors = problem.NumResidualBlocks();
  if (stats.n_variables == 0) return stats;

  const ceres::Solver::Options options = solver_options(config_, full);
  ceres::Solver::Summary summary;
  const auto start = std::chrono::steady_clock::now();
  ceres::Solve(options, &problem, &summary);
  stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!summary.IsSolutionUsable())
    throw std::runtime_error("GraphOptimizer: Ceres failed: " + summary.message);

  stats.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  stats.initial_cost = summary.initial_cost;
  stats.final_cost = summary.final_cost;
  graph_problem.write_back();
  graph.update_retired_poses();
  return stats;
}

}  // namespace tsgraphs::graph
