#pragma once
/// The bound on positions read from files of a run or a sequence (trajectories, scene graphs).

namespace tsgraphs::io {

/// Largest |coordinate| a position file may hold, m. No place on Earth is farther from any
/// origin (the circumference is 4e7 m; UTM northings stay below 1e7 m), and a larger value
/// would overflow the squares, rasters and drawings made of it.
inline constexpr double kMaxCoordinate = 1e8;

}  // namespace tsgraphs::io
