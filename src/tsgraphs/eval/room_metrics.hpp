#pragma once
/// Room figures of docs/metrics.md: the consistency of the rooms extracted on two traversals
/// ("Consistency across two traversals", the paper's Table 1; the events are io::RoomEvent) and
/// detected rooms against rooms_gt.json ("Against ground truth").
#include <optional>
#include <string>
#include <vector>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/core/rect.hpp"
#include "tsgraphs/io/run_folder.hpp"
#include "tsgraphs/io/sequence_folder.hpp"

namespace tsgraphs::eval {

/// Two footprints pair as one room only with at least this Dice score (metrics.md).
constexpr double kPairMinDice = 0.5;
/// A detection matches a ground-truth room only with at least this IoU (metrics.md).
constexpr double kMatchMinIou = 0.5;
/// Under- and over-segmentation count an overlap of at least this fraction of the
/// ground-truth room's area (metrics.md).
constexpr double kSegmentMinCover = 0.25;

/// A room footprint with the name of its level (the caller maps level indices to names).
struct DetectedRoom {
  OrientedRect rect;
  std::string level;
  Polygon2 polygon;  ///< the footprint when it is no rectangle (empty: rect)

  Polygon2 footprint() const { return footprint_of(rect, polygon); }
  Vec2 center() const { return polygon.size() >= 3 ? centroid(polygon) : rect.center; }
};

/// A pair of footprints taken as the same room.
struct RoomPair {
  std::size_t a = 0, b = 0;  ///< indices into the first and second list
  double dice = 0.0;
  double center_distance = 0.0;  ///< m
};

/// The Table 1 figures; dcs and d_center are empty when nothing pairs.
struct Consistency {
  int N1st = 0, N2nd = 0, N_re = 0;
  double f_re = 0.0;               ///< N_re / N1st, 0 when N1st = 0
  std::optional<double> dcs;       ///< mean Dice over the pairs
  std::optional<double> d_center;  ///< mean distance between paired centres, m
  std::vector<RoomPair> pairs;     ///< in the order they were taken (highest Dice first)
};

/// Pairs rooms of `first` with rooms of `second` one-to-one, greedily by the highest Dice score
/// first (ties: lower index in `first`, then in `second`); a pair needs Dice >= kPairMinDice and
/// the same level. N1st = |first|, N2nd = |second|. Also compares two runs (`eval --against`).
Consistency consistency_between(const std::vector<DetectedRoom>& first,
                                const std::vector<DetectedRoom>& second);

/// consistency_between the footprints of every lap-1 event and of every lap-2 event (new or
/// associated); events of later laps are not used.
Consistency consistency(const std::vector<io::RoomEvent>& events);

/// Detected rooms against the ground-truth rooms; figures that cannot be computed are empty.
struct RoomsVsTruth {
  std::optional<double> precision;  ///< matched / detected; empty without detections
  std::optional<double> recall;     ///< matched / ground-truth rooms; empty without them
  std::optional<double> f1;         ///< empty unless both precision and recall exist
  std::optional<double> mean_iou;   ///< over the matched pairs; empty without a match
  int n_matched = 0;                ///< pairs with IoU >= kMatchMinIou
  int under_segmented = 0;          ///< detections covering >= kSegmentMinCover of two or more truth rooms
  int over_segmented = 0;           ///< truth rooms covered >= kSegmentMinCover by two or more detections
  int n_rooms_final = 0;            ///< detections
};

/// Area shared by a footprint and a (possibly non-convex) simple polygon.
double intersection_area(const OrientedRect& rect, const Polygon2& polygon);
/// Intersection over union of a footprint and a simple polygon; 0 when both are empty.
double iou(const OrientedRect& rect, const Polygon2& polygon);

/// The ground-truth rooms the sensor's path enters: a pose inside the polygon, on the room's
/// level (the highest level elevation at or below the pose). A method that extracts rooms from
/// the free space it walks can find only these, so recall is counted over them (metrics.md).
std::vector<io::RoomTruth> visited_rooms(const std::vector<io::RoomTruth>& truth,
                                         const std::vector<Pose3>& poses);

/// Matches detections one-to-one to ground-truth rooms of the same level (level name), greedily
/// by the highest IoU first (ties: lower detection index, then lower truth index), keeping pairs
/// with IoU >= kMatchMinIou, and counts under- and over-segmentation (metrics.md).
RoomsVsTruth rooms_vs_truth(const std::vector<DetectedRoom>& detected,
                            const std::vector<io::RoomTruth>& truth);

}  // namespace tsgraphs::eval
