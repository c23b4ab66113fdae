#pragma once
/// The bounds of the quantities that several commands and files accept, declared once: every
/// reader and option that takes one of them checks it against the constant here, before any work
/// (docs/reliability.md, "Limits"). A value beyond one of them is a typo, or a file or option
/// that would make a run write gigabytes or loop for hours.
#include <cstdint>
#include <limits>

namespace tsgraphs::limits {

/// Laps of a survey path (a scene's `trajectory.laps`, `simulate`, `generate`, `import-map`, a
/// suite file's `laps:`).
inline constexpr int kMaxLaps = 10000;
/// Scans of one recording: 28 hours at 10 Hz, terabytes of points.
inline constexpr double kMaxSequenceScans = 1e6;
/// A scene's coordinates (m from its origin) and the span of what it builds (m).
inline constexpr double kMaxSceneCoordinate = 1e7;
inline constexpr double kMaxSceneExtent = 1e4;
/// Highest sensor a platform may set (m, a suite's platforms, `demo --platform-height`): a person
/// holds it no higher, and the lowest generated ceiling (2.6 m) must stay above it.
inline constexpr double kMaxPlatformHeight = 2.5;
/// Seeds of the simulator and the generator: the largest a command line or a file can spell
/// without its number being clamped on the way in.
inline constexpr long long kMaxSeed = std::numeric_limits<long long>::max();

}  // namespace tsgraphs::limits
