#pragma once
/// IPA room-segmentation precision and recall (docs/metrics.md; Bormann et al., ICRA 2016, as
/// ipa320/ipa_coverage_planning's evaluation_segmentation.cpp computes them): how much of each
/// segment lies in one true room, and how much of each true room one segment covers, counted
/// in raster cells.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/eval/footprint_raster.hpp"
#include "tsgraphs/io/sequence_info.hpp"

namespace tsgraphs::eval {

/// Segments and true rooms of this many cells or fewer are left out (IPA's "mini rooms").
constexpr std::size_t kIpaMaxSmallRegionCells = 100;

/// A set of raster cells on a level (ascending cells).
struct CellRegion {
  std::string level;
  std::vector<CellKey> cells;
};

/// The four figures (IPA's names: micro = mean of the per-region ratios, macro = ratio of the
/// cell totals). Precision is empty without a segment, recall without a true room.
struct IpaFigures {
  std::optional<double> precision_micro, recall_micro, precision_macro, recall_macro;
  int n_segments = 0;  ///< segments counted (more than kIpaMaxSmallRegionCells cells)
  int n_truth = 0;     ///< true rooms counted
};

/// The figures of `segments` against `truth`, after leaving out the regions of at most
/// kIpaMaxSmallRegionCells cells: for each segment the most cells it shares with one true room
/// of its level, over its size (precision), and for each true room the most it shares with one
/// segment, over its size (recall).
IpaFigures ipa_precision_recall(const std::vector<CellRegion>& segments,
                                const std::vector<CellRegion>& truth);

/// The segments of a room map: each footprint's cells on its level, a cell in two footprints
/// given to the one of smaller polygon area (ties: the lower index), clipped to the free space
/// (the union of the `free_space` rooms of the level). Throws std::invalid_argument for a
/// footprint too large to rasterise.
std::vector<CellRegion> segments_of(const std::vector<LevelFootprint>& footprints,
                                    const std::vector<io::RoomTruth>& free_space);

/// The true rooms as cell regions.
std::vector<CellRegion> regions_of(const std::vector<io::RoomTruth>& truth);

/// ipa_precision_recall(segments_of(footprints, all_truth), regions_of(counted_truth)): the free
/// space is every true room, the rooms that count may be fewer (the visited ones).
IpaFigures ipa_segmentation_metrics(const std::vector<LevelFootprint>& footprints,
                                    const std::vector<io::RoomTruth>& all_truth,
                                    const std::vector<io::RoomTruth>& counted_truth);

}  // namespace tsgraphs::eval
