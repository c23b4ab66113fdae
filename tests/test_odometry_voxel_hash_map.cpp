// The odometry's local voxel map: nearest neighbour against brute force, the per-voxel cap,
// remove_far, and the shape of each voxel's points (flat, scattered, a line).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "tsgraphs/odometry/voxel_hash_map.hpp"

using tsgraphs::odometry::Surface;
using tsgraphs::odometry::VoxelHashMap;
using tsgraphs::odometry::VoxelIndex;

namespace {

std::vector<Eigen::Vector3d> random_points(std::size_t n, double half_extent, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-half_extent, half_extent);
  std::vector<Eigen::Vector3d> pts(n);
  for (auto& p : pts) {
    // one draw per statement, the last argument first: a call's argument order is unspecified (gcc's kept)
    const double z = u(rng), y = u(rng), x = u(rng);
    p = Eigen::Vector3d(x, y, z);
  }
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
  EXPECT_THROW(VoxelHashMap(0.5, 3, {2, 0.15, 0.3}), std::invalid_argument);
  EXPECT_THROW(VoxelHashMap(0.5, 3, {4, 0.0, 0.3}), std::invalid_argument);
  EXPECT_THROW(VoxelHashMap(0.5, 3, {4, 0.15, -1.0}), std::invalid_argument);
}

namespace {

// `n` points spread over the voxel [0, 1)^3 by `f(u, v)` for u, v uniform in [0.05, 0.95]
// (`f` returns an Eigen::Vector3d, not an expression of temporaries).
template <class F>
std::vector<Eigen::Vector3d> sample(std::size_t n, std::uint32_t seed, F f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  std::vector<Eigen::Vector3d> pts;
  for (std::size_t i = 0; i < n; ++i) {
    const double b = u(rng), a = u(rng);  // the last argument first, as gcc drew them
    pts.push_back(f(a, b));
  }
  return pts;
}

}  // namespace

TEST(VoxelHashMap, AFlatPatchIsPlanarWithItsNormal) {
  VoxelHashMap map(1.0, 20);
  // A wall tilted 30 degrees about z, with 1 cm of noise across it.
  const Eigen::Vector3d n(std::cos(0.5236), std::sin(0.5236), 0.0);
  const Eigen::Vector3d along(-n.y(), n.x(), 0.0);
  std::mt19937 noise_rng(9);
  std::normal_distribution<double> noise(0.0, 0.01);
  map.add_points(sample(20, 1, [&](double a, double b) -> Eigen::Vector3d {
    return Eigen::Vector3d(0.5, 0.5, 0.5) + (a - 0.5) * 0.8 * along + Eigen::Vector3d(0, 0, (b - 0.5) * 0.8) +
           noise(noise_rng) * n;
  }));
  Eigen::Vector3d normal;
  ASSERT_EQ(map.surface_of(VoxelIndex(0, 0, 0), &normal), Surface::planar);
  EXPECT_GT(std::abs(normal.dot(n)), 0.99);
  // nearest() hands the voxel's shape and normal over with the point.
  const auto nb = map.nearest(Eigen::Vector3d(0.6, 0.5, 0.5));
  ASSERT_TRUE(nb.found);
  EXPECT_EQ(nb.surface, Surface::planar);
  EXPECT_GT(std::abs(nb.normal.dot(n)), 0.99);
}

TEST(VoxelHashMap, ALineIsUnknownACornerIsScattered) {
  // One ring of a scan on the floor: points along a line. Its normal could be any direction
  // across it, and matching along the wrong one pulls the odometry towards standing still.
  VoxelHashMap line(1.0, 20);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.005);
  line.add_points(sample(20, 2, [&](double a, double) -> Eigen::Vector3d {
    const double dz = noise(rng), dy = noise(rng);  // the last argument first, as gcc drew them
    return Eigen::Vector3d(a, 0.5 + dy, 0.2 + dz);
  }));
  EXPECT_EQ(line.surface_of(VoxelIndex(0, 0, 0)), Surface::unknown);

  // Two faces meeting at a corner.
  VoxelHashMap corner(1.0, 20);
  std::vector<Eigen::Vector3d> pts =
      sample(10, 4, [](double a, double b) { return Eigen::Vector3d(0.5, a, b); });
  const auto other = sample(10, 5, [](double a, double b) { return Eigen::Vector3d(a, 0.5, b); });
  pts.insert(pts.end(), other.begin(), other.end());
  corner.add_points(pts);
  EXPECT_EQ(corner.surface_of(VoxelIndex(0, 0, 0)), Surface::scattered);

  // Too few points to tell.
  VoxelHashMap sparse(1.0, 20);
  sparse.add_points({{0.1, 0.1, 0.5}, {0.9, 0.1, 0.5}, {0.5, 0.9, 0.5}});
  EXPECT_EQ(sparse.surface_of(VoxelIndex(0, 0, 0)), Surface::unknown);
  // A fourth point makes it a plane: the shape follows the points added.
  sparse.add_points({{0.5, 0.4, 0.5}});
  EXPECT_EQ(sparse.surface_of(VoxelIndex(0, 0, 0)), Surface::planar);
  EXPECT_EQ(sparse.surface_of(VoxelIndex(5, 5, 5)), Surface::unknown);  // an empty voxel
}
