#pragma once
/// The S-Graphs+ baseline's free space (DESIGN.md "Baseline mode"): a voxel map of the occupied
/// points, the Euclidean distance of each voxel to the nearest occupied voxel (ESDF, capped at
/// max_distance), and free-space vertices = the voxels of one horizontal slice above the floor
/// whose distance exceeds min_free_distance, clustered over 8-neighbour edges. Unlike the
/// traversable free space it knows nothing of the ground: a void is free space like a room.
#include <Eigen/Core>
#include <vector>

#include "tsgraphs/freespace/free_space.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::freespace {

struct EsdfFreeSpaceConfig {
  double voxel_size = 0.2;
  double max_distance = 5.0;
  double min_free_distance = 0.8;
  double slice_height = 1.0;
  double robot_radius = 1.0;
  double robot_height_tolerance = 1.5;

  template <class V>
  void visit(V& v) {
    v("voxel_size", voxel_size, between(0.02, 10.0), "voxel edge (m), S-Graphs+'s TSDF resolution");
    v("max_distance", max_distance, above(0.0, 100.0), "ESDF distances are capped here (m)");
    v("min_free_distance", min_free_distance, between(0.0, 100.0),
      "free-space vertices: slice voxels farther than this from any occupied voxel (m)");
    v("slice_height", slice_height, above(0.0, 100.0),
      "the slice is the voxel layer holding this height above the floor (m)");
    v("robot_radius", robot_radius, above(0.0, 1000.0),
      "the robot's vertex: nearest vertex within this horizontally (m)...");
    v("robot_height_tolerance", robot_height_tolerance, above(0.0, 1000.0),
      "...and within this of the robot position's height (m)");
  }
};

/// The ESDF on the slice: cells of the horizontal bounding box of the occupied voxels that can
/// be within max_distance of the slice. Voxel (i, j, k) spans [i, i+1) x voxel_size etc. in the
/// map frame.
struct EsdfSlice {
  double voxel_size = 0.2;
  int min_i = 0;                 ///< voxel index of column 0
  int min_j = 0;                 ///< voxel index of row 0
  int layer = 0;                 ///< voxel index k of the slice
  int width = 0;                 ///< columns (along x)
  int height = 0;                ///< rows (along y)
  std::vector<double> distance;  ///< per cell, row-major (cell = row * width + column), metres

  /// Centre of a cell in [0, width * height) (map frame).
  Eigen::Vector3d centre(int cell) const;
  /// The cell holding p's (x, y), or -1 outside the slice.
  int cell_at(const Eigen::Vector3d& p) const;
};

struct EsdfFreeSpace {
  EsdfSlice slice;
  FreeSpace free_space;  ///< candidate vertex i is slice cell i
};

/// Free space from the `occupied` points (map frame; the pipeline passes the non-ground points)
/// on the level whose floor is at `floor_height`. Distances are exact Euclidean distances
/// between voxel centres (a 3-D distance transform restricted to the slice). No occupied voxel
/// within max_distance of the slice: an empty slice and no clusters.
/// Throws std::invalid_argument unless voxel_size > 0 and max_distance > 0.
EsdfFreeSpace esdf_free_space(const std::vector<Eigen::Vector3d>& occupied, double floor_height,
                              const Eigen::Vector3d& robot, const EsdfFreeSpaceConfig& config = {});

}  // namespace tsgraphs::freespace
