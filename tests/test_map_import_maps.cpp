// Occupancy maps made scenes: outlines traced along cell edges and simplified without
// crossing, the drawn building's slab, voids, wall voxels, rooms and survey path, and its
// scene loaded and scanned by the simulator.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <array>
#include <set>

#include "map_test_support.hpp"
#include "test_support.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/occupancy_map.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/io/room_labels.hpp"
#include "tsgraphs/map_import/map_import.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/scene/survey_path.hpp"
#include "tsgraphs/scene/trajectory.hpp"
#include "tsgraphs/sim/simulator.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using namespace tsgraphs::scene;
using namespace tsgraphs::map_import;
using test::DrawnMap;
using test::kMapRes;
using Cell2 = std::array<int, 2>;

namespace {

/// A region mask from rows of text, the first line the top row: '#' in the region.
std::vector<int> mask(const std::vector<std::string>& rows_top_first, int* cols, int* rows) {
  *rows = static_cast<int>(rows_top_first.size());
  *cols = static_cast<int>(rows_top_first.front().size());
  std::vector<int> out(static_cast<std::size_t>(*cols) * *rows, -1);
  for (int j = 0; j < *rows; ++j) {
    for (int c = 0; c < *cols; ++c) {
      if (rows_top_first[j][c] == '#') out[static_cast<std::size_t>(*rows - 1 - j) * *cols + c] = 0;
    }
  }
  return out;
}

Vec2 centroid_of(const Polygon2& p) {
  Vec2 c = Vec2::Zero();
  double a2 = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& u = p[i];
    const Vec2& v = p[(i + 1) % p.size()];
    const double w = u.x() * v.y() - v.x() * u.y();
    a2 += w;
    c += w * (u + v);
  }
  return c / (3.0 * a2);
}

/// The drawn map as map_server classifies it, placed at `origin` with `yaw`.
MapRaster raster(const DrawnMap& d, const Vec2& origin, double yaw) {
  io::MapMetadata meta;
  const io::OccupancyMap m = io::classify(d.map, meta);
  MapRaster r;
  r.cols = m.width;
  r.rows = m.height;
  r.resolution = kMapRes;
  r.origin = origin;
  r.yaw = yaw;
  for (io::CellState s : m.cells)
    r.cells.push_back(s == io::CellState::kFree       ? MapCell::kFree
                      : s == io::CellState::kOccupied ? MapCell::kOccupied
                                                      : MapCell::kUnknown);
  return r;
}

/// Exact distance from `p` (map frame) to the nearest cell that is not free (or the map's edge).
double exact_clearance(const MapRaster& r, const Vec2& p, double search) {
  double best = search;
  const int c0 = static_cast<int>(std::floor((p.x() - search) / r.resolution));
  const int c1 = static_cast<int>(std::floor((p.x() + search) / r.resolution));
  const int r0 = static_cast<int>(std::floor((p.y() - search) / r.resolution));
  const int r1 = static_cast<int>(std::floor((p.y() + search) / r.resolution));
  for (int rr = r0; rr <= r1; ++rr) {
    for (int cc = c0; cc <= c1; ++cc) {
      const bool blocked = cc < 0 || rr < 0 || cc >= r.cols || rr >= r.rows || r.at(cc, rr) != MapCell::kFree;
      if (!blocked) continue;
      const double dx = std::max({cc * r.resolution - p.x(), 0.0, p.x() - (cc + 1) * r.resolution});
      const double dy = std::max({rr * r.resolution - p.y(), 0.0, p.y() - (rr + 1) * r.resolution});
      best = std::min(best, std::hypot(dx, dy));
    }
  }
  return best;
}

class MapImportTest : public test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    drawn_ = test::draw_test_building();
    map_ = raster(drawn_, origin_, 0.0);
    labels_ = io::room_labels(drawn_.labels);
    config_.name = "drawn";
    config_.voxel_file = "drawn_walls.pcd";
    imported_ = import_map(map_, labels_.room, labels_.count, config_);
  }

  /// Writes the scene and its voxels as the command does and loads them back.
  Scene write_and_load(const ImportedMap& im) {
    PointCloud cloud;
    cloud.points = im.voxels;
    io::write_file_atomic((dir_ / config_.voxel_file).string(), io::encode_pcd(cloud));
    io::write_file_atomic((dir_ / "drawn.yaml").string(), scene_yaml(im.scene));
    return load_scene((dir_ / "drawn.yaml").string());
  }

  DrawnMap drawn_;
  Vec2 origin_{-2.0, -1.0};
  MapRaster map_;
  io::RoomLabels labels_;
  MapImportConfig config_;
  ImportedMap imported_;
};

}  // namespace

TEST(TraceOutlines, ASquareAndAnLShapeAreTheirCellEdges) {
  int cols, rows;
  const std::vector<int> l = mask({"#...", "#...", "###."}, &cols, &rows);
  const auto out = trace_outlines(l, cols, rows, 1, false);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].size(), 6u);
  EXPECT_DOUBLE_EQ(signed_area(out[0]), 5.0);  // counter-clockwise, 5 cells
  EXPECT_FALSE(find_self_intersection(out[0]));
}

TEST(TraceOutlines, DiagonalContactSplitsFourConnectedAndJoinsEightConnected) {
  int cols, rows;
  // A loop whose cells (1, 0) and (2, 1) touch only at a corner: 4-connected, the pocket inside
  // opens to the outside there; 8-connected, the pocket is a hole (filled by the outline).
  const std::vector<int> loop = mask({"####", "#..#", "#.##", "##.."}, &cols, &rows);
  const auto four = trace_outlines(loop, cols, rows, 1, false);
  EXPECT_FALSE(find_self_intersection(four[0]));
  EXPECT_NEAR(signed_area(four[0]), 11.0, 0.05);
  const auto eight = trace_outlines(loop, cols, rows, 1, true);
  EXPECT_FALSE(find_self_intersection(eight[0]));
  EXPECT_NEAR(signed_area(eight[0]), 14.0, 0.05);
  // Two cells touching at a corner: one outline round both (8) or round the first only (4).
  const std::vector<int> pair = mask({".#", "#."}, &cols, &rows);
  EXPECT_NEAR(area(trace_outlines(pair, cols, rows, 1, false)[0]), 1.0, 0.05);
  const auto both = trace_outlines(pair, cols, rows, 1, true);
  EXPECT_NEAR(area(both[0]), 2.0, 0.05);
  EXPECT_FALSE(find_self_intersection(both[0]));
}

TEST(SimplifyOutlines, StaircaseBecomesALineAndNeighboursNeverCross) {
  // A staircase (a wall at 45 degrees) and a parallel one a cell away.
  std::vector<int> labels(40 * 40, -1);
  for (int r = 0; r < 40; ++r) {
    for (int c = 0; c < 40; ++c) {
      if (c <= r) labels[r * 40 + c] = 0;
      if (c >= r + 2) labels[r * 40 + c] = 1;
    }
  }
  const auto outlines = trace_outlines(labels, 40, 40, 2, true);
  EXPECT_GT(outlines[0].size(), 70u);
  const auto simple = simplify_outlines(outlines, 1.0);
  EXPECT_LT(simple[0].size(), 12u);
  for (const Polygon2& p : simple) EXPECT_FALSE(find_self_intersection(p));
  for (std::size_t i = 0; i < simple[0].size(); ++i) {
    for (std::size_t j = 0; j < simple[1].size(); ++j) {
      EXPECT_FALSE(segments_intersect(simple[0][i], simple[0][(i + 1) % simple[0].size()], simple[1][j],
                                      simple[1][(j + 1) % simple[1].size()]));
    }
  }
}

TEST_F(MapImportTest, SlabIsTheKnownAreaAndTheLargeUnknownHoleAVoid) {
  const Scene& s = imported_.scene;
  ASSERT_EQ(s.levels.size(), 1u);
  const Level& l = s.levels[0];
  EXPECT_EQ(l.name, "L0");
  EXPECT_DOUBLE_EQ(l.ceiling, 2.6);
  EXPECT_EQ(l.slab.size(), 4u);  // the building's rectangle; the stray speck is left out
  EXPECT_NEAR(area(l.slab), drawn_.building.area(), 1e-6);
  const Vec2 c = centroid_of(l.slab);
  EXPECT_NEAR(c.x(), origin_.x() + drawn_.building.cx(), 1e-6);
  EXPECT_NEAR(c.y(), origin_.y() + drawn_.building.cy(), 1e-6);
  ASSERT_EQ(l.voids.size(), 1u);
  EXPECT_NEAR(area(l.voids[0]), drawn_.void_hole.area(), 1e-6);
  EXPECT_TRUE(contains(l.voids[0], origin_ + Vec2(drawn_.void_hole.cx(), drawn_.void_hole.cy())));
  EXPECT_EQ(imported_.stats.small_holes, 1);  // the 0.25 m² hole stays floor
}

TEST_F(MapImportTest, RoomsAreTheWhiteRegionsInReadingOrder) {
  const Scene& s = imported_.scene;
  ASSERT_EQ(s.rooms.size(), drawn_.rooms.size());
  for (std::size_t i = 0; i < s.rooms.size(); ++i) {
    const test::DrawnRoom& want = drawn_.rooms[i];
    const Room& got = s.rooms[i];
    EXPECT_EQ(got.name, want.name);
    EXPECT_EQ(got.level, 0);
    EXPECT_NEAR(area(got.polygon), want.box.area(), 1e-6) << got.name;  // holes in a room are not cut out
    const Vec2 c = centroid_of(got.polygon);
    EXPECT_NEAR(c.x(), origin_.x() + want.box.cx(), 1e-6) << got.name;
    EXPECT_NEAR(c.y(), origin_.y() + want.box.cy(), 1e-6) << got.name;
    EXPECT_FALSE(find_self_intersection(got.polygon));
  }
}

TEST_F(MapImportTest, WallsAreTheSkinOfTheOccupiedCellsFloorToCeiling) {
  // Count the skin independently: occupied cells of the building with a non-occupied side.
  std::size_t occupied = 0, skin = 0;
  std::set<std::pair<int, int>> skin_cells;
  for (int r = 0; r < map_.rows; ++r) {
    for (int c = 0; c < map_.cols; ++c) {
      if (map_.at(c, r) != MapCell::kOccupied) continue;
      ++occupied;
      const bool open = map_.at(c + 1, r) != MapCell::kOccupied || map_.at(c - 1, r) != MapCell::kOccupied ||
                        map_.at(c, r + 1) != MapCell::kOccupied || map_.at(c, r - 1) != MapCell::kOccupied;
      if (open) {
        ++skin;
        skin_cells.insert({c, r});
      }
    }
  }
  EXPECT_EQ(imported_.stats.occupied_cells, occupied);
  EXPECT_EQ(imported_.stats.skin_cells, skin);
  EXPECT_LT(skin, occupied * 3 / 4);  // the thick walls' insides get nothing
  EXPECT_EQ(imported_.voxels.size(), skin * static_cast<std::size_t>(test::kWallHeightCells));
  for (const Eigen::Vector3f& v : imported_.voxels) {
    const int c = static_cast<int>(std::floor(v.x() / kMapRes)),
              r = static_cast<int>(std::floor(v.y() / kMapRes));
    ASSERT_TRUE(skin_cells.count({c, r})) << v.transpose();
    ASSERT_GT(v.z(), 0.0f);
    ASSERT_LT(v.z(), 2.6f);
  }
  ASSERT_EQ(imported_.scene.voxel_maps.size(), 1u);
  const VoxelMap& vm = imported_.scene.voxel_maps[0];
  EXPECT_EQ(vm.file, "drawn_walls.pcd");
  EXPECT_DOUBLE_EQ(vm.voxel_size, kMapRes);
  EXPECT_EQ(vm.label, VoxelLabel::kWall);
  EXPECT_DOUBLE_EQ(vm.offset.x(), origin_.x());
  EXPECT_DOUBLE_EQ(vm.offset.y(), origin_.y());
}

TEST_F(MapImportTest, PathKeepsTheClearanceAndEntersEveryReachableRoom) {
  const Scene& s = imported_.scene;
  EXPECT_EQ(s.trajectory.laps, 2);
  EXPECT_TRUE(s.trajectory.closed);
  EXPECT_DOUBLE_EQ(s.trajectory.speed, 1.0);
  EXPECT_DOUBLE_EQ(s.trajectory.yaw_rate_deg, 90.0);
  EXPECT_EQ(s.sensor.preset, "os1-64");
  EXPECT_DOUBLE_EQ(s.sensor.mount_height, 0.55);
  // The planner's own measure: the raster's clearance less a half cell diagonal.
  WalkableGrid grid;
  grid.frame.resolution = kMapRes;
  grid.frame.cols = map_.cols;
  grid.frame.rows = map_.rows;
  for (MapCell c : map_.cells) grid.free.push_back(c == MapCell::kFree);
  compute_clearance(&grid);
  const PathClearance raster = path_clearance(
      s, [&](const Vec2& xy, double, int) { return grid.clearance_at(map_.to_map(xy)) - 0.71 * kMapRes; });
  EXPECT_GE(raster.min_clearance, config_.clearance - 1e-9);
  // The exact distance to the nearest occupied or unknown cell's square, within the raster's error.
  const PathClearance exact = path_clearance(
      s, [&](const Vec2& xy, double, int) { return exact_clearance(map_, map_.to_map(xy), 1.0); });
  EXPECT_GE(exact.min_clearance, config_.clearance - 0.71 * kMapRes);
  // Every room but the closet is entered; the closet is named in a warning.
  const Trajectory t(s);
  std::vector<bool> entered(s.rooms.size(), false);
  for (double time = 0.0; time <= t.duration(); time += 0.05) {
    const Vec2 xy = t.body_pose(time).translation().head<2>();
    for (std::size_t i = 0; i < s.rooms.size(); ++i)
      entered[i] = entered[i] || contains(s.rooms[i].polygon, xy);
  }
  for (std::size_t i = 0; i < s.rooms.size(); ++i)
    EXPECT_EQ(entered[i], drawn_.rooms[i].reachable) << s.rooms[i].name;
  ASSERT_EQ(imported_.warnings.size(), 1u) << imported_.warnings.back();
  EXPECT_NE(imported_.warnings[0].find("room 'room_5'"), std::string::npos) << imported_.warnings[0];
  EXPECT_NE(imported_.warnings[0].find("left out"), std::string::npos);
  EXPECT_GT(imported_.stats.path_length, 20.0);
  EXPECT_LT(imported_.stats.path_length, 80.0);
}

// Speckle noise: single unknown cells sprinkled over 2 % of the free space are floor, to the
// scene and to the path: the same rooms are reached as without them.
TEST_F(MapImportTest, UnknownSpecklesInTheFreeSpaceDoNotWallRoomsOff) {
  MapRaster noisy = map_;
  std::uint64_t x = 99;
  int specks = 0;
  for (int r = 1; r + 1 < noisy.rows; ++r) {
    for (int c = 1; c + 1 < noisy.cols; ++c) {
      x = x * 6364136223846793005ULL + 1442695040888963407ULL;
      const std::size_t i = static_cast<std::size_t>(r) * noisy.cols + c;
      if ((x >> 33) % 50 != 0 || map_.cells[i] != MapCell::kFree) continue;
      bool isolated = true;  // a speck, not part of a larger unknown patch
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc)
          isolated = isolated && noisy.cells[i + dr * noisy.cols + dc] != MapCell::kUnknown;
      if (!isolated) continue;
      noisy.cells[i] = MapCell::kUnknown;
      ++specks;
    }
  }
  ASSERT_GT(specks, 50);
  const ImportedMap im = import_map(noisy, labels_.room, labels_.count, config_);
  EXPECT_EQ(im.warnings.size(), imported_.warnings.size());
  EXPECT_EQ(im.scene.levels[0].voids.size(), imported_.scene.levels[0].voids.size());
  const Trajectory t(im.scene);
  std::vector<bool> entered(im.scene.rooms.size(), false);
  for (double time = 0.0; time <= t.duration(); time += 0.05) {
    const Vec2 xy = t.body_pose(time).translation().head<2>();
    for (std::size_t i = 0; i < im.scene.rooms.size(); ++i)
      entered[i] = entered[i] || contains(im.scene.rooms[i].polygon, xy);
  }
  for (std::size_t i = 0; i < im.scene.rooms.size(); ++i)
    EXPECT_EQ(entered[i], drawn_.rooms[i].reachable) << i;
}

TEST_F(MapImportTest, WrittenSceneLoadsWithoutWarningsAndTheSimulatorSeesTheWalls) {
  const Scene loaded = write_and_load(imported_);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  ASSERT_EQ(loaded.rooms.size(), 5u);
  EXPECT_EQ(loaded.trajectory.waypoints.size(), imported_.scene.trajectory.waypoints.size());
  const sim::Simulator simulator(loaded, 1);
  EXPECT_TRUE(simulator.trajectory().warnings().empty());
  // A few scans: most returns are walls, floor and ceiling, and every wall return is on an
  // occupied cell of the map (within a cell of its face, plus the range noise).
  for (std::size_t k : {std::size_t{0}, simulator.num_scans() / 3, simulator.num_scans() / 2}) {
    const PointCloud scan = simulator.scan(k);
    const Pose3& pose = simulator.true_poses()[k];
    std::size_t walls = 0, floor = 0, ceiling = 0, off = 0;
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const PointLabel label = static_cast<PointLabel>(scan.labels[i]);
      floor += label == PointLabel::kFloor;
      ceiling += label == PointLabel::kCeiling;
      if (label != PointLabel::kWall) continue;
      ++walls;
      const Eigen::Vector3d w = pose * scan.points[i].cast<double>();
      const Vec2 m = map_.to_map(w.head<2>());
      bool near_occupied = false;
      const int c = static_cast<int>(std::floor(m.x() / kMapRes)),
                r = static_cast<int>(std::floor(m.y() / kMapRes));
      for (int dr = -2; dr <= 2 && !near_occupied; ++dr)
        for (int dc = -2; dc <= 2 && !near_occupied; ++dc)
          near_occupied = map_.at(std::clamp(c + dc, 0, map_.cols - 1),
                                  std::clamp(r + dr, 0, map_.rows - 1)) == MapCell::kOccupied;
      off += !near_occupied;
    }
    EXPECT_GT(walls, scan.size() / 5) << "scan " << k;
    EXPECT_GT(floor, 1000u);  // the ceiling is out of the OS1-64's 22.5 degrees in rooms this small
    EXPECT_EQ(floor + ceiling + walls, scan.size());  // nothing else in the scene
    EXPECT_EQ(off, 0u) << "scan " << k;
  }
}

TEST_F(MapImportTest, SameInputSameScene) {
  const ImportedMap again = import_map(map_, labels_.room, labels_.count, config_);
  EXPECT_EQ(scene_yaml(again.scene), scene_yaml(imported_.scene));
  EXPECT_EQ(again.voxels, imported_.voxels);
}

TEST_F(MapImportTest, YawRotatesTheMapAboutItsOrigin) {
  const MapRaster turned = raster(drawn_, origin_, M_PI / 2);
  const ImportedMap im = import_map(turned, labels_.room, labels_.count, config_);
  const Level& l = im.scene.levels[0];
  // Map x runs along world y, map y along world -x.
  for (const Vec2& p : l.slab) {
    EXPECT_GE(p.x(), origin_.x() - drawn_.building.y1 - 1e-6);
    EXPECT_LE(p.x(), origin_.x() - drawn_.building.y0 + 1e-6);
    EXPECT_GE(p.y(), origin_.y() + drawn_.building.x0 - 1e-6);
    EXPECT_LE(p.y(), origin_.y() + drawn_.building.x1 + 1e-6);
  }
  EXPECT_NEAR(im.scene.voxel_maps[0].yaw_deg, 90.0, 1e-9);
  const Vec2 c = centroid_of(im.scene.rooms[0].polygon);
  EXPECT_NEAR(c.x(), origin_.x() - drawn_.rooms[0].box.cy(), 1e-6);
  EXPECT_NEAR(c.y(), origin_.y() + drawn_.rooms[0].box.cx(), 1e-6);
  const Scene loaded = write_and_load(im);
  EXPECT_TRUE(loaded.warnings.empty());
}

TEST_F(MapImportTest, WithoutRoomsThePathCoversTheFreeSpace) {
  const ImportedMap im = import_map(map_, {}, 0, config_);
  EXPECT_TRUE(im.scene.rooms.empty());
  EXPECT_TRUE(im.warnings.empty());
  // 7 m tiles over a 12 x 8 m building: four stops, and the path reaches into every big room.
  const Trajectory t(im.scene);
  std::vector<bool> entered(drawn_.rooms.size(), false);
  for (double time = 0.0; time <= t.duration(); time += 0.05) {
    const Vec2 m = map_.to_map(t.body_pose(time).translation().head<2>());
    for (std::size_t i = 0; i < drawn_.rooms.size(); ++i) {
      const test::MapBox& b = drawn_.rooms[i].box;
      entered[i] = entered[i] || (m.x() > b.x0 && m.x() < b.x1 && m.y() > b.y0 && m.y() < b.y1);
    }
  }
  EXPECT_TRUE(entered[3]);                             // the corridor
  EXPECT_GE(entered[0] + entered[1] + entered[2], 2);  // rooms that hold a tile's most open point
  EXPECT_TRUE(write_and_load(im).warnings.empty());
}

namespace {

/// A laser map's room as map_server gives it: a 7.4 m x 5.4 m free room at 0.05 m, its 0.1 m
/// walls parted from the free space by a fringe of unknown cells (1 cell on the left and bottom,
/// 2 on the right and top, 4 at the top's right end), the bottom wall seen in dashes (2-cell
/// gaps of unknown), unknown all round.
struct FringedRoom {
  MapRaster map;
  std::size_t occupied = 0;
  std::vector<Cell2> fringe;     ///< unknown cells between the walls and the free space
  std::vector<Cell2> dash_gaps;  ///< unknown cells between the bottom wall's dashes
};

FringedRoom fringed_room() {
  FringedRoom f;
  MapRaster& m = f.map;
  m.cols = 200;
  m.rows = 160;
  m.resolution = 0.05;
  m.cells.assign(static_cast<std::size_t>(m.cols) * m.rows, MapCell::kUnknown);
  const auto set = [&](int c, int r, MapCell v) { m.cells[static_cast<std::size_t>(r) * m.cols + c] = v; };
  const int c0 = 20, c1 = 180, r0 = 20, r1 = 140;  // the walls' outer edges
  const int left = 1, right = 2, bottom = 1, top = 2;
  for (int r = r0; r < r1; ++r)
    for (int c = c0; c < c1; ++c) {
      const bool wall = c < c0 + 2 || c >= c1 - 2 || r < r0 + 2 || r >= r1 - 2;
      const bool free = c >= c0 + 2 + left && c < c1 - 2 - right && r >= r0 + 2 + bottom && r < r1 - 2 - top;
      if (wall) set(c, r, MapCell::kOccupied);
      if (free) set(c, r, MapCell::kFree);
    }
  for (int c = c1 - 40; c < c1 - 4; ++c)  // a wider fringe under the top wall's right end
    for (int r = r1 - 2 - 4; r < r1 - 2 - top; ++r) set(c, r, MapCell::kUnknown);
  for (int c = c0 + 10; c < c1 - 10; c += 6)  // dashes: 2 of every 6 cells of the bottom wall unknown
    for (int r = r0; r < r0 + 2; ++r)
      for (int k = 0; k < 2; ++k) {
        set(c + k, r, MapCell::kUnknown);
        f.dash_gaps.push_back({c + k, r});
      }
  for (int r = 0; r < m.rows; ++r)
    for (int c = 0; c < m.cols; ++c) {
      const MapCell v = m.at(c, r);
      f.occupied += v == MapCell::kOccupied;
      const bool inside = c >= c0 + 2 && c < c1 - 2 && r >= r0 + 2 && r < r1 - 2;
      if (inside && v == MapCell::kUnknown) f.fringe.push_back({c, r});
    }
  return f;
}

bool has_column(const std::vector<Eigen::Vector3f>& voxels, const Cell2& cell, double res) {
  for (const Eigen::Vector3f& v : voxels)
    if (static_cast<int>(std::floor(v.x() / res)) == cell[0] &&
        static_cast<int>(std::floor(v.y() / res)) == cell[1])
      return true;
  return false;
}

}  // namespace

// The bug this guards: with the slab only the known cells' largest region, a fringe of unknown
// parts the walls from it and the scene has no wall at all.
TEST_F(MapImportTest, FringedLaserMapImportsItsWallsAndTheSensorCannotSeeOut) {
  const FringedRoom f = fringed_room();
  ASSERT_GT(f.fringe.size(), 800u);
  MapImportConfig config = config_;
  const ImportedMap im = import_map(f.map, {}, 0, config);
  EXPECT_EQ(im.stats.occupied_cells, f.occupied);
  EXPECT_EQ(im.stats.occupied_off_slab, 0u);
  // The dashes' gaps are wall (and the inner corners' diagonal cell of fringe).
  EXPECT_GE(im.stats.wall_gap_cells, f.dash_gaps.size());
  EXPECT_LE(im.stats.wall_gap_cells, f.dash_gaps.size() + 4 * 3);
  EXPECT_TRUE(im.warnings.empty()) << im.warnings.front();
  ASSERT_EQ(im.scene.voxel_maps.size(), 1u);
  // Walls stand all round: each row has a column within the left and the right wall's band,
  // each column within the bottom and the top wall's (dashes' gaps included); the fringe is floor.
  const double res = f.map.resolution;
  const auto column_in = [&](int c0, int c1, int r0, int r1) {
    for (int r = r0; r < r1; ++r)
      for (int c = c0; c < c1; ++c)
        if (has_column(im.voxels, {c, r}, res)) return true;
    return false;
  };
  for (int r = 20; r < 140; ++r) {
    ASSERT_TRUE(column_in(20, 22, r, r + 1)) << r;
    ASSERT_TRUE(column_in(178, 180, r, r + 1)) << r;
  }
  for (int c = 20; c < 180; ++c) {
    ASSERT_TRUE(column_in(c, c + 1, 20, 22)) << c;
    ASSERT_TRUE(column_in(c, c + 1, 138, 140)) << c;
  }
  for (const Cell2& g : f.dash_gaps) ASSERT_TRUE(has_column(im.voxels, g, res) || g[1] == 20) << g[0];
  const Level& level = im.scene.levels[0];
  EXPECT_TRUE(level.voids.empty());
  for (const Cell2& cell : f.fringe) {
    ASSERT_TRUE(contains(level.slab, f.map.to_world(res * Vec2(cell[0] + 0.5, cell[1] + 0.5))));
    ASSERT_FALSE(has_column(im.voxels, cell, res) && cell[0] > 24 && cell[0] < 174)
        << cell[0] << " " << cell[1];
  }
  // Every fringe cell is bridged but two: where the top's 4-cell fringe meets the right wall's,
  // every run across them is longer than 0.2 m. They are a small hole: floor as well.
  EXPECT_EQ(im.stats.bridged_cells, f.fringe.size() + f.dash_gaps.size() - 2);
  EXPECT_EQ(im.stats.small_holes, 1);
  // A scan from the room's middle: every ray returns (from a wall, the floor or the ceiling): none
  // leaves through the fringe or the dashes' gaps.
  const Scene loaded = write_and_load(im);
  const sim::Simulator simulator(loaded, 1);
  Pose3 pose = Pose3::Identity();
  pose.translation() =
      Eigen::Vector3d(f.map.origin.x() + 5.0, f.map.origin.y() + 4.0, loaded.sensor.mount_height);
  const PointCloud scan = simulator.scan_at(pose, 0);
  const double rays = static_cast<double>(loaded.sensor.channels) * loaded.sensor.columns;
  EXPECT_GE(static_cast<double>(scan.size()), (1.0 - loaded.sensor.dropout) * rays - 3.0 * std::sqrt(rays));
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Vec2 m = f.map.to_map((pose * scan.points[i].cast<double>()).head<2>());
    ASSERT_TRUE(m.x() > 0.95 && m.x() < 9.05 && m.y() > 0.95 && m.y() < 7.05) << m.transpose();
  }
  // Without the bridging (the old rule) the walls are lost, and the import says so.
  config.fringe_width = 0.0;
  const ImportedMap bare = import_map(f.map, {}, 0, config);
  EXPECT_EQ(bare.stats.occupied_cells, 0u);
  EXPECT_TRUE(bare.voxels.empty());
  ASSERT_FALSE(bare.warnings.empty());
  EXPECT_NE(bare.warnings[0].find("none of the map's " + std::to_string(f.occupied) +
                                  " occupied cells lies on the slab"),
            std::string::npos)
      << bare.warnings[0];
}

TEST_F(MapImportTest, AMapWithNoOccupiedCellWarnsThatItHasNoWall) {
  MapRaster open = map_;
  for (MapCell& c : open.cells)
    if (c == MapCell::kOccupied) c = MapCell::kFree;
  const ImportedMap im = import_map(open, {}, 0, config_);
  EXPECT_TRUE(im.voxels.empty());
  EXPECT_TRUE(im.scene.voxel_maps.empty());
  ASSERT_FALSE(im.warnings.empty());
  EXPECT_EQ(im.warnings[0], "the map has no occupied cell: the scene has no wall");
}

// Colour labels (one colour per room) of the drawn building, room_2 in two pieces parted by a
// 0.3 m band of black, room_4 (the corridor) touching room_1 along its door.
TEST_F(MapImportTest, ColourLabelsGiveOneRoomEachAndPiecesMakeOnePolygon) {
  io::Image colour;
  colour.width = drawn_.labels.width;
  colour.height = drawn_.labels.height;
  colour.channels = 3;
  colour.samples.assign(static_cast<std::size_t>(colour.width) * colour.height * 3, 0);
  const std::vector<std::array<std::uint8_t, 3>> palette = {
      {230, 60, 60}, {60, 200, 60}, {60, 60, 230}, {220, 160, 40}, {160, 40, 200}};
  for (int j = 0; j < colour.height; ++j) {
    for (int i = 0; i < colour.width; ++i) {
      const int k = labels_.at(i, colour.height - 1 - j);
      const double x = (i + 0.5) * kMapRes, y = (colour.height - 1 - j + 0.5) * kMapRes;
      const bool band = k == 1 && y > 5.8 && y < 6.1;              // parts room_2
      const bool door = x > 2.5 && x < 3.5 && y > 3.0 && y < 3.1;  // room_1's door: the corridor's colour
      const int room = door ? 3 : band ? -1 : k;
      if (room < 0) continue;
      for (int ch = 0; ch < 3; ++ch)
        colour.samples[(static_cast<std::size_t>(j) * colour.width + i) * 3 + ch] = palette[room][ch];
    }
  }
  const io::RoomLabels labels = io::room_labels(colour);
  ASSERT_EQ(labels.convention, io::RoomLabelConvention::kColour);
  ASSERT_EQ(labels.count, 5);
  const ImportedMap im = import_map(map_, labels.room, labels.count, config_);
  const Scene& s = im.scene;
  ASSERT_EQ(s.rooms.size(), 5u);
  for (std::size_t i = 0; i < s.rooms.size(); ++i) {
    EXPECT_EQ(s.rooms[i].name, drawn_.rooms[i].name);
    EXPECT_FALSE(find_self_intersection(s.rooms[i].polygon)) << i;
    // Each room's extent: the box's area within a cell along its outline.
    const test::MapBox& b = drawn_.rooms[i].box;
    EXPECT_NEAR(area(s.rooms[i].polygon), b.area(), 2.0 * (b.x1 - b.x0 + b.y1 - b.y0) * kMapRes) << i;
    for (std::size_t j = i + 1; j < s.rooms.size(); ++j)
      EXPECT_LT(intersection_area(s.rooms[i].polygon, s.rooms[j].polygon), 1e-9) << i << " " << j;
  }
  // room_2 is one polygon over both pieces and the band between them.
  const test::MapBox& b2 = drawn_.rooms[1].box;
  for (const double y : {4.0, 5.95, 8.0})
    EXPECT_TRUE(contains(s.rooms[1].polygon, origin_ + Vec2(b2.cx(), y))) << y;
  EXPECT_GT(im.stats.room_cells_left_out, 0u);  // the corridor's cells in room_1's door, given up
  EXPECT_EQ(im.stats.room_slits, 0);
  EXPECT_EQ(im.warnings.size(), 1u);  // the closet, as with the grey labels
}

TEST(MapImport, MapsWithNoKnownOrNoOpenCellAreInputErrors) {
  MapRaster r;
  r.cols = 20;
  r.rows = 10;
  r.cells.assign(200, MapCell::kUnknown);
  EXPECT_NE(test::input_error_of([&] { import_map(r, {}, 0, {}); }).find("no known cell"), std::string::npos);
  r.cells.assign(200, MapCell::kFree);  // 1 m x 0.5 m: nowhere 0.4 m from the edge
  EXPECT_NE(test::input_error_of([&] { import_map(r, {}, 0, {}); }).find("--clearance"), std::string::npos);
}
