#include "tsgraphs/freespace/sight_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tsgraphs/core/voxel_key.hpp"

namespace tsgraphs::freespace {
namespace {

void bump(std::uint32_t& count, int delta) {
  if (delta > 0)
    ++count;
  else if (count > 0)
    --count;
}

}  // namespace

SightMap::SightMap(double floor_z, const SightMapConfig& config)
    : floor_z_(floor_z),
      config_(config),
      lo_(Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity())),
      hi_(-lo_) {
  check_config(config, "SightMapConfig");  // the keys; floor_step and headroom come from the free space's
  if (!(config.floor_step >= 0.0)) throw std::invalid_argument("SightMapConfig: floor_step must be >= 0");
  if (!(config.headroom > config.floor_step))
    throw std::invalid_argument("SightMapConfig: headroom must be above floor_step");
}

std::size_t SightMap::index_in_tile(long c, long r) {
  return static_cast<std::size_t>((r & (kTileSide - 1)) * kTileSide + (c & (kTileSide - 1)));
}

SightMap::Tile& SightMap::tile_miss(std::uint64_t key) {
  last_.tile = &tiles_[key];
  last_.key = key;
  return *last_.tile;
}

inline SightMap::Tile& SightMap::tile_at(long c, long r, std::size_t* i) {
  *i = index_in_tile(c, r);
  // A ray walks many cells of one tile in a row: look the tile up only when it changes (the
  // map's nodes stay put when it grows).
  const std::uint64_t key = cell_key(c >> kTileBits, r >> kTileBits);
  if (last_.tile != nullptr && key == last_.key) return *last_.tile;
  return tile_miss(key);
}

std::uint8_t SightMap::height_code(double z) const {
  return static_cast<std::uint8_t>(std::clamp(std::ceil((z - floor_z_) / kLowStep), 1.0, 255.0));
}

void SightMap::mark(long c, long r, Mark m, int delta, double z) {
  std::size_t i;
  Tile& t = tile_at(c, r, &i);
  if (m == Mark::hit) {
    bump(t.hit[i], delta);
    if (t.hit[i] == 0) {
      t.low[i] = 0;
    } else if (delta > 0) {
      const std::uint8_t code = height_code(z);
      if (t.low[i] == 0 || code < t.low[i]) t.low[i] = code;
    }
    return;
  }
  bump(m == Mark::passed ? t.passed[i] : m == Mark::floor ? t.floor[i] : t.below[i], delta);
}

const SightMap::Tile* SightMap::tile(long tc, long tr) const {
  const auto it = tiles_.find(cell_key(tc, tr));
  return it == tiles_.end() ? nullptr : &it->second;
}

void SightMap::add_scan(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points) {
  trace(sensor, points, +1);
}

void SightMap::remove_scan(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points) {
  trace(sensor, points, -1);
}

void SightMap::trace(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points, int delta) {
  const double res = config_.cell;
  const double low = floor_z_ - config_.floor_step;
  // A ray that is lower still than a slab's thickness (taken as another floor_step) is under
  // the floor, in the storey below: it says nothing more of this level's cells above it.
  const double under = low - config_.floor_step;
  const double top = floor_z_ + config_.headroom;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector2d d = (p - sensor).head<2>();
    const double length = d.norm();
    if (!(length <= config_.max_range) || !p.allFinite()) continue;
    // Cells along the ray's ground track (Amanatides and Woo), each judged at the ray's height
    // where it enters the cell.
    const Eigen::Vector2d a = sensor.head<2>() / res;
    long c = static_cast<long>(std::floor(a.x())), r = static_cast<long>(std::floor(a.y()));
    const long c_end = static_cast<long>(std::floor(p.x() / res)),
               r_end = static_cast<long>(std::floor(p.y() / res));
    const int step_c = d.x() > 0 ? 1 : -1, step_r = d.y() > 0 ? 1 : -1;
    const double inv_x = d.x() != 0.0 ? std::abs(res / d.x()) : std::numeric_limits<double>::infinity();
    const double inv_y = d.y() != 0.0 ? std::abs(res / d.y()) : std::numeric_limits<double>::infinity();
    double t_x = d.x() != 0.0 ? ((step_c > 0 ? c + 1 - a.x() : a.x() - c) * inv_x) : inv_x;
    double t_y = d.y() != 0.0 ? ((step_r > 0 ? r + 1 - a.y() : a.y() - r) * inv_y) : inv_y;
    double t = 0.0;
    const bool rising = p.z() > sensor.z();
    while (c != c_end || r != r_end) {
      if (t > 1.0) break;
      const double z = sensor.z() + t * (p.z() - sensor.z());
      if (z < under) break;
      if (z > top && rising) break;  // above walking height, and only higher on
      std::size_t i;
      Tile& cell = tile_at(c, r, &i);
      if (z < low)
        bump(cell.below[i], delta);
      else if (z <= top)
        bump(cell.passed[i], delta);
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
    if (std::abs(p.z() - floor_z_) <= config_.floor_step)
      mark(c_end, r_end, Mark::floor, delta);
    else if (p.z() >= under && p.z() < low)
      mark(c_end, r_end, Mark::below, delta);
    else if (p.z() >= low)
      mark(c_end, r_end, Mark::hit, delta, p.z());
    lo_ = lo_.cwiseMin(sensor.head<2>()).cwiseMin(p.head<2>());
    hi_ = hi_.cwiseMax(sensor.head<2>()).cwiseMax(p.head<2>());
  }
}

const SightMap::Tile* SightMap::cell(const GridFrame& f, int col, int row, std::size_t* i) const {
  const Eigen::Vector2d q = f.center(col, row);
  const long c = static_cast<long>(std::floor(q.x() / config_.cell)),
             r = static_cast<long>(std::floor(q.y() / config_.cell));
  *i = index_in_tile(c, r);
  return tile(c >> kTileBits, r >> kTileBits);
}

template <class Test>
std::vector<std::uint8_t> SightMap::cells_where(const GridFrame& f, Test test) const {
  std::vector<std::uint8_t> out(f.size(), 0);
  for (int row = 0; row < f.rows; ++row) {
    for (int col = 0; col < f.cols; ++col) {
      std::size_t i;
      const Tile* t = cell(f, col, row, &i);
      if (t != nullptr && test(*t, i)) out[f.index(col, row)] = 1;
    }
  }
  return out;
}

bool SightMap::return_near(const Eigen::Vector2d& xy, double z) const {
  const long c = static_cast<long>(std::floor(xy.x() / config_.cell)),
             r = static_cast<long>(std::floor(xy.y() / config_.cell));
  const std::uint8_t code = height_code(z);
  for (long dr = -1; dr <= 1; ++dr) {
    for (long dc = -1; dc <= 1; ++dc) {
      const Tile* t = tile((c + dc) >> kTileBits, (r + dr) >> kTileBits);
      const std::size_t i = index_in_tile(c + dc, r + dr);
      if (t != nullptr && t->low[i] > 0 && t->low[i] <= code) return true;
    }
  }
  return false;
}

std::vector<std::uint8_t> SightMap::open_cells(const GridFrame& f) const {
  return cells_where(f, [](const Tile& t, std::size_t i) {
    return (t.passed[i] > 0 || t.floor[i] > 0) && t.below[i] <= t.floor[i];
  });
}

std::vector<std::uint8_t> SightMap::known_cells(const GridFrame& f) const {
  return cells_where(f, [](const Tile& t, std::size_t i) {
    return t.passed[i] > 0 || t.floor[i] > 0 || t.below[i] > 0 || t.hit[i] > 0;
  });
}

}  // namespace tsgraphs::freespace
