#pragma once
/// Checks of the command line's numbers, read from the option's own text so that nothing is
/// clamped on the way in (CLI11 turns a seed beyond 64 bits into the largest one) and the error
/// names the range in words (CLI11's own checks print DBL_MAX's 309 digits).
#include <CLI/CLI.hpp>

namespace tsgraphs::app {

/// A whole number in [lo, hi].
CLI::Validator whole_number_in(long long lo, long long hi);

/// A finite number in [lo, hi].
CLI::Validator number_in(double lo, double hi);

/// `--laps`: a whole number of laps within core/limits.hpp's bound (every command's).
CLI::Validator laps_check();

/// `--seed`: a whole number in [0, limits::kMaxSeed].
CLI::Validator seed_check();

}  // namespace tsgraphs::app
