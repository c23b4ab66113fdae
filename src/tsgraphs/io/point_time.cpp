#include "tsgraphs/io/point_time.hpp"

#include <algorithm>
#include <cmath>

namespace tsgraphs::io {
namespace {
constexpr double kDay = 86400.0;  // s: relative times within a scan are fractions of a second
}  // namespace

const std::vector<std::string>& time_field_names() {
  static const std::vector<std::string> names = {"t", "time", "timestamp", "offset_time"};
  return names;
}

std::optional<double> time_field_scale(const std::string& name, bool integer_type) {
  const std::vector<std::string>& names = time_field_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) return std::nullopt;
  return integer_type ? 1e-9 : 1.0;
}

std::vector<float> relative_times(const std::vector<double>& seconds) {
  std::vector<float> out(seconds.size());
  if (seconds.empty()) return out;
  double lowest = seconds.front(), largest = 0.0;
  for (const double s : seconds) {
    lowest = std::min(lowest, s);
    largest = std::max(largest, std::abs(s));
  }
  const double origin = largest > kDay ? lowest : 0.0;
  for (std::size_t i = 0; i < seconds.size(); ++i) out[i] = static_cast<float>(seconds[i] - origin);
  return out;
}

}  // namespace tsgraphs::io
