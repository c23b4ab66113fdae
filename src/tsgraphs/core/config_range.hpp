#pragma once
/// A parameter's valid values, declared once beside the field where its config visits it:
/// `v("voxel_size", voxel_size, above(0.0, 1.0))`. The parameter file's reader checks them at
/// load (file:line: section.key: must be ...); check_ranges() checks a config built in code.
/// Ranges bound work too: no value may make a loop run 2e9 times or a grid hold 1e12 cells.
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace tsgraphs {

/// The numbers a parameter may take: an interval whose ends may be open or absent.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;  ///< min itself is excluded
  bool max_open = false;  ///< max itself is excluded

  bool contains(double x) const {
    return std::isfinite(x) && (min_open ? x > min : x >= min) && (max_open ? x < max : x <= max);
  }
  /// "must be > 0 and <= 10", "must be in [0, 1]", "must be >= 1".
  std::string describe() const {
    const auto num = [](double x) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%g", x);
      return std::string(buf);
    };
    const bool low = std::isfinite(min), high = std::isfinite(max);
    if (low && high && !min_open && !max_open) return "must be in [" + num(min) + ", " + num(max) + "]";
    std::string s = "must be";
    if (low) s += (min_open ? " > " : " >= ") + num(min);
    if (low && high) s += " and";
    if (high) s += (max_open ? " < " : " <= ") + num(max);
    if (!low && !high) s += " a finite number";
    return s;
  }
};

/// [lo, hi].
inline Range between(double lo, double hi) { return {lo, hi, false, false}; }
/// (lo, hi].
inline Range above(double lo, double hi) { return {lo, hi, true, false}; }

/// The words a parameter may take.
struct OneOf {
  std::vector<std::string> values;
  OneOf(std::initializer_list<const char*> v) : values(v.begin(), v.end()) {}
  bool contains(const std::string& s) const {
    for (const std::string& v : values)
      if (v == s) return true;
    return false;
  }
  std::string describe() const {
    std::string s = "must be ";
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) s += i + 1 == values.size() ? " or " : ", ";
      s += values[i];
    }
    return s;
  }
};

namespace detail {

template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

/// Whether `value` lies in `limits` (an unset optional does: it is measured).
template <class T, class L>
bool within(const T& value, const L& limits) {
  if constexpr (IsOptional<T>::value) {
    return !value || within(*value, limits);
  } else if constexpr (std::is_same_v<L, OneOf>) {
    return limits.contains(value);
  } else {
    return limits.contains(static_cast<double>(value));
  }
}

// Visits a config and throws at the first field outside its declared limits.
struct RangeChecker {
  std::string prefix;
  template <class T>
  void operator()(const char*, const T&) {}
  template <class T, class L>
  void operator()(const char* key, const T& field, const L& limits) {
    if (!within(field, limits)) throw std::invalid_argument(prefix + key + " " + limits.describe());
  }
  template <class S>
  void section(const char* key, S& sub) {
    RangeChecker inner{prefix + key + "."};
    sub.visit(inner);
  }
};

}  // namespace detail

/// Checks every limit `config`'s visit() declares; the first field outside its limits is a
/// std::invalid_argument "<name>: <key> must be ..." (key with its sub-section, e.g.
/// "registration.voxel_size").
template <class Config>
void check_ranges(const Config& config, const std::string& name) {
  detail::RangeChecker checker{name + ": "};
  Config copy = config;  // visit() is not const: it also serves the reader
  copy.visit(checker);
}

}  // namespace tsgraphs
