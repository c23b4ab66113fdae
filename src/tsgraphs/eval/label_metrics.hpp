#pragma once
/// A room segmentation against the truth when both are labels on one raster (`segment-map` on a
/// 2-D map and its room-label image): the IPA precision and recall (ipa_segmentation_metrics.hpp)
/// and room precision, recall and F1 at IoU kMatchMinIou (docs/metrics.md), over the whole map.
#include <optional>
#include <vector>

#include "tsgraphs/eval/ipa_segmentation_metrics.hpp"

namespace tsgraphs::eval {

/// Rooms matched one-to-one between two labellings.
struct LabelRoomFigures {
  std::optional<double> precision;  ///< matched / segments; empty without segments
  std::optional<double> recall;     ///< matched / true rooms; empty without them
  std::optional<double> f1;         ///< empty unless both exist
  std::optional<double> mean_iou;   ///< over the matched pairs
  int n_matched = 0, n_segments = 0, n_truth = 0;
};

struct LabelFigures {
  IpaFigures ipa;
  LabelRoomFigures rooms;
};

/// The regions of a labelling (one label per cell, -1 for none; cell (c, r) at index r * cols + c),
/// region k holding the cells labelled k, ascending keys.
std::vector<CellRegion> regions_of_labels(const std::vector<int>& labels, int cols);

/// IPA figures and room figures of `segments` against `truth` (same raster). Regions of at most
/// kIpaMaxSmallRegionCells cells are left out of both, as the IPA evaluation does; rooms pair one
/// to one, greedily by the highest IoU first (ties: lower segment, then lower truth index), a
/// pair counting with IoU >= kMatchMinIou. Throws std::invalid_argument when the sizes differ.
LabelFigures compare_labels(const std::vector<int>& segments, const std::vector<int>& truth, int cols);

}  // namespace tsgraphs::eval
