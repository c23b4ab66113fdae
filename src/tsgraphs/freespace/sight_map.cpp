#include "tsgraphs/freespace/sight_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tsgraphs::freespace {
namespace {

std::uint64_t tile_key(long tc, long tr) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(tc)) << 32) | static_cast<std::uint32_t>(tr);
}

void bump(std::uint16_t& count) {
  if (count < std::numeric_limits<std::uint16_t>::max()) ++count;
}

}  // namespace

SightMap::SightMap(double floor_z, const SightMapConfig& config)
    : floor_z_(floor_z),
      config_(config),
      lo_(Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity())),
      hi_(-lo_) {
  if (!(config.cell > 0.0)) throw std::invalid_argument("SightMapConfig: cell must be > 0");
  if (!(config.floor_step >= 0.0)) throw std::invalid_argument("SightMapConfig: floor_step must be >= 0");
  if (!(config.headroom > config.floor_step)) throw std::invalid_argument("SightMapConfig: headroom must be above floor_step");
  if (!(config.max_range > 0.0)) throw std::invalid_argument("SightMapConfig: max_range must be > 0");
}

void SightMap::mark(long c, long r, Mark m) {
  Tile& t = tiles_[tile_key(c >> kTileBits, r >> kTileBits)];
  const std::size_t i = static_cast<std::size_t>((r & (kTileSide - 1)) * kTileSide + (c & (kTileSide - 1)));
  if (m == Mark::hit) {
    t.hit[i] = 1;
    return;
  }
  bump(m == Mark::passed ? t.passed[i] : m == Mark::floor ? t.floor[i] : t.below[i]);
}

const SightMap::Tile* SightMap::tile(long tc, long tr) const {
  const auto it = tiles_.find(tile_key(tc, tr));
  return it == tiles_.end() ? nullptr : &it->second;
}

void SightMap::add_scan(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points) {
  const double res = config_.cell;
  const double low = floor_z_ - config_.floor_step;
  const double top = floor_z_ + config_.headroom;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector2d d = (p - sensor).head<2>();
    const double length = d.norm();
    if (!(length <= config_.max_range) || !p.allFinite()) continue;
    // Cells along the ray's ground track (Amanatides and Woo), each judged at the ray's height
    // where it enters the cell.
    const Eigen::Vector2d a = sensor.head<2>() / res;
    long c = static_cast<long>(std::floor(a.x())), r = static_cast<long>(std::floor(a.y()));
    const long c_end = static_cast<long>(std::floor(p.x() / res)), r_end = static_cast<long>(std::floor(p.y() / res));
    const int step_c = d.x() > 0 ? 1 : -1, step_r = d.y() > 0 ? 1 : -1;
    const double inv_x = d.x() != 0.0 ? std::abs(res / d.x()) : std::numeric_limits<double>::infinity();
    const double inv_y = d.y() != 0.0 ? std::abs(res / d.y()) : std::numeric_limits<double>::infinity();
    double t_x = d.x() != 0.0 ? ((step_c > 0 ? c + 1 - a.x() : a.x() - c) * inv_x) : inv_x;
    double t_y = d.y() != 0.0 ? ((step_r > 0 ? r + 1 - a.y() : a.y() - r) * inv_y) : inv_y;
    double t = 0.0;
    while (c != c_end || r != r_end) {
      if (t > 1.0) break;
      const double z = sensor.z() + t * (p.z() - sensor.z());
      if (z < low) mark(c, r, Mark::below);
      else if (z <= top) mark(c, r, Mark::passed);
      if (t_x < t_y) {
        t = t_x;
        t_x += inv_x;
        c += step_c;
      } else {
        t = t_y;
        t_y += inv_y;
        r += step_r;
      }
    }
    if (std::abs(p.z() - floor_z_) <= config_.floor_step) mark(c_end, r_end, Mark::floor);
    else if (p.z() < low) mark(c_end, r_end, Mark::below);
    else mark(c_end, r_end, Mark::hit);
    lo_ = lo_.cwiseMin(sensor.head<2>()).cwiseMin(p.head<2>());
    hi_ = hi_.cwiseMax(sensor.head<2>()).cwiseMax(p.head<2>());
  }
}

const SightMap::Tile* SightMap::cell(const GridFrame& f, int col, int row, std::size_t* i) const {
  const Eigen::Vector2d q = f.center(col, row);
  const long c = static_cast<long>(std::floor(q.x() / config_.cell)), r = static_cast<long>(std::floor(q.y() / config_.cell));
  *i = static_cast<std::size_t>((r & (kTileSide - 1)) * kTileSide + (c & (kTileSide - 1)));
  return tile(c >> kTileBits, r >> kTileBits);
}

std::vector<std::uint8_t> SightMap::open_cells(const GridFrame& f) const {
  std::vector<std::uint8_t> open(f.size(), 0);
  for (int row = 0; row < f.rows; ++row) {
    for (int col = 0; col < f.cols; ++col) {
      std::size_t i;
      const Tile* t = cell(f, col, row, &i);
      if (t == nullptr) continue;
      const bool seen = t->passed[i] > 0 || t->floor[i] > 0;
      open[f.index(col, row)] = seen && t->below[i] <= t->floor[i] ? 1 : 0;
    }
  }
  return open;
}

std::vector<std::uint8_t> SightMap::known_cells(const GridFrame& f) const {
  std::vector<std::uint8_t> known(f.size(), 0);
  for (int row = 0; row < f.rows; ++row) {
    for (int col = 0; col < f.cols; ++col) {
      std::size_t i;
      const Tile* t = cell(f, col, row, &i);
      if (t != nullptr && (t->passed[i] > 0 || t->floor[i] > 0 || t->below[i] > 0 || t->hit[i] > 0))
        known[f.index(col, row)] = 1;
    }
  }
  return known;
}

}  // namespace tsgraphs::freespace
