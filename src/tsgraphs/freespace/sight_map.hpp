#pragma once
/// The free space a LiDAR sees on one level: a 2-D raster of where its rays passed at walking
/// height (between the floor and the headroom), where they met the floor, and where they went
/// below it (no floor there: a void, a ramp's well, the storey below).
///
/// A sensor mounted high sees the floor only far away (1.7 m up with a lowest beam at -15 deg:
/// beyond 6.3 m), so a small room's floor may never become traversable ground; the rays that
/// cross the room to its walls still show it is open at walking height and has a floor under
/// it wherever they did not go below it. A ray is followed down only through the slab's
/// thickness: past a void's edge it runs on under the floor, beneath rooms that have one.
/// The room segmentation takes its spaces from this and from the traversable ground together,
/// so that the same rooms come from any mount height. A scan can be taken back and traced
/// again (remove_scan, add_scan) when the back-end corrects its keyframe.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "tsgraphs/core/grid_frame.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::freespace {

struct SightMapConfig {
  double cell = 0.1;
  double floor_step = 0.2;  ///< a return within this of the floor height is the floor (m); the free space's
                            ///< obstacle_min_height
  double headroom = 2.0;  ///< a ray below this above the floor passes at walking height (m); the free space's
                          ///< obstacle_max_height
  double max_range = 20.0;

  template <class V>
  void visit(V& v) {
    v("cell", cell, between(0.01, 10.0), "raster cell (m), the room segmentation's");
    v("max_range", max_range, above(0.0, 1000.0),
      "returns farther than this horizontally are not traced (m): far returns on the floor are "
      "tilt-sensitive");
  }
};

class SightMap {
 public:
  /// Throws std::invalid_argument for cell <= 0, floor_step < 0, headroom <= floor_step or max_range <= 0.
  SightMap(double floor_z, const SightMapConfig& config);

  /// Traces the rays from `sensor` to each of `points` (map frame).
  void add_scan(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points);
  /// Takes back a scan given to add_scan with the same sensor and points (its keyframe has
  /// moved: the back-end corrected it), so that it can be traced again where it now is. The
  /// counts return to what they were without it; a cell's lowest return does so only when no
  /// other return is left in it (the map keeps the lowest, not all).
  void remove_scan(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points);

  /// Per cell of `frame`: `open` where rays passed at walking height or met the floor, and
  /// rays never went below the floor more often than they met it there.
  std::vector<std::uint8_t> open_cells(const GridFrame& frame) const;
  /// Per cell of `frame`: whether any ray passed or ended there (open or not), i.e. it is no
  /// frontier of what the sensor has seen.
  std::vector<std::uint8_t> known_cells(const GridFrame& frame) const;

  /// Whether a return above the floor ended at most z high (map frame) in the cell of xy or
  /// one of its 8 neighbours (something stands there that low).
  bool return_near(const Eigen::Vector2d& xy, double z) const;

  double floor_z() const { return floor_z_; }
  /// The box of every cell touched (lo > hi when none).
  Eigen::Vector2d lo() const { return lo_; }
  Eigen::Vector2d hi() const { return hi_; }

 private:
  static constexpr int kTileBits = 5;  // 32 x 32 cells a tile
  static constexpr int kTileSide = 1 << kTileBits;
  struct Tile {
    // Counts, not flags, so that a scan can be taken back (remove_scan).
    std::uint32_t passed[kTileSide * kTileSide] = {};
    std::uint32_t floor[kTileSide * kTileSide] = {};
    std::uint32_t below[kTileSide * kTileSide] = {};
    std::uint32_t hit[kTileSide * kTileSide] = {};  ///< returns above the floor that ended here
    std::uint8_t low[kTileSide * kTileSide] =
        {};  ///< the lowest return in it, kLowStep units above the floor (0: none)
  };
  static constexpr double kLowStep = 0.05;  // m: 12.7 m in a byte
  /// A height above the floor in kLowStep units, 1 to 255 (0 is "none").
  std::uint8_t height_code(double z) const;
  enum class Mark { passed, floor, below, hit };
  /// Cell (c, r)'s index in its tile.
  static std::size_t index_in_tile(long c, long r);
  /// The tile holding cell (c, r) (made if new) and the cell's index in it.
  Tile& tile_at(long c, long r, std::size_t* i);
  /// tile_at's lookup when the cell is in another tile than the last one (made if new).
  Tile& tile_miss(std::uint64_t key);
  /// Adds `delta` (+1 or -1) to cell (c, r)'s count `m`; `z`: the return's height (map frame), for a hit.
  void mark(long c, long r, Mark m, int delta, double z = 0.0);
  /// add_scan (delta +1) and remove_scan (delta -1).
  void trace(const Eigen::Vector3d& sensor, const std::vector<Eigen::Vector3d>& points, int delta);
  const Tile* tile(long tc, long tr) const;
  /// The tile and index of the cell holding the frame's cell centre, or nullptr.
  const Tile* cell(const GridFrame& f, int col, int row, std::size_t* i) const;
  /// 1 for each cell of f whose tile cell passes test(tile, index).
  template <class Test>
  std::vector<std::uint8_t> cells_where(const GridFrame& f, Test test) const;

  double floor_z_;
  SightMapConfig config_;
  std::unordered_map<std::uint64_t, Tile> tiles_;
  /// The tile tile_at found last; a copy or a move starts without one (its tiles are others).
  struct TileCache {
    Tile* tile = nullptr;
    std::uint64_t key = 0;
    TileCache() = default;
    TileCache(const TileCache&) {}
    TileCache& operator=(const TileCache&) {
      tile = nullptr;
      return *this;
    }
  };
  TileCache last_;
  Eigen::Vector2d lo_, hi_;
};

}  // namespace tsgraphs::freespace
