#include "tsgraphs/ground/ground_slope.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tsgraphs::ground {

namespace {

// The sums kept per cell: count; x, y, z; xx, xy, yy, xz, yz (positions relative to the
// grid's corner); the normals' height gradients gx, gy.
enum Sum { kN, kX, kY, kZ, kXX, kXY, kYY, kXZ, kYZ, kGX, kGY, kSums };

// Nodes fix a plane when their spread across their main direction is at least this share of
// the spread along it (a ring's arc, a single row of nodes fix none).
constexpr double kMinSpreadRatio = 0.1;

}  // namespace

std::vector<double> ground_slopes(const std::vector<Eigen::Vector3d>& positions,
                                  const std::vector<Eigen::Vector3d>& normals, double cell, double radius) {
  if (!(cell > 0.0) || !std::isfinite(cell)) throw std::invalid_argument("ground_slopes: cell must be > 0");
  if (!(radius >= 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("ground_slopes: radius must be >= 0");
  if (positions.size() != normals.size())
    throw std::invalid_argument("ground_slopes: one normal per position");
  std::vector<double> slopes(positions.size(), 0.0);
  const auto usable = [&](std::size_t i) {
    return positions[i].allFinite() && normals[i].allFinite() && std::abs(normals[i].z()) > 1e-6;
  };
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!usable(i)) continue;
    lo = lo.cwiseMin(positions[i]);
    hi = hi.cwiseMax(positions[i]);
  }
  if (!(lo.x() <= hi.x())) return slopes;
  const int cols = static_cast<int>(std::floor((hi.x() - lo.x()) / cell)) + 1;
  const int rows = static_cast<int>(std::floor((hi.y() - lo.y()) / cell)) + 1;
  const auto cell_of = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2i(std::clamp(static_cast<int>(std::floor((p.x() - lo.x()) / cell)), 0, cols - 1),
                           std::clamp(static_cast<int>(std::floor((p.y() - lo.y()) / cell)), 0, rows - 1));
  };
  // Summed-area tables, one row and column of zeros in front.
  const std::size_t stride = static_cast<std::size_t>(cols) + 1;
  std::vector<std::array<double, kSums>> table(stride * (static_cast<std::size_t>(rows) + 1));
  for (auto& t : table) t.fill(0.0);
  const auto at = [&](int c, int r) {
    return static_cast<std::size_t>(r) * stride + static_cast<std::size_t>(c);
  };
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!usable(i)) continue;
    const Eigen::Vector3d p = positions[i] - lo;
    const Eigen::Vector3d& n = normals[i];
    const Eigen::Vector2i c = cell_of(positions[i]);
    std::array<double, kSums>& s = table[at(c.x() + 1, c.y() + 1)];
    s[kN] += 1.0;
    s[kX] += p.x();
    s[kY] += p.y();
    s[kZ] += p.z();
    s[kXX] += p.x() * p.x();
    s[kXY] += p.x() * p.y();
    s[kYY] += p.y() * p.y();
    s[kXZ] += p.x() * p.z();
    s[kYZ] += p.y() * p.z();
    s[kGX] -= n.x() / n.z();
    s[kGY] -= n.y() / n.z();
  }
  for (int r = 1; r <= rows; ++r)
    for (int c = 1; c <= cols; ++c)
      for (int k = 0; k < kSums; ++k)
        table[at(c, r)][k] += table[at(c - 1, r)][k] + table[at(c, r - 1)][k] - table[at(c - 1, r - 1)][k];
  const int reach = static_cast<int>(std::floor(radius / cell + 0.5));
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!positions[i].allFinite()) continue;
    const Eigen::Vector2i c = cell_of(positions[i]);
    const int c0 = std::max(c.x() - reach, 0), c1 = std::min(c.x() + reach, cols - 1) + 1;
    const int r0 = std::max(c.y() - reach, 0), r1 = std::min(c.y() + reach, rows - 1) + 1;
    std::array<double, kSums> s;
    for (int k = 0; k < kSums; ++k)
      s[k] = table[at(c1, r1)][k] - table[at(c0, r1)][k] - table[at(c1, r0)][k] + table[at(c0, r0)][k];
    const double m = s[kN];
    if (!(m > 0.0)) continue;
    const double tilt = std::hypot(s[kGX], s[kGY]) / m;
    // The plane z = a + g . (x, y) through the window's nodes, from their centred moments.
    const double sxx = s[kXX] - s[kX] * s[kX] / m, sxy = s[kXY] - s[kX] * s[kY] / m,
                 syy = s[kYY] - s[kY] * s[kY] / m;
    const double sxz = s[kXZ] - s[kX] * s[kZ] / m, syz = s[kYZ] - s[kY] * s[kZ] / m;
    const double det = sxx * syy - sxy * sxy;
    // det / trace^2 is about the square of the spreads' ratio.
    if (!(det > kMinSpreadRatio * kMinSpreadRatio * (sxx + syy) * (sxx + syy))) continue;
    const double gx = (syy * sxz - sxy * syz) / det, gy = (sxx * syz - sxy * sxz) / det;
    slopes[i] = std::min(tilt, std::hypot(gx, gy));
  }
  return slopes;
}

}  // namespace tsgraphs::ground
