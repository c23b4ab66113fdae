// Occupancy maps made scenes: outlines traced along cell edges and simplified without
// crossing, the drawn building's slab, voids, wall voxels, rooms and survey path, and its
// scene loaded and scanned by the simulator.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "map_test_support.hpp"
#include "test_support.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/occupancy_map.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/scene/map_import.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/scene_writer.hpp"
#include "tsgraphs/scene/survey_path.hpp"
#include "tsgraphs/scene/trajectory.hpp"
#include "tsgraphs/sim/simulator.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using namespace tsgraphs::scene;
using test::DrawnMap;
using test::kMapRes;

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

std::vector<std::uint8_t> grey_bottom_first(const io::Image& img) {
  std::vector<std::uint8_t> out(img.samples.size());
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i)
      out[static_cast<std::size_t>(img.height - 1 - j) * img.width + i] = img.at(i, j);
  return out;
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
    grey_ = grey_bottom_first(drawn_.labels);
    config_.name = "drawn";
    config_.voxel_file = "drawn_walls.pcd";
    imported_ = import_map(map_, grey_, config_);
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
  std::vector<std::uint8_t> grey_;
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
    const int c = static_cast<int>(std::floor(v.x() / kMapRes)), r = static_cast<int>(std::floor(v.y() / kMapRes));
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
  const PathClearance exact =
      path_clearance(s, [&](const Vec2& xy, double, int) { return exact_clearance(map_, map_.to_map(xy), 1.0); });
  EXPECT_GE(exact.min_clearance, config_.clearance - 0.71 * kMapRes);
  // Every room but the closet is entered; the closet is named in a warning.
  const Trajectory t(s);
  std::vector<bool> entered(s.rooms.size(), false);
  for (double time = 0.0; time <= t.duration(); time += 0.05) {
    const Vec2 xy = t.body_pose(time).translation().head<2>();
    for (std::size_t i = 0; i < s.rooms.size(); ++i) entered[i] = entered[i] || contains(s.rooms[i].polygon, xy);
  }
  for (std::size_t i = 0; i < s.rooms.size(); ++i) EXPECT_EQ(entered[i], drawn_.rooms[i].reachable) << s.rooms[i].name;
  ASSERT_EQ(imported_.warnings.size(), 1u);
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
        for (int dc = -1; dc <= 1; ++dc) isolated = isolated && noisy.cells[i + dr * noisy.cols + dc] != MapCell::kUnknown;
      if (!isolated) continue;
      noisy.cells[i] = MapCell::kUnknown;
      ++specks;
    }
  }
  ASSERT_GT(specks, 50);
  const ImportedMap im = import_map(noisy, grey_, config_);
  EXPECT_EQ(im.warnings.size(), imported_.warnings.size());
  EXPECT_EQ(im.scene.levels[0].voids.size(), imported_.scene.levels[0].voids.size());
  const Trajectory t(im.scene);
  std::vector<bool> entered(im.scene.rooms.size(), false);
  for (double time = 0.0; time <= t.duration(); time += 0.05) {
    const Vec2 xy = t.body_pose(time).translation().head<2>();
    for (std::size_t i = 0; i < im.scene.rooms.size(); ++i) entered[i] = entered[i] || contains(im.scene.rooms[i].polygon, xy);
  }
  for (std::size_t i = 0; i < im.scene.rooms.size(); ++i) EXPECT_EQ(entered[i], drawn_.rooms[i].reachable) << i;
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
      const int c = static_cast<int>(std::floor(m.x() / kMapRes)), r = static_cast<int>(std::floor(m.y() / kMapRes));
      for (int dr = -2; dr <= 2 && !near_occupied; ++dr)
        for (int dc = -2; dc <= 2 && !near_occupied; ++dc)
          near_occupied =
              map_.at(std::clamp(c + dc, 0, map_.cols - 1), std::clamp(r + dr, 0, map_.rows - 1)) == MapCell::kOccupied;
      off += !near_occupied;
    }
    EXPECT_GT(walls, scan.size() / 5) << "scan " << k;
    EXPECT_GT(floor, 1000u);  // the ceiling is out of the OS1-64's 22.5 degrees in rooms this small
    EXPECT_EQ(floor + ceiling + walls, scan.size());  // nothing else in the scene
    EXPECT_EQ(off, 0u) << "scan " << k;
  }
}

TEST_F(MapImportTest, SameInputSameScene) {
  const ImportedMap again = import_map(map_, grey_, config_);
  EXPECT_EQ(scene_yaml(again.scene), scene_yaml(imported_.scene));
  EXPECT_EQ(again.voxels, imported_.voxels);
}

TEST_F(MapImportTest, YawRotatesTheMapAboutItsOrigin) {
  const MapRaster turned = raster(drawn_, origin_, M_PI / 2);
  const ImportedMap im = import_map(turned, grey_, config_);
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
  const ImportedMap im = import_map(map_, {}, config_);
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

TEST(MapImport, MapsWithNoKnownOrNoOpenCellAreInputErrors) {
  MapRaster r;
  r.cols = 20;
  r.rows = 10;
  r.cells.assign(200, MapCell::kUnknown);
  EXPECT_NE(test::input_error_of([&] { import_map(r, {}, {}); }).find("no known cell"), std::string::npos);
  r.cells.assign(200, MapCell::kFree);  // 1 m x 0.5 m: nowhere 0.4 m from the edge
  EXPECT_NE(test::input_error_of([&] { import_map(r, {}, {}); }).find("--clearance"), std::string::npos);
}
