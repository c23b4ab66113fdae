// Checks of the command line's numbers (cli_checks.hpp).
#include "cli_checks.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <system_error>

#include "tsgraphs/core/limits.hpp"

namespace tsgraphs::app {

namespace {

std::string range_text(double lo, double hi) {
  char text[96];
  std::snprintf(text, sizeof text, "[%.10g, %.10g]", lo, hi);
  return text;
}

}  // namespace

CLI::Validator whole_number_in(long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        long long v = 0;
        const char* end = text.data() + text.size();
        const auto [stop, ec] = std::from_chars(text.data(), end, v);
        if (ec != std::errc() || stop != end || v < lo || v > hi)
          return "must be a whole number in " + range + ", not '" + text + "'";
        return "";
      },
      "INT in " + range);
}

CLI::Validator number_in(double lo, double hi) {
  const std::string range = range_text(lo, hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        double v = 0.0;
        const char* end = text.data() + text.size();
        const auto [stop, ec] = std::from_chars(text.data(), end, v);
        if (ec != std::errc() || stop != end || !std::isfinite(v) || v < lo || v > hi)
          return "must be a number in " + range + ", not '" + text + "'";
        return "";
      },
      "NUMBER in " + range);
}

CLI::Validator laps_check() { return whole_number_in(1, limits::kMaxLaps); }

CLI::Validator seed_check() { return whole_number_in(0, limits::kMaxSeed); }

}  // namespace tsgraphs::app
