#pragma once
// Synthetic clouds of plain surfaces for registration and loop-closure tests.
#include <algorithm>
#include <cmath>

#include "tsgraphs/core/point_cloud.hpp"

namespace test_support {

using tsgraphs::PointCloud;

// Points on the axis-aligned rectangle [lo, hi] (one of its extents zero: the plane) every `step`.
inline void add_patch(PointCloud* cloud, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, float step) {
  const auto count = [&](int axis) {
    return std::max(1, static_cast<int>(std::lround((hi[axis] - lo[axis]) / step)) + 1);
  };
  for (int i = 0; i < count(0); ++i)
    for (int j = 0; j < count(1); ++j)
      for (int k = 0; k < count(2); ++k)
        cloud->points.emplace_back(lo.x() + step * static_cast<float>(i),
                                   lo.y() + step * static_cast<float>(j),
                                   lo.z() + step * static_cast<float>(k));
}

// A corridor 2 m wide and 2.5 m high from x = -length / 2 to length / 2: floor, ceiling, side
// walls; with `ends`, walls closing it.
inline PointCloud corridor(float length, bool ends) {
  PointCloud c;
  const float h = length / 2.0f, step = 0.05f;
  add_patch(&c, {-h, -1.0f, 0.0f}, {h, 1.0f, 0.0f}, step);
  add_patch(&c, {-h, -1.0f, 2.5f}, {h, 1.0f, 2.5f}, step);
  add_patch(&c, {-h, -1.0f, 0.0f}, {h, -1.0f, 2.5f}, step);
  add_patch(&c, {-h, 1.0f, 0.0f}, {h, 1.0f, 2.5f}, step);
  if (ends) {
    add_patch(&c, {-h, -1.0f, 0.0f}, {-h, 1.0f, 2.5f}, step);
    add_patch(&c, {h, -1.0f, 0.0f}, {h, 1.0f, 2.5f}, step);
  }
  return c;
}

}  // namespace test_support
