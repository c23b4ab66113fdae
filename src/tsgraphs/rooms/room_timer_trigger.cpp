#include "tsgraphs/rooms/room_timer_trigger.hpp"

#include <cmath>

namespace tsgraphs::rooms {

namespace {
/// Stamps that differ by float rounding only (e.g. 1.1 - 0.1) count as a full period.
constexpr double kStampEpsilon = 1e-9;
}  // namespace

RoomTimerTrigger::RoomTimerTrigger(RoomTimerConfig config) : config_(config) {}

bool RoomTimerTrigger::update(double stamp) {
  if (!started_) {
    started_ = true;
    last_fire_ = stamp;
    return false;
  }
  if (stamp - last_fire_ + kStampEpsilon < config_.period_s) return false;
  // Skip whole periods without keyframes: one firing, on the latest grid time not after stamp.
  last_fire_ += std::floor((stamp - last_fire_ + kStampEpsilon) / config_.period_s) * config_.period_s;
  return true;
}

void RoomTimerTrigger::reset() {
  started_ = false;
  last_fire_ = 0.0;
}

}  // namespace tsgraphs::rooms
