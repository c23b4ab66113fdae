#pragma once
/// The S-Graphs+ baseline's room trigger: extract rooms at a fixed period of the data's time.
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::rooms {

struct RoomTimerConfig {
  double period_s = 1.0;

  template <class V>
  void visit(V& v) {
    v("period_s", period_s, above(0.0, 1e6), "extraction period (s), S-Graphs+'s 1.0 s");
  }
};

class RoomTimerTrigger {
 public:
  explicit RoomTimerTrigger(RoomTimerConfig config = {});

  /// Feeds a keyframe's time stamp (s, non-decreasing). The first stamp starts the clock; later
  /// ones return true when at least one period has elapsed since the last firing. Firings stay on
  /// the grid first stamp + k * period, so that they do not drift with the keyframe times.
  bool update(double stamp);
  void reset();

 private:
  RoomTimerConfig config_;
  bool started_ = false;
  double last_fire_ = 0.0;
};

}  // namespace tsgraphs::rooms
