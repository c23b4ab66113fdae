// One segmentation core, two inputs (issue 51): the room layer online, on the
// map it builds while a robot surveys a building, gives the same rooms as
// segment-map on that building's 2-D map. The building is the drawn floor of
// the segment-map tests, made a scene by import_map (its occupied cells
// standing as wall columns), simulated and run scan by scan.
// ctest: slow (seconds a test: simulated runs or generated buildings)
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "drawn_floor_support.hpp"
#include "test_support.hpp"
#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/pcd.hpp"
#include "tsgraphs/pipeline/pipeline.hpp"
#include "tsgraphs/rooms/map_segmentation.hpp"
#include "tsgraphs/map_import/map_import.hpp"
#include "tsgraphs/sim/simulator.hpp"

namespace tsgraphs {
namespace {

using test::DrawnFloor;
using test::FloorCell;

map_import::MapRaster raster_of(const DrawnFloor &d) {
  map_import::MapRaster r;
  r.cols = d.frame.cols;
  r.rows = d.frame.rows;
  r.resolution = d.frame.resolution;
  r.cells.resize(d.cells.size());
  for (std::size_t i = 0; i < d.cells.size(); ++i)
    r.cells[i] = d.cells[i] == FloorCell::kFree       ? map_import::MapCell::kFree
                 : d.cells[i] == FloorCell::kOccupied ? map_import::MapCell::kOccupied
                                                      : map_import::MapCell::kUnknown;
  return r;
}

/// The final rooms' footprints in the world frame (the scene's, which is the
/// map's here).
std::vector<Polygon2> online_rooms(const scene::Scene &scene, std::uint64_t seed) {
  sim::Simulator sim(scene, seed);
  pipeline::Pipeline slam;
  for (std::size_t k = 0; k < sim.num_scans(); ++k)
    slam.process(k, sim.times()[k], sim.scan(k), sim.odometry_poses()[k]);
  slam.finish();
  // The map frame is the odometry frame, which starts at the true first pose.
  const auto &kfs = slam.graph().keyframes();
  const Pose3 T_world_map = sim.true_poses()[kfs[0].scan_index] * kfs[0].pose.inverse();
  std::vector<Polygon2> rooms;
  for (const auto &[id, r] : slam.room_map().rooms()) {
    Polygon2 world;
    for (const Vec2 &p : footprint_of(r.rect, r.outline))
      world.push_back((T_world_map * Eigen::Vector3d(p.x(), p.y(), 0)).head<2>());
    rooms.push_back(world);
  }
  return rooms;
}

TEST(OnlineVsMap, TheRoomLayerOnASurveyGivesSegmentMapsRooms) {
  const DrawnFloor d = test::draw_floor();
  const rooms::MapSegmentation offline =
      rooms::segment_map(d.frame, d.mask(FloorCell::kFree), d.mask(FloorCell::kOccupied));

  map_import::MapImportConfig config;
  config.laps = 1;
  map_import::ImportedMap imported =
      map_import::import_map(raster_of(d), d.truth, static_cast<int>(d.names.size()), config);
  ASSERT_EQ(imported.scene.voxel_maps.size(), 1u);
  const std::filesystem::path dir = test::fresh_temp_dir();
  const std::string pcd = (dir / "walls.pcd").string();
  PointCloud cloud;
  cloud.points = imported.voxels;
  io::write_file_atomic(pcd, io::encode_pcd(cloud));
  imported.scene.voxel_maps[0].file = pcd;
  const std::vector<Polygon2> online = online_rooms(imported.scene, 1);
  std::filesystem::remove_all(dir);

  // Each of segment-map's rooms against the online room that shares most of it,
  // counted on the map's free cells (where both segmentations can put a room).
  const int n_offline = static_cast<int>(offline.rooms.spaces.size());
  std::vector<std::size_t> size_off(n_offline, 0), size_on(online.size(), 0);
  std::vector<std::vector<std::size_t>> shared(n_offline, std::vector<std::size_t>(online.size(), 0));
  for (int r = 0; r < d.frame.rows; ++r)
    for (int c = 0; c < d.frame.cols; ++c) {
      const std::size_t i = d.frame.index(c, r);
      if (d.cells[i] != FloorCell::kFree) continue;
      const int s = offline.rooms.label[i];
      if (s >= 0) ++size_off[s];
      for (std::size_t k = 0; k < online.size(); ++k) {
        if (!contains(online[k], d.frame.center(c, r))) continue;
        ++size_on[k];
        if (s >= 0) ++shared[s][k];
      }
    }
  int rooms_offline = 0;
  for (int s = 0; s < n_offline; ++s) {
    if (size_off[s] == 0) continue;
    ++rooms_offline;
    double best = 0.0;
    for (std::size_t k = 0; k < online.size(); ++k)
      best = std::max(best, static_cast<double>(shared[s][k]) /
                                static_cast<double>(size_off[s] + size_on[k] - shared[s][k]));
    std::printf(
        "segment-map's room %d (%zu cells): IoU %.2f with the online "
        "room that shares most of it\n",
        s, size_off[s], best);
    EXPECT_GE(best, 0.8) << "segment-map's room " << s;
  }
  EXPECT_EQ(rooms_offline, static_cast<int>(d.names.size()));
  EXPECT_EQ(online.size(), d.names.size());
}

}  // namespace
}  // namespace tsgraphs
