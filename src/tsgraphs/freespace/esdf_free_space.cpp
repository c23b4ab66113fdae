#include "tsgraphs/freespace/esdf_free_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tsgraphs::freespace {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The 8 horizontal neighbour offsets of a slice cell.
constexpr int kNeighbourOffsets[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0},
                                         {1, 0},   {-1, 1}, {0, 1},  {1, 1}};

// Exact 1-D squared distance transform of sampled function f (Felzenszwalb & Huttenlocher,
// lower envelope of parabolas), in place on n values spaced `stride` apart. Infinite samples
// (no occupied voxel) take no part in the envelope; all infinite stays infinite.
void distance_transform_1d(double* f, int n, int stride, std::vector<double>& values, std::vector<int>& v,
                           std::vector<double>& z) {
  values.resize(static_cast<std::size_t>(n));
  v.resize(static_cast<std::size_t>(n));
  z.resize(static_cast<std::size_t>(n) + 1);
  for (int q = 0; q < n; ++q)
    values[static_cast<std::size_t>(q)] = f[static_cast<std::ptrdiff_t>(q) * stride];
  int k = -1;  // index of the rightmost parabola of the envelope
  for (int q = 0; q < n; ++q) {
    const double fq = values[static_cast<std::size_t>(q)];
    if (!std::isfinite(fq)) continue;
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    double s = 0.0;
    for (;;) {
      const int p = v[static_cast<std::size_t>(k)];
      s = ((fq + double(q) * q) - (values[static_cast<std::size_t>(p)] + double(p) * p)) / (2.0 * (q - p));
      // z[0] is -inf, so k never drops below 0.
      if (s <= z[static_cast<std::size_t>(k)]) {
        --k;
      } else {
        break;
      }
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] = s;
    z[static_cast<std::size_t>(k) + 1] = kInf;
  }
  if (k < 0) return;  // nothing occupied on this line: f stays infinite
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<std::size_t>(k) + 1] < q) ++k;
    const int p = v[static_cast<std::size_t>(k)];
    f[static_cast<std::ptrdiff_t>(q) * stride] =
        double(q - p) * (q - p) + values[static_cast<std::size_t>(p)];
  }
}

int voxel_index(double x, double voxel_size) { return static_cast<int>(std::floor(x / voxel_size)); }

}  // namespace

Eigen::Vector3d EsdfSlice::centre(int cell) const {
  const int column = cell % width;
  const int row = cell / width;
  return Eigen::Vector3d((min_i + column + 0.5) * voxel_size, (min_j + row + 0.5) * voxel_size,
                         (layer + 0.5) * voxel_size);
}

int EsdfSlice::cell_at(const Eigen::Vector3d& p) const {
  const int column = voxel_index(p.x(), voxel_size) - min_i;
  const int row = voxel_index(p.y(), voxel_size) - min_j;
  if (column < 0 || row < 0 || column >= width || row >= height) return -1;
  return row * width + column;
}

EsdfFreeSpace esdf_free_space(const std::vector<Eigen::Vector3d>& occupied, double floor_height,
                              const Eigen::Vector3d& robot, const EsdfFreeSpaceConfig& config) {
  if (!(config.voxel_size > 0.0) || !(config.max_distance > 0.0))
    throw std::invalid_argument("esdf_free_space: voxel_size > 0 and max_distance > 0 required");
  const double vs = config.voxel_size;

  EsdfFreeSpace out;
  EsdfSlice& slice = out.slice;
  slice.voxel_size = vs;
  slice.layer = voxel_index(floor_height + config.slice_height, vs);
  // Layers farther than this from the slice are beyond max_distance whatever their column.
  const int reach = static_cast<int>(std::ceil(config.max_distance / vs));

  struct Occupied {
    int i, j, dk;
  };
  std::vector<Occupied> voxels;
  int min_i = std::numeric_limits<int>::max(), min_j = min_i;
  int max_i = std::numeric_limits<int>::min(), max_j = max_i;
  for (const auto& p : occupied) {
    if (!p.allFinite()) continue;
    const int dk = voxel_index(p.z(), vs) - slice.layer;
    if (std::abs(dk) > reach) continue;
    const Occupied o{voxel_index(p.x(), vs), voxel_index(p.y(), vs), dk};
    voxels.push_back(o);
    min_i = std::min(min_i, o.i);
    min_j = std::min(min_j, o.j);
    max_i = std::max(max_i, o.i);
    max_j = std::max(max_j, o.j);
  }
  if (voxels.empty()) return out;

  slice.min_i = min_i;
  slice.min_j = min_j;
  slice.width = max_i - min_i + 1;
  slice.height = max_j - min_j + 1;
  const int cells = slice.width * slice.height;

  // Squared distances in voxel units: first vertical, to the nearest occupied voxel of each
  // column; then the exact transform along rows and along columns adds the horizontal part.
  std::vector<double>& d = slice.distance;
  d.assign(static_cast<std::size_t>(cells), kInf);
  for (const auto& o : voxels) {
    double& cell = d[static_cast<std::size_t>((o.j - min_j) * slice.width + (o.i - min_i))];
    cell = std::min(cell, double(o.dk) * o.dk);
  }
  std::vector<double> values, z;
  std::vector<int> v;
  for (int row = 0; row < slice.height; ++row)
    distance_transform_1d(d.data() + static_cast<std::ptrdiff_t>(row) * slice.width, slice.width, 1, values,
                          v, z);
  for (int column = 0; column < slice.width; ++column)
    distance_transform_1d(d.data() + column, slice.height, slice.width, values, v, z);
  for (double& x : d) x = std::min(std::sqrt(x) * vs, config.max_distance);

  std::vector<Eigen::Vector3d> positions(static_cast<std::size_t>(cells));
  std::vector<bool> kept(static_cast<std::size_t>(cells));
  for (int c = 0; c < cells; ++c) {
    positions[static_cast<std::size_t>(c)] = slice.centre(c);
    kept[static_cast<std::size_t>(c)] = d[static_cast<std::size_t>(c)] > config.min_free_distance;
  }
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(cells));
  for (int row = 0; row < slice.height; ++row) {
    for (int column = 0; column < slice.width; ++column) {
      const int c = row * slice.width + column;
      if (!kept[static_cast<std::size_t>(c)]) continue;
      for (const auto& o : kNeighbourOffsets) {
        const int nc = column + o[0], nr = row + o[1];
        if (nc < 0 || nr < 0 || nc >= slice.width || nr >= slice.height) continue;
        const int n = nr * slice.width + nc;
        if (kept[static_cast<std::size_t>(n)]) neighbours[static_cast<std::size_t>(c)].push_back(n);
      }
    }
  }
  out.free_space = connected_components(positions, kept, neighbours);
  identify_robot_cluster(out.free_space, positions, robot, config.robot_radius,
                         config.robot_height_tolerance);
  compute_robot_path_distance(out.free_space, positions, kept, neighbours);
  return out;
}

}  // namespace tsgraphs::freespace
