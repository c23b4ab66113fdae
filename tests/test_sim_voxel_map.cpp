// Voxel maps: PCD voxel centres become cubes with the right labels, yaw and offset.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/sim/ray_caster.hpp"
#include "tsgraphs/sim/scene_mesh.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;
using namespace tsgraphs::sim;
using namespace tsgraphs::scene;
using tsgraphs::test::TempDirTest;

namespace {

constexpr double kVoxel = 0.1;

// A wall of voxel centres in the plane x = 3.05 (y in [-1, 1], z in [0.05, 2.95]) plus a floor
// layer at z = 0.05 and a ceiling layer at z = 2.95 for x in [0, 3].
fs::path write_map(const fs::path& dir) {
  std::vector<Eigen::Vector3d> pts;
  for (int j = -10; j < 10; ++j) {
    for (int k = 0; k < 30; ++k) pts.emplace_back(3.05, (j + 0.5) * kVoxel, (k + 0.5) * kVoxel);
    for (int i = 0; i < 30; ++i) {
      pts.emplace_back((i + 0.5) * kVoxel, (j + 0.5) * kVoxel, 0.05);
      pts.emplace_back((i + 0.5) * kVoxel, (j + 0.5) * kVoxel, 2.95);
    }
  }
  fs::create_directories(dir / "maps");
  const fs::path file = dir / "maps" / "block.pcd";
  std::ofstream out(file);
  out << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << pts.size()
      << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << pts.size() << "\nDATA ascii\n";
  for (const auto& p : pts) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  return file;
}

Scene scene_with_map(const fs::path& dir, const std::string& extra) {
  const fs::path scene = dir / "scene.yaml";
  std::ofstream(scene)
      << "levels: [{name: L0, elevation: 1.0, ceiling: 3.0, slab: [[-5,-5],[5,-5],[5,5],[-5,5]]}]\n"
         "voxel_maps:\n  - {file: maps/block.pcd, voxel_size: 0.1, level: L0"
      << extra << "}\ntrajectory: {waypoints: [[0.5, 0.5], [1.5, 0.5]]}\n";
  return load_scene(scene.string());
}

class VoxelMapTest : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    write_map(dir_);
  }
};

}  // namespace

TEST_F(VoxelMapTest, CubesAreHitAtTheirFacesWithAutoLabels) {
  const Scene scene = scene_with_map(dir_, "");
  const RayCaster caster(build_scene_mesh(scene));
  // Level elevation 1.0: the map's z is relative to it. The wall's near face is at x = 3.0.
  const RayHit wall = caster.cast({1.0f, 0.05f, 2.5f}, {1, 0, 0}, 20.0f);
  EXPECT_NEAR(wall.range, 2.0f, 1e-4);
  EXPECT_EQ(wall.label, static_cast<std::uint32_t>(PointLabel::kWall));
  // The floor layer's top face is at z = 1.0 + 0.1: auto label floor.
  const RayHit floor = caster.cast({1.03f, 0.05f, 2.5f}, {0, 0, -1}, 20.0f);
  EXPECT_NEAR(floor.range, 1.4f, 1e-4);
  EXPECT_EQ(floor.label, static_cast<std::uint32_t>(PointLabel::kFloor));
  // The ceiling layer's lower face at z = 1.0 + 2.9 (above it: the level's own ceiling at 4.0).
  const RayHit ceiling = caster.cast({1.03f, 0.05f, 2.5f}, {0, 0, 1}, 20.0f);
  EXPECT_NEAR(ceiling.range, 1.4f, 1e-4);
  EXPECT_EQ(ceiling.label, static_cast<std::uint32_t>(PointLabel::kCeiling));
}

TEST_F(VoxelMapTest, InnerFacesAreDroppedAndColumnsMerged) {
  const Scene scene = scene_with_map(dir_, ", label: box");
  const LabelledMesh mesh = build_scene_mesh(scene);
  // The wall is a 1 x 20 x 30 block of cubes, the floor and ceiling layers 30 x 20 x 1 each;
  // the wall's bottom and top rows touch the layers' last column. Only faces between a cube
  // and empty space remain: 2 * (20*30) + 2 * (1*30) + 2 * (1*20) of the wall and
  // 2 * (30*20) + 2*30 + 2*20 of each layer, less 2 * 2 * 20 where they touch: 3820 faces
  // of 0.1 x 0.1 m.
  double area = 0.0;
  std::size_t box_triangles = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.labels[t] != static_cast<std::uint32_t>(PointLabel::kBox)) continue;
    ++box_triangles;
    const Eigen::Vector3f a = mesh.vertices[mesh.triangles[t][0]], b = mesh.vertices[mesh.triangles[t][1]],
                          c = mesh.vertices[mesh.triangles[t][2]];
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  EXPECT_NEAR(area, 3820 * 0.01, 1e-3);
  // Side faces merge up each column: +x 20 runs, -x 20 (the wall between the layers) + 40
  // (the layers' west ends), +y and -y 1 + 60 each: 202 quads. Top and bottom faces stay one
  // per cube: 2440. Two triangles a quad.
  EXPECT_EQ(box_triangles, 2u * (202 + 2440));
}

TEST_F(VoxelMapTest, YawAndOffsetMoveTheMap) {
  // Rotated 90 degrees the wall lies in the plane y = 3.05, then moved 1 m along y.
  const Scene scene = scene_with_map(dir_, ", yaw_deg: 90, offset: [0, 1.0, 0], label: wall");
  const RayCaster caster(build_scene_mesh(scene));
  const RayHit wall = caster.cast({0.05f, 0.0f, 2.5f}, {0, 1, 0}, 20.0f);
  EXPECT_NEAR(wall.range, 4.0f, 1e-4);
  EXPECT_EQ(wall.label, static_cast<std::uint32_t>(PointLabel::kWall));
  const RayHit floor = caster.cast({0.05f, 2.0f, 2.5f}, {0, 0, -1}, 20.0f);
  EXPECT_EQ(floor.label, static_cast<std::uint32_t>(PointLabel::kWall));  // label: wall for every cube
}

TEST_F(VoxelMapTest, BadMapFilesAreInputErrors) {
  std::ofstream(dir_ / "maps" / "block.pcd") << "not a point cloud\n";
  const Scene scene = scene_with_map(dir_, "");
  EXPECT_THROW(build_scene_mesh(scene), InputError);
}
