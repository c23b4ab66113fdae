#pragma once
/// Odometry that no platform in a building could have, refused before a run: a corrupt pose
/// line (a digit lost or added) otherwise becomes a jump that every map grid spans.
#include <string>

#include "tsgraphs/io/sequence_info.hpp"

namespace tsgraphs::io {

/// Fastest platform between two scans, m/s: no robot, walker or drone indoors moves at
/// 360 km/h; a corrupt pose does.
inline constexpr double kMaxPlatformSpeed = 100.0;
/// A step this long is allowed whatever the time between the scans (stamps may repeat, or come
/// from another clock than the poses'), m.
inline constexpr double kMaxUntimedStep = 1.0;
/// Farthest pose from the first, m: as for scenes, no building is 10 km across.
inline constexpr double kMaxRunExtent = 1e4;

/// InputError naming `source` and the scan when a pose is farther from the previous scan's
/// than kMaxPlatformSpeed allows (plus kMaxUntimedStep), or farther than kMaxRunExtent from
/// the first. Sequences without odometry pass.
void check_odometry_motion(const SequenceInfo& info, const std::string& source);

}  // namespace tsgraphs::io
