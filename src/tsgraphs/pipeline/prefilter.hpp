#pragma once
/// Step 1 of every scan: drop non-finite points, crop by range, voxel-downsample.
#include <cstddef>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::pipeline {

struct PrefilterConfig {
  double min_range = 0.5;
  double max_range = 30.0;
  double voxel_size = 0.1;

  template <class V>
  void visit(V& v) {
    v("min_range", min_range, between(0.0, 10000.0), "m; nearer points (the platform itself) are dropped");
    v("max_range", max_range, above(0.0, 10000.0), "m; farther points are dropped: sparse and noisy indoors");
    v.require(max_range > min_range, "max_range", "must be > min_range");
    v("voxel_size", voxel_size, between(0.0, 100.0),
      "m; one point (the centroid) per voxel; 0 = no downsampling");
  }
};

/// Returns the filtered cloud, in the order the voxels were first hit (deterministic). Each
/// voxel keeps the centroid of its points, the mean intensity and the first point's label.
/// `num_non_finite`, when given, receives the number of NaN/inf points dropped.
PointCloud prefilter(const PointCloud& scan, const PrefilterConfig& config,
                     std::size_t* num_non_finite = nullptr);

}  // namespace tsgraphs::pipeline
