#pragma once
// `run --segmentations`: each segmentation of the room layer (TS-graphs mode) as a label image,
// to see what the online layer made of the floor at each step, as segment-map's --out shows it
// for a map.
#include <cstddef>
#include <string>

#include "tsgraphs/pipeline/pipeline.hpp"

namespace tsgraphs::app {

/// Writes into `folder` (created): NNNN.png per segmentation (one colour per space, black
/// none; row 0 at the top is the raster's highest y) and, at close(), index.csv: per image its
/// keyframe, time, level, the raster's origin (m, map frame, its lowest x and y), cell (m),
/// columns, rows and spaces, so that a pixel can be put on the map.
class SegmentationImages {
 public:
  explicit SegmentationImages(std::string folder);
  /// After a scan and at the end: writes the room layer's latest segmentation if it is one not
  /// written yet (of several in one scan, the last).
  void write_new(const pipeline::Pipeline& slam);
  void close() const;

 private:
  std::string folder_;
  std::size_t written_ = 0;
  std::string index_;
};

}  // namespace tsgraphs::app
