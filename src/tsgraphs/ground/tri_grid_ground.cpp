#include "tsgraphs/ground/tri_grid_ground.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace tsgraphs::ground {

namespace {

/// Below this normal z a plane is (near) vertical and has no height to speak of.
constexpr float kMinNormalZ = 1e-3f;
/// Points needed for a plane.
constexpr std::size_t kMinPlanePoints = 3;

/// Centroid offsets of the triangles from their cell's centre, in cells (a triangle of a
/// unit cell with apex at the centre has its centroid a third of a cell from it).
constexpr double kCentroidOffset = 1.0 / 3.0;

/// Height at (x, y) of the plane through `point` with `normal`.
float plane_height(const Eigen::Vector3f& point, const Eigen::Vector3f& normal, float x, float y) {
  if (normal.z() < kMinNormalZ) return point.z();
  return point.z() - (normal.x() * (x - point.x()) + normal.y() * (y - point.y())) / normal.z();
}

struct Plane {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

/// PCA plane of `pts`; `prior_spread` is added as a standard deviation to both horizontal
/// directions, so points on one scan line (a line has no plane of its own) give the least
/// tilted plane through them, while a patch with real extent keeps its own slope.
Plane fit_plane(const std::vector<Eigen::Vector3f>& pts, double prior_spread) {
  const Eigen::Vector3d origin = pts.front().cast<double>();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3f& p : pts) {
    const Eigen::Vector3d q = p.cast<double>() - origin;
    sum += q;
    sum_sq.noalias() += q * q.transpose();
  }
  const double n = static_cast<double>(pts.size());
  const Eigen::Vector3d mean = sum / n;
  Eigen::Matrix3d cov = sum_sq / n - mean * mean.transpose();
  cov(0, 0) += prior_spread * prior_spread;
  cov(1, 1) += prior_spread * prior_spread;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(cov);
  Plane plane;
  plane.mean = mean + origin;
  plane.normal = solver.eigenvectors().col(0).normalized();  // smallest eigenvalue first
  if (plane.normal.z() < 0.0) plane.normal = -plane.normal;
  return plane;
}

/// Standard deviation of `pts` across their main horizontal direction (0 for a line).
double horizontal_spread(const std::vector<Eigen::Vector3f>& pts) {
  if (pts.size() < 2) return 0.0;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d sum_sq = Eigen::Matrix2d::Zero();
  const Eigen::Vector2d origin = pts.front().head<2>().cast<double>();
  for (const Eigen::Vector3f& p : pts) {
    const Eigen::Vector2d q = p.head<2>().cast<double>() - origin;
    sum += q;
    sum_sq.noalias() += q * q.transpose();
  }
  const double n = static_cast<double>(pts.size());
  const Eigen::Matrix2d cov = sum_sq / n - (sum / n) * (sum / n).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver;
  solver.computeDirect(cov, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(solver.eigenvalues()(0), 0.0));
}

/// Scratch buffers reused from node to node.
struct NodeScratch {
  std::vector<Eigen::Vector3f> sorted;   ///< the node's points, by height
  std::vector<Eigen::Vector3f> surface;  ///< the lowest point of each column, by height
  std::vector<Eigen::Vector3f> subset;   ///< seeds, then the inliers of each round
  std::vector<int> column_stamp;         ///< per column of the cell: 1 + the last node that used it
};

/// The lowest point of each fit_column-wide column of the node's cell, by height: a wall (or a
/// box side) standing in the node then adds only its foot, so it cannot tip the floor's plane.
void lowest_per_column(const TriGrid& grid, int node_index, double column, NodeScratch* scratch) {
  const int per_side = std::max(1, static_cast<int>(std::ceil(grid.resolution() / column)));
  std::vector<int>& stamp = scratch->column_stamp;
  if (stamp.size() != static_cast<std::size_t>(per_side) * per_side) stamp.assign(per_side * per_side, 0);
  const Eigen::Vector2d corner = grid.cell_corner(node_index);
  scratch->surface.clear();
  for (const Eigen::Vector3f& p : scratch->sorted) {
    const int u = std::clamp(static_cast<int>((p.x() - corner.x()) / column), 0, per_side - 1);
    const int v = std::clamp(static_cast<int>((p.y() - corner.y()) / column), 0, per_side - 1);
    int& s = stamp[u * per_side + v];
    if (s == node_index + 1) continue;
    s = node_index + 1;
    scratch->surface.push_back(p);
  }
}

/// The node's points, by height.
void points_by_height(const TriGridField& field, int node_index, std::vector<Eigen::Vector3f>* out) {
  std::vector<Eigen::Vector3f>& sorted = *out;
  sorted.clear();
  for (int k = field.node_begin[node_index]; k < field.node_begin[node_index + 1]; ++k)
    sorted.push_back(field.points[field.node_points[k]]);
  std::sort(sorted.begin(), sorted.end(),
            [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) { return a.z() < b.z(); });
}

/// Robust lowest level of `surface` (by height, not empty): the lowest point with num_lpr
/// points (itself included) within th_outlier above it. Lone returns below it (multipath,
/// noise) do not set the level.
float robust_lowest(const std::vector<Eigen::Vector3f>& surface, const GroundConfig& config) {
  const std::size_t m = surface.size();
  const std::size_t support = std::min<std::size_t>(std::max(config.num_lpr, 1), m);
  std::size_t low = 0;
  for (std::size_t i = 0; i + support <= m; ++i) {
    if (surface[i + support - 1].z() - surface[i].z() <= config.th_outlier) {
      low = i;
      break;
    }
  }
  return surface[low].z();
}

/// Lowest-point representative: the mean height of the num_lpr lowest points from `first`.
double lowest_point_representative(const std::vector<Eigen::Vector3f>& surface, std::size_t first,
                                   const GroundConfig& config) {
  const std::size_t lpr_end =
      std::min(surface.size(), first + static_cast<std::size_t>(std::max(config.num_lpr, 1)));
  double lpr = 0.0;
  for (std::size_t i = first; i < lpr_end; ++i) lpr += surface[i].z();
  lpr /= static_cast<double>(lpr_end - first);
  return lpr;
}

/// PCA rounds, starting from the level plane through the LPR: each fits the seeds
/// surface[first, seeds_end) within th_dist of the current plane (both sides). Seeding from the
/// lowest level keeps a wall standing in the node from tipping the plane up: only its foot is
/// near that level. False when no round had enough points; `subset` holds the last inliers.
bool fit_seed_plane(const std::vector<Eigen::Vector3f>& surface, std::size_t first, std::size_t seeds_end,
                    double lpr, const GroundConfig& config, std::vector<Eigen::Vector3f>* subset,
                    Plane* out) {
  const float band = static_cast<float>(config.th_dist);
  bool fitted = false;
  Plane plane;
  plane.mean = Eigen::Vector3d(0.0, 0.0, lpr);
  for (int it = 0; it < config.num_iter; ++it) {
    const Eigen::Vector3f n = plane.normal.cast<float>();
    const Eigen::Vector3f c = plane.mean.cast<float>();
    subset->clear();
    for (std::size_t i = first; i < seeds_end; ++i)
      if (std::abs(n.dot(surface[i] - c)) < band) subset->push_back(surface[i]);
    if (subset->size() < kMinPlanePoints) break;
    plane = fit_plane(*subset, config.plane_prior_spread);
    fitted = true;
  }
  *out = plane;
  return fitted;
}

/// Whether every point of the seeds' height range [floor_z, lpr + th_seeds), not only the
/// column-lowest ones, stands up as a steep face (`subset` is scratch).
bool seeds_stand_up(const std::vector<Eigen::Vector3f>& sorted, float floor_z, double lpr,
                    const GroundConfig& config, std::vector<Eigen::Vector3f>* subset) {
  subset->clear();
  for (const Eigen::Vector3f& p : sorted)
    if (p.z() >= floor_z && p.z() < lpr + config.th_seeds) subset->push_back(p);
  return fit_plane(*subset, config.plane_prior_spread).normal.z() < config.th_normal;
}

/// The points of surface[first, end) within th_dist of the plane through `mean` with `normal`.
int count_inliers(const std::vector<Eigen::Vector3f>& surface, std::size_t first,
                  const Eigen::Vector3f& normal, const Eigen::Vector3f& mean, double th_dist) {
  int inliers = 0;
  for (std::size_t i = first; i < surface.size(); ++i)
    if (std::abs(normal.dot(surface[i] - mean)) <= th_dist) ++inliers;
  return inliers;
}

void model_node(const TriGridField& field, int node_index, const GroundConfig& config, NodeScratch* scratch,
                TriGridNode* node) {
  points_by_height(field, node_index, &scratch->sorted);
  const bool enough_points = static_cast<int>(scratch->sorted.size()) >= config.num_min_pts;
  lowest_per_column(field.grid, node_index, config.fit_column, scratch);
  const std::vector<Eigen::Vector3f>& surface = scratch->surface;
  const std::size_t m = surface.size();

  node->lowest = robust_lowest(surface, config);
  const float floor_z = node->lowest - static_cast<float>(config.th_outlier);
  std::size_t first = 0;  // points below lowest - th_outlier are rejected
  while (first < m && surface[first].z() < floor_z) ++first;

  if (!enough_points) {
    node->state = NodeState::kUnknown;
    node->centre.z() = node->lowest;
    return;
  }
  node->state = NodeState::kModelled;

  const double lpr = lowest_point_representative(surface, first, config);
  std::size_t seeds_end = first;
  while (seeds_end < m && surface[seeds_end].z() < lpr + config.th_seeds) ++seeds_end;
  std::vector<Eigen::Vector3f>& subset = scratch->subset;
  Plane plane;
  if (!fit_seed_plane(surface, first, seeds_end, lpr, config, &subset, &plane)) {
    node->centre.z() = node->lowest;
    return;
  }
  node->normal = plane.normal.cast<float>();
  const Eigen::Vector3f mean = plane.mean.cast<float>();
  node->ground_like = plane.normal.z() >= config.th_normal;
  // Inliers on one line (a scan ring) get their tilt from the prior, and the foot of a wall
  // or of a void's edge seen from above is such a line too: it is a face's foot when the
  // seeds above the line stand up as a steep face.
  if (node->ground_like && horizontal_spread(subset) < config.plane_prior_spread)
    node->face_foot = seeds_stand_up(scratch->sorted, floor_z, lpr, config, &subset);
  node->num_inliers = count_inliers(surface, first, node->normal, mean, config.th_dist);
  // The plane's reference point moves from the mean to the triangle's centroid.
  node->centre.z() = plane_height(mean, node->normal, node->centre.x(), node->centre.y());
}

}  // namespace

TriGrid::TriGrid(double resolution, double half_extent) : resolution_(resolution) {
  cells_ = std::max(1, static_cast<int>(std::ceil(2.0 * half_extent / resolution)));
  origin_ = -0.5 * cells_ * resolution;
}

int TriGrid::node(int row, int column, int triangle) const {
  if (row < 0 || column < 0 || row >= cells_ || column >= cells_) return -1;
  return (row * cells_ + column) * 4 + triangle;
}

int TriGrid::node_at(double x, double y) const {
  const double u = (x - origin_) / resolution_;
  const double v = (y - origin_) / resolution_;
  if (!(u >= 0.0 && v >= 0.0 && u < cells_ && v < cells_)) return -1;
  const int r = static_cast<int>(u);
  const int c = static_cast<int>(v);
  const double dx = u - r - 0.5;  // offset from the cell's centre, in cells
  const double dy = v - c - 0.5;
  int tri;
  if (std::abs(dx) >= std::abs(dy)) {
    tri = dx >= 0.0 ? kPlusX : kMinusX;
  } else {
    tri = dy >= 0.0 ? kPlusY : kMinusY;
  }
  return (r * cells_ + c) * 4 + tri;
}

Eigen::Vector2d TriGrid::cell_corner(int node) const {
  return Eigen::Vector2d(origin_ + row(node) * resolution_, origin_ + column(node) * resolution_);
}

Eigen::Vector2d TriGrid::centroid(int node) const {
  Eigen::Vector2d p(origin_ + (row(node) + 0.5) * resolution_, origin_ + (column(node) + 0.5) * resolution_);
  const double off = kCentroidOffset * resolution_;
  switch (triangle(node)) {
    case kPlusX:
      p.x() += off;
      break;
    case kPlusY:
      p.y() += off;
      break;
    case kMinusX:
      p.x() -= off;
      break;
    default:
      p.y() -= off;
      break;
  }
  return p;
}

int TriGrid::adjacent(int node, std::array<int, 3>* out) const {
  const int r = row(node), c = column(node), t = triangle(node);
  const int base = node - t;
  // The two triangles of the same cell that share a diagonal half with t.
  (*out)[0] = base + (t + 1) % 4;
  (*out)[1] = base + (t + 3) % 4;
  int across = -1;
  switch (t) {
    case kPlusX:
      across = this->node(r + 1, c, kMinusX);
      break;
    case kPlusY:
      across = this->node(r, c + 1, kMinusY);
      break;
    case kMinusX:
      across = this->node(r - 1, c, kPlusX);
      break;
    default:
      across = this->node(r, c - 1, kPlusY);
      break;
  }
  if (across < 0) return 2;
  (*out)[2] = across;
  return 3;
}

float TriGridNode::height_at(float x, float y) const { return plane_height(centre, normal, x, y); }

Eigen::Matrix3d level_rotation(const Eigen::Matrix3d& R_map_sensor) {
  const double yaw = std::atan2(R_map_sensor(1, 0), R_map_sensor(0, 0));
  return Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_map_sensor;
}

void build_tri_grid_field(const PointCloud& cloud, const Eigen::Matrix3d& R_level_sensor,
                          const GroundConfig& config, TriGridField* out) {
  TriGridField& field = *out;  // every buffer is refilled; their capacity is kept
  field.grid = TriGrid(config.resolution, config.max_range);
  const int num_nodes = field.grid.num_nodes();
  const std::size_t n = cloud.size();
  const Eigen::Matrix3f R = R_level_sensor.cast<float>();
  const double min_sq = config.min_range * config.min_range;
  const double max_sq = config.max_range * config.max_range;

  field.points.resize(n);
  field.point_node.assign(n, -1);
  field.node_begin.assign(num_nodes + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f p = R * cloud.points[i];
    field.points[i] = p;
    if (!p.allFinite()) continue;
    const double r_sq = static_cast<double>(p.x()) * p.x() + static_cast<double>(p.y()) * p.y();
    if (r_sq < min_sq || r_sq > max_sq) continue;
    const int node = field.grid.node_at(p.x(), p.y());
    field.point_node[i] = node;
    if (node >= 0) ++field.node_begin[node + 1];
  }
  for (int k = 0; k < num_nodes; ++k) field.node_begin[k + 1] += field.node_begin[k];
  field.node_points.resize(field.node_begin[num_nodes]);
  {
    std::vector<int> fill(field.node_begin.begin(), field.node_begin.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      if (field.point_node[i] >= 0) field.node_points[fill[field.point_node[i]]++] = static_cast<int>(i);
  }

  field.nodes.assign(num_nodes, TriGridNode{});
  NodeScratch scratch;
  for (int k = 0; k < num_nodes; ++k) {
    TriGridNode& node = field.nodes[k];
    const Eigen::Vector2d c = field.grid.centroid(k);
    node.centre = Eigen::Vector3f(static_cast<float>(c.x()), static_cast<float>(c.y()), 0.0f);
    node.num_points = field.node_begin[k + 1] - field.node_begin[k];
    if (node.num_points == 0) continue;
    model_node(field, k, config, &scratch, &node);
  }
}

TriGridField build_tri_grid_field(const PointCloud& cloud, const Eigen::Matrix3d& R_level_sensor,
                                  const GroundConfig& config) {
  TriGridField field;
  build_tri_grid_field(cloud, R_level_sensor, config, &field);
  return field;
}

}  // namespace tsgraphs::ground
