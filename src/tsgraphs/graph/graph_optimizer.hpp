#pragma once
/// Ceres back-end of the situational graph. Keyframes are SE(3) (translation + unit
/// quaternion), planes have a minimal 3-dof parameterisation (unit normal on S^2 + offset),
/// rooms and floors are 2-D centres. A local solve frees only the last keyframes, the planes
/// they see and the rooms (and their floors) with such a plane, holding the rest fixed, so its
/// cost does not grow with the run; a full solve frees everything but the anchor (after a loop
/// closure). Estimates are warm-started from the graph's values. Retired keyframes
/// (keyframe_retirement.hpp) are no variables: their poses follow their anchors' after a solve.
///
/// Room factors (S-Graphs' room-4-planes and room-2-planes): for each facing pair of a room's
/// walls, the centre's offset from the pair's mid-plane along the pair's normal (for a room with
/// perpendicular pairs, the centre minus the midpoint of the walls); a corridor adds its centre
/// minus the measured cluster centre, along the corridor. Floor factor: the floor's centre minus
/// the mean of its rooms' centres, one residual per floor, so a floor never pulls its rooms
/// together.
#include <string>

#include "tsgraphs/graph/situational_graph.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::graph {

/// Ceres's linear solvers, by Ceres's names.
enum class LinearSolver {
  sparse_normal_cholesky,
  sparse_schur,
  dense_schur,
  iterative_schur,
  dense_qr,
  dense_normal_cholesky,
  cgnr
};
inline const Choices<LinearSolver> kLinearSolvers{
    {LinearSolver::sparse_normal_cholesky, "sparse_normal_cholesky"},
    {LinearSolver::sparse_schur, "sparse_schur"},
    {LinearSolver::dense_schur, "dense_schur"},
    {LinearSolver::iterative_schur, "iterative_schur"},
    {LinearSolver::dense_qr, "dense_qr"},
    {LinearSolver::dense_normal_cholesky, "dense_normal_cholesky"},
    {LinearSolver::cgnr, "cgnr"}};

/// Ceres's sparse back-ends, by Ceres's names (which of them a Ceres build has varies).
enum class SparseLibrary { eigen_sparse, suite_sparse, cx_sparse, accelerate_sparse, no_sparse };
inline const Choices<SparseLibrary> kSparseLibraries{{SparseLibrary::eigen_sparse, "eigen_sparse"},
                                                     {SparseLibrary::suite_sparse, "suite_sparse"},
                                                     {SparseLibrary::cx_sparse, "cx_sparse"},
                                                     {SparseLibrary::accelerate_sparse, "accelerate_sparse"},
                                                     {SparseLibrary::no_sparse, "no_sparse"}};

/// Whether this build of Ceres has `library`.
bool sparse_library_available(SparseLibrary library);
struct GraphOptimizerConfig;
/// Why Ceres refuses the config's solver settings (e.g. a solver without the sparse library it
/// needs); empty when it accepts them or the library is missing (sparse_library's own check).
std::string solver_problem(const GraphOptimizerConfig& config);

struct GraphOptimizerConfig {
  double odometry_sigma_trans = 0.05;
  double odometry_sigma_rot_deg = 0.5;
  double loop_sigma_trans = 0.05;
  double loop_sigma_rot_deg = 0.5;
  double plane_sigma_angle_deg = 1.0;
  double plane_sigma_distance = 0.02;
  double huber_plane = 1.0;
  double huber_loop = 1.0;
  double room_sigma = 0.05;
  double corridor_sigma = 0.05;
  double corridor_along_sigma = 0.5;
  double floor_sigma = 0.5;
  double huber_room = 1.0;
  double huber_floor = 1.0;
  int local_window = 10;
  int max_iterations = 20;
  int max_iterations_full = 50;
  LinearSolver linear_solver = LinearSolver::sparse_normal_cholesky;
  /// Sparse solvers' back-end: Eigen's and CXSparse were the fastest on bench_graph (2000
  /// keyframes), SuiteSparse 10-100% slower there.
  SparseLibrary sparse_library = SparseLibrary::eigen_sparse;
  int num_threads = 1;

  template <class V>
  void visit(V& v) {
    v("odometry_sigma_trans", odometry_sigma_trans, above(0.0, 1e6),
      "m; std of odometry translation between keyframes");
    v("odometry_sigma_rot_deg", odometry_sigma_rot_deg, above(0.0, 1e6),
      "deg; std of odometry rotation between keyframes");
    v("loop_sigma_trans", loop_sigma_trans, above(0.0, 1e6), "m; std of a loop closure's translation");
    v("loop_sigma_rot_deg", loop_sigma_rot_deg, above(0.0, 1e6), "deg; std of a loop closure's rotation");
    v("plane_sigma_angle_deg", plane_sigma_angle_deg, above(0.0, 1e6),
      "deg; std of a measured plane's normal");
    v("plane_sigma_distance", plane_sigma_distance, above(0.0, 1e6), "m; std of a measured plane's offset");
    v("huber_plane", huber_plane, above(0.0, 1e6), "Huber delta on keyframe-plane factors (whitened units)");
    v("huber_loop", huber_loop, above(0.0, 1e6), "Huber delta on loop factors (whitened units)");
    v("room_sigma", room_sigma, above(0.0, 1e6), "m; std of a room centre off its walls' mid-planes");
    v("corridor_sigma", corridor_sigma, above(0.0, 1e6),
      "m; std of a corridor centre from its walls' midline");
    v("corridor_along_sigma", corridor_along_sigma, above(0.0, 1e6),
      "m; std of a corridor centre along it, from the cluster centre");
    v("floor_sigma", floor_sigma, above(0.0, 1e6), "m; std of a floor centre from its rooms' mean centre");
    v("huber_room", huber_room, above(0.0, 1e6), "Huber delta on room and corridor factors (whitened units)");
    v("huber_floor", huber_floor, above(0.0, 1e6), "Huber delta on floor factors (whitened units)");
    v("local_window", local_window, between(1, 100000), "keyframes freed by a local solve");
    v("max_iterations", max_iterations, between(1, 10000), "Ceres iterations per local solve");
    v("max_iterations_full", max_iterations_full, between(1, 10000), "Ceres iterations per full solve");
    v("linear_solver", linear_solver, kLinearSolvers,
      "Ceres's: sparse_normal_cholesky, sparse_schur, dense_schur, iterative_schur, dense_qr, "
      "dense_normal_cholesky or cgnr");
    v("sparse_library", sparse_library, kSparseLibraries,
      "the sparse solvers' back-end: eigen_sparse, suite_sparse, cx_sparse, accelerate_sparse or no_sparse, "
      "one this Ceres has (speeds: docs/benchmarks.md)");
    v("num_threads", num_threads, between(1, 256), "Ceres threads; 1 keeps runs byte-identical");
    v.require(sparse_library_available(sparse_library), "sparse_library",
              "must be one this Ceres was built with");
    const std::string problem = solver_problem(*this);
    v.require(problem.empty(), "linear_solver", problem);
  }
};

/// What one optimisation did (one row of timings.csv; T_PGO is the sum of wall_time_s).
struct OptimizationStats {
  bool full = false;
  double wall_time_s = 0.0;
  int n_variables = 0;  ///< parameter blocks freed
  int n_factors = 0;    ///< residual blocks in the problem
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;
};

class GraphOptimizer {
 public:
  /// Throws std::invalid_argument for a config its visit() refuses (check_config).
  explicit GraphOptimizer(GraphOptimizerConfig config = {});
  /// Optimises `graph` in place (keyframe poses, planes, rooms, floors). With `full` false, only
  /// the last `local_window` keyframes, the planes they observe, the rooms with one of those
  /// planes and the floors of those rooms move. Needs at least one keyframe; throws
  /// std::invalid_argument for an edge to an unknown node, a retired keyframe or a keyframe to
  /// itself, a folded pose edge without its sigmas, a room edge
  /// with a plane count that does not fit its kind, a horizontal plane or a pair whose normals do
  /// not face each other, and std::runtime_error when Ceres gives no usable solution. A measured
  /// plane must share its map plane's sign convention (the factor compares normals, so a flipped
  /// one is an outlier).
  OptimizationStats optimize(SituationalGraph& graph, bool full);
  const GraphOptimizerConfig& config() const { return config_; }

 private:
  GraphOptimizerConfig config_;
};

}  // namespace tsgraphs::graph
