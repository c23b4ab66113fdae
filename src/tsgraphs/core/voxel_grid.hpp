#pragma once
/// Downsampling to one centroid per voxel. Shared by the prefilter, registration, the map
/// output and the room layer.
#include <cstddef>
#include <cstdint>
#include <limits>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/core/voxel_key.hpp"

namespace tsgraphs {

/// The finite points of `cloud` whose distance from the origin is in [min_range, max_range],
/// one per voxel of edge `voxel_size`: the centroid of its points, their mean intensity and
/// the first point's label, in the order the voxels were first hit (deterministic).
/// voxel_size <= 0 keeps every such point. `num_non_finite`, when given, receives the number
/// of NaN/inf points dropped.
PointCloud voxel_downsample(const PointCloud& cloud, double voxel_size, double min_range = 0.0,
                            double max_range = std::numeric_limits<double>::infinity(),
                            std::size_t* num_non_finite = nullptr);

}  // namespace tsgraphs
