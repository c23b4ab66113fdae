#pragma once
/// The flush rule (TS-graphs, DESIGN step 7): lower-layer data are accumulated while the aisle
/// the robot is in keeps its width and direction; when the width changes by more than a ratio,
/// the aisle turns by more than an angle, or the robot passes a doorway, the accumulated
/// segment is extracted as one room and the accumulator is flushed.
#include <vector>

#include <Eigen/Core>

#include "tsgraphs/core/polygon.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::rooms {

struct AisleMeasureConfig {
  double neighbourhood_radius = 3.0;
  double min_anisotropy = 1.5;
  double slice_half_width = 0.3;
  double max_gap = 0.5;
  int min_points = 40;
  int width_directions = 4;

  template <class V>
  void visit(V& v) {
    v("neighbourhood_radius", neighbourhood_radius, above(0.0, 100.0),
      "cluster points within this of the robot give the aisle direction (m)");
    v("min_anisotropy", min_anisotropy, between(1.0, 1e6),
      "principal std ratio below this: no defined direction (an open room)");
    v("slice_half_width", slice_half_width, above(0.0, 100.0),
      "cross-section: cluster points within this of the line through the robot (m)");
    v("max_gap", max_gap, above(0.0, 100.0),
      "the cross-section ends at a gap wider than this between points (m)");
    v("min_points", min_points, between(1, 10000000),
      "fewer neighbourhood points: no measurement (the map near the robot is still filling in)");
    v("width_directions", width_directions, between(1, 360),
      "the width is the shortest cross-section over this many directions: a room's width does not flip with "
      "its axis");
  }
};

/// The aisle at the robot: its width and (undirected) direction.
struct AisleMeasurement {
  bool valid = false;              ///< false when too few cluster points are near the robot
  double width = 0.0;              ///< shortest cross-section of the cluster through the robot (m)
  Vec2 direction = Vec2::UnitX();  ///< unit principal axis of the cluster near the robot, map x-y
  bool direction_defined = false;  ///< false when the cluster near the robot has no dominant axis
};

/// Measures the aisle from the free-space cluster (map frame) and the robot's position: its axis
/// is the principal axis of the cluster near the robot (`direction_defined` false without a
/// dominant one, so that turns are not judged from it), its width the shortest cross-section
/// through the robot over `width_directions` directions, the first across the axis.
AisleMeasurement measure_aisle(const std::vector<Eigen::Vector3d>& cluster, const Eigen::Vector3d& robot,
                               const AisleMeasureConfig& config = {});

struct RoomFlushConfig {
  double width_change_ratio = 0.3;
  double direction_change_deg = 30.0;
  double max_aisle_width = 4.0;
  int confirm_keyframes = 2;
  double doorway_ratio = 0.3;

  template <class V>
  void visit(V& v) {
    v("width_change_ratio", width_change_ratio, between(0.0, 100.0),
      "flush when |width - median| > ratio * median of the segment");
    v("direction_change_deg", direction_change_deg, between(0.0, 180.0),
      "flush when the aisle turns by more than this from the segment's axis...");
    v("max_aisle_width", max_aisle_width, above(0.0, 1000.0),
      "...where it is narrower than this (m); turning in a wider space is walking a room, and widths both "
      "above it are both open space (no width change)");
    v("confirm_keyframes", confirm_keyframes, between(1, 1000),
      "a change must hold for this many keyframes in a row (a map still filling in is not one)");
    v("doorway_ratio", doorway_ratio, between(0.0, 1.0),
      "a blip narrower than this share of the space on both sides is a doorway (flush)");
  }
};

enum class FlushReason { none, width_change, direction_change, doorway };

class RoomFlushTrigger {
 public:
  explicit RoomFlushTrigger(RoomFlushConfig config = {});

  /// Feeds one keyframe's aisle. A keyframe that differs from the segment (width or turn) is
  /// held pending; when confirm_keyframes in a row differ, returns the reason to flush the
  /// segment accumulated so far, and the pending keyframes start the next segment. A pending
  /// keyframe followed by one that does not differ joins the segment after all. Passing a
  /// doorway flushes at once (this keyframe starts the next segment). An invalid measurement
  /// (no cluster near the robot) changes nothing.
  FlushReason update(const AisleMeasurement& aisle, bool passed_doorway);
  /// Forgets the accumulated segment.
  void reset();

  /// Keyframes measured in the current segment.
  int segment_keyframes() const { return static_cast<int>(widths_.size()); }
  /// After a flush: how many of the latest keyframes start the new segment (the confirming ones).
  int starting_keyframes() const { return carried_; }
  /// Latest keyframes held pending, not (yet) in the segment.
  int pending_keyframes() const { return static_cast<int>(pending_.size()); }
  /// Median width of the accumulated segment; 0 when it is empty.
  double segment_median_width() const;

 private:
  FlushReason judge(const AisleMeasurement& aisle) const;
  void accumulate(const AisleMeasurement& aisle);

  RoomFlushConfig config_;
  std::vector<double> widths_;
  std::vector<AisleMeasurement> pending_;
  FlushReason pending_reason_ = FlushReason::none;
  int carried_ = 1;
  Vec2 axis_sum_ = Vec2::Zero();  ///< sign-aligned sum of the defined directions of the segment
};

}  // namespace tsgraphs::rooms
