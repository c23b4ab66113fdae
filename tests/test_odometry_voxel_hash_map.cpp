// The odometry's local voxel map: nearest neighbour against brute force, the per-voxel cap,
// and remove_far.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <stdexcept>

#include "tsgraphs/odometry/voxel_hash_map.hpp"

using tsgraphs::odometry::VoxelHashMap;
using tsgraphs::odometry::VoxelIndex;

namespace {

std::vector<Eigen::Vector3d> random_points(std::size_t n, double half_extent, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-half_extent, half_extent);
  std::vector<Eigen::Vector3d> pts(n);
  for (auto& p : pts) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return pts;
}

}  // namespace

TEST(VoxelHashMap, NearestEqualsBruteForceWithinOneVoxel) {
  constexpr double kVoxel = 0.5;
  // Enough points per voxel that the cap drops some: the query must agree with what is stored.
  VoxelHashMap map(kVoxel, 5);
  map.add_points(random_points(20000, 4.0, 1));
  const std::vector<Eigen::Vector3d> stored = map.points();
  const std::vector<Eigen::Vector3d> queries = random_points(500, 4.5, 2);
  int checked = 0;
  for (const Eigen::Vector3d& q : queries) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d best_p = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : stored) {
      if ((p - q).norm() < best) {
        best = (p - q).norm();
        best_p = p;
      }
    }
    const auto nb = map.nearest(q);
    // A neighbour within one voxel edge lies in the 27 voxels searched, so the answer is exact.
    if (best <= kVoxel) {
      ASSERT_TRUE(nb.found);
      EXPECT_DOUBLE_EQ(nb.distance, best);
      EXPECT_EQ((nb.point - q).squaredNorm(), (best_p - q).squaredNorm());  // the same point, or one as near
      ++checked;
    } else if (nb.found) {
      EXPECT_GE(nb.distance, best);  // never closer than the truth
    }
  }
  EXPECT_GT(checked, 400);
}

TEST(VoxelHashMap, EmptyNeighbourhoodFindsNothing) {
  VoxelHashMap map(1.0, 3);
  map.add_points({Eigen::Vector3d(0.5, 0.5, 0.5)});
  EXPECT_TRUE(map.nearest(Eigen::Vector3d(0.9, 0.1, 0.2)).found);
  EXPECT_TRUE(map.nearest(Eigen::Vector3d(1.9, 1.9, -0.9)).found);  // diagonal neighbour voxel
  EXPECT_FALSE(map.nearest(Eigen::Vector3d(2.1, 0.5, 0.5)).found);  // two voxels away
}

TEST(VoxelHashMap, NoVoxelHoldsMoreThanTheCap) {
  constexpr std::size_t kCap = 4;
  VoxelHashMap map(0.3, kCap);
  const auto pts = random_points(30000, 2.0, 3);
  map.add_points(pts);
  map.add_points(random_points(30000, 2.0, 4));  // a second pass over the same space
  std::size_t full = 0;
  for (const Eigen::Vector3d& p : pts) {
    const auto& voxel = map.voxel_points(map.voxel_of(p));
    ASSERT_LE(voxel.size(), kCap);
    if (voxel.size() == kCap) ++full;
  }
  EXPECT_GT(full, pts.size() / 2);  // the data were dense enough for the cap to matter
  EXPECT_LE(map.num_points(), kCap * map.num_voxels());
  // The first points of a voxel are the ones kept.
  VoxelHashMap small(1.0, 2);
  small.add_points({{0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}, {0.3, 0.3, 0.3}});
  const auto& v = small.voxel_points(VoxelIndex(0, 0, 0));
  ASSERT_EQ(v.size(), 2u);
  EXPECT_DOUBLE_EQ(v[1].x(), 0.2);
}

TEST(VoxelHashMap, RemoveFarRemovesExactlyTheFarVoxels) {
  constexpr double kVoxel = 0.4;
  constexpr double kMaxDistance = 3.0;
  VoxelHashMap map(kVoxel, 3);
  map.add_points(random_points(20000, 6.0, 5));
  const Eigen::Vector3d origin(1.0, -0.5, 0.2);
  // Which voxels should survive, decided before removal.
  std::vector<VoxelIndex> near, far;
  for (const Eigen::Vector3d& p : map.points()) {
    const VoxelIndex v = map.voxel_of(p);
    ((map.voxel_centre(v) - origin).norm() <= kMaxDistance ? near : far).push_back(v);
  }
  ASSERT_FALSE(near.empty());
  ASSERT_FALSE(far.empty());
  const std::size_t near_points = near.size();
  map.remove_far(origin, kMaxDistance);
  for (const VoxelIndex& v : far) EXPECT_TRUE(map.voxel_points(v).empty());
  for (const VoxelIndex& v : near) EXPECT_FALSE(map.voxel_points(v).empty());
  EXPECT_EQ(map.num_points(), near_points);
}

TEST(VoxelHashMap, RejectsBadParameters) {
  EXPECT_THROW(VoxelHashMap(0.0, 3), std::invalid_argument);
  EXPECT_THROW(VoxelHashMap(-1.0, 3), std::invalid_argument);
  EXPECT_THROW(VoxelHashMap(0.5, 0), std::invalid_argument);
}
