// Prefilter (step 1) and keyframe selection (step 3).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tsgraphs/pipeline/keyframe_selector.hpp"
#include "tsgraphs/pipeline/prefilter.hpp"

using namespace tsgraphs;
using namespace tsgraphs::pipeline;

namespace {

PointCloud cloud_of(std::initializer_list<Eigen::Vector3f> pts) {
  PointCloud c;
  for (const auto& p : pts) {
    c.points.push_back(p);
    c.intensity.push_back(0.5f);
    c.labels.push_back(4);
  }
  return c;
}

}  // namespace

TEST(Prefilter, DropsNonFiniteAndCropsByRange) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  PointCloud c = cloud_of({{0.1f, 0, 0}, {2, 0, 0}, {nan, 0, 0}, {0, inf, 0}, {40, 0, 0}, {0, 5, 1}});
  PrefilterConfig cfg;
  cfg.voxel_size = 0.0;
  std::size_t non_finite = 0;
  const PointCloud out = prefilter(c, cfg, &non_finite);
  EXPECT_EQ(non_finite, 2u);
  ASSERT_EQ(out.size(), 2u);  // 0.1 m is inside min_range, 40 m beyond max_range
  EXPECT_FLOAT_EQ(out.points[0].x(), 2.0f);
  EXPECT_FLOAT_EQ(out.points[1].y(), 5.0f);
  EXPECT_EQ(out.labels.size(), 2u);
  EXPECT_EQ(out.intensity.size(), 2u);
}

TEST(Prefilter, VoxelKeepsCentroidPerCellInFirstSeenOrder) {
  PointCloud c = cloud_of({{2.01f, 0.01f, 0.01f}, {5.05f, 0.05f, 0.05f}, {2.09f, 0.09f, 0.09f}});
  PrefilterConfig cfg;
  cfg.voxel_size = 0.1;
  const PointCloud out = prefilter(c, cfg);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out.points[0].x(), 2.05f, 1e-5);
  EXPECT_NEAR(out.points[0].y(), 0.05f, 1e-5);
  EXPECT_NEAR(out.points[1].x(), 5.05f, 1e-5);
}

TEST(Prefilter, NegativeCoordinatesFallInTheirOwnVoxels) {
  // floor() not truncation: -0.05 and +0.05 are different voxels of size 0.1.
  PointCloud c = cloud_of({{-0.05f, 3, 0}, {0.05f, 3, 0}});
  PrefilterConfig cfg;
  EXPECT_EQ(prefilter(c, cfg).size(), 2u);
}

TEST(Prefilter, EmptyAndAllNaNScansGiveEmptyClouds) {
  PrefilterConfig cfg;
  EXPECT_TRUE(prefilter(PointCloud{}, cfg).empty());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(prefilter(cloud_of({{nan, nan, nan}}), cfg).empty());
}

TEST(Prefilter, ReducesADenseCloudToOnePointPerVoxel) {
  PointCloud c;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j)
      c.points.emplace_back(2.0f + i * 0.01f, j * 0.01f, 0.0f);  // 1 m x 1 m, 1 cm grid
  PrefilterConfig cfg;
  cfg.voxel_size = 0.1;
  EXPECT_EQ(prefilter(c, cfg).size(), 100u);
}

TEST(KeyframeSelector, FirstPoseThenByDistanceOrAngle) {
  KeyframeConfig cfg;
  cfg.delta_trans = 1.0;
  cfg.delta_angle_deg = 20.0;
  KeyframeSelector sel(cfg);
  const Pose3 a = make_pose({0, 0, 0}, 0.0);
  ASSERT_TRUE(sel.is_keyframe(a));
  sel.accept(a);
  EXPECT_FALSE(sel.is_keyframe(make_pose({0.9, 0, 0}, 0.0)));
  EXPECT_TRUE(sel.is_keyframe(make_pose({1.0, 0, 0}, 0.0)));
  EXPECT_FALSE(sel.is_keyframe(make_pose({0, 0, 0}, 19.0 * M_PI / 180.0)));
  EXPECT_TRUE(sel.is_keyframe(make_pose({0, 0, 0}, 21.0 * M_PI / 180.0)));
  sel.accept(make_pose({1.0, 0, 0}, 0.0));
  EXPECT_FALSE(sel.is_keyframe(make_pose({1.5, 0, 0}, 0.0)));  // measured from the last accepted one
}
