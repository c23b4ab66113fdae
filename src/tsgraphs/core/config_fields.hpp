#pragma once
/// A config's fields, each declared once in its struct's visit(): key, valid values and the
/// one-line comment config/params.yaml shows, beside the rules that tie fields together.
///
///   v("voxel_size", voxel_size, above(0.0, 1.0), "m; one point per voxel");   // a number
///   v("motion", motion, kMotions, "poses | registration | auto");              // an enum
///   v("preset", preset, Words{"auto", "os1-64"}, "a sensor's settings");         // a table's key
///   v("enabled", enabled, "de-skew scans with per-point times");               // a bool
///   v.section("registration", registration, "GICP");                           // a sub-config
///   v.require(max_range > min_range, "max_range", "must be > min_range");      // across fields
///
/// The struct's members hold the defaults, right above; a member's own comment is for what the
/// one line cannot say. The parameter file's reader checks each declaration at load
/// (file:line: section.key: must be ...); check_config() checks a config built in code against
/// the same ones. Ranges bound work too: no value may make a loop run 2e9 times or a grid hold
/// 1e12 cells.
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace tsgraphs {

/// What a parameter file writes for an optional field left to be measured.
inline constexpr const char* kAutoWord = "auto";

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

/// "must be a, b or c".
inline std::string must_be_one_of(const std::vector<std::string>& words) {
  std::string s = "must be ";
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) s += i + 1 == words.size() ? " or " : ", ";
    s += words[i];
  }
  return s;
}

/// The words an enum parameter is written as: parsed once at load, the code compares enums.
template <class E>
struct Choices {
  std::vector<std::pair<E, std::string>> names;

  Choices(std::initializer_list<std::pair<E, const char*>> list) {
    for (const auto& [value, name] : list) names.emplace_back(value, name);
  }
  /// The word for `value` (every enumerator has one).
  const std::string& name(E value) const {
    for (const auto& [v, n] : names)
      if (v == value) return n;
    throw std::logic_error("Choices: an enumerator without a name");
  }
  /// The enumerator written as `word`; none for a word not listed.
  std::optional<E> parse(const std::string& word) const {
    for (const auto& [v, n] : names)
      if (n == word) return v;
    return std::nullopt;
  }
  /// Every word, in the order declared.
  std::vector<std::string> words() const {
    std::vector<std::string> out;
    for (const auto& entry : names) out.push_back(entry.second);
    return out;
  }
  bool contains(E value) const {
    for (const auto& entry : names)
      if (entry.first == value) return true;
    return false;
  }
  /// "must be a, b or c".
  std::string describe() const { return must_be_one_of(words()); }
};

/// The words a text parameter may take when they name entries of a table kept elsewhere (a
/// sensor preset): the text is passed on, not switched on.
struct Words {
  std::vector<std::string> values;
  Words(std::initializer_list<const char*> v) : values(v.begin(), v.end()) {}
  bool contains(const std::string& s) const {
    for (const std::string& v : values)
      if (v == s) return true;
    return false;
  }
  std::string describe() const { return must_be_one_of(values); }
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
  } else if constexpr (std::is_same_v<L, Range>) {
    return limits.contains(static_cast<double>(value));
  } else {
    return limits.contains(value);
  }
}

// Visits a config and throws at the first field outside its declared limits or the first
// rule between fields it breaks.
struct ConfigChecker {
  std::string prefix;
  template <class T>
  void operator()(const char*, const T&, const char*) {}
  template <class T, class L>
  void operator()(const char* key, const T& field, const L& limits, const char*) {
    if (!within(field, limits)) throw std::invalid_argument(prefix + key + " " + limits.describe());
  }
  template <class S>
  void section(const char* key, S& sub, const char*) {
    ConfigChecker inner{prefix + key + "."};
    sub.visit(inner);
  }
  void require(bool holds, const char* key, const std::string& what) {
    if (!holds) throw std::invalid_argument(prefix + key + " " + what);
  }
};

}  // namespace detail

/// Checks every declaration `config`'s visit() makes; the first field outside its limits, or
/// rule broken, is a std::invalid_argument "<name>: <key> must be ..." (key with its
/// sub-section, e.g. "registration.voxel_size").
template <class Config>
void check_config(const Config& config, const std::string& name) {
  detail::ConfigChecker checker{name + ": "};
  Config copy = config;  // visit() is not const: it also serves the reader
  copy.visit(checker);
}

}  // namespace tsgraphs
