#pragma once
/// Reading YAML mappings with errors that name the file, the line and the key path, and
/// with unknown keys rejected. Used for scenes and for parameter files.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <initializer_list>
#include <type_traits>
#include <string>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/polygon.hpp"

namespace tsgraphs {

class YamlMap {
 public:
  /// Wraps `node`, which must be a mapping (or null, read as empty); `path` names it in
  /// messages ("" for the document root, "walls[2]" for an entry).
  YamlMap(YAML::Node node, std::string file, std::string path);

  /// Parses a whole file; a missing file or a syntax error is an InputError.
  static YamlMap load_file(const std::string& file);
  /// Parses text (for tests); `file` is the name used in messages.
  static YamlMap load_string(const std::string& text, const std::string& file);

  bool has(const std::string& key) const;
  /// The value of `key` converted to T, or `fallback` when the key is absent.
  template <class T>
  T get(const std::string& key, const T& fallback) const {
    return has(key) ? as<T>(raw(key), key_path(key)) : fallback;
  }
  /// The value of `key`; an InputError when absent.
  template <class T>
  T require(const std::string& key) const {
    return as<T>(required(key), key_path(key));
  }
  /// A nested mapping (empty when absent).
  YamlMap map(const std::string& key) const;
  /// The entries of a sequence (empty when absent); each entry a mapping.
  std::vector<YamlMap> maps(const std::string& key) const;
  /// [x, y] pair.
  Vec2 vec2(const std::string& key) const;
  /// A list of at least three [x, y] points.
  Polygon2 polygon(const std::string& key) const;

  /// Throws an InputError naming the first key that is not in `allowed`.
  void check_keys(std::initializer_list<const char*> allowed) const;
  void check_keys(const std::vector<std::string>& allowed) const;

  /// An InputError at `key`'s line (the mapping's own line when the key is absent).
  InputError error(const std::string& key, const std::string& what) const;
  /// An InputError at the mapping's own line.
  InputError error_here(const std::string& what) const;

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  /// 1-based line of `key` (of the mapping when absent), 0 if unknown.
  int line_of(const std::string& key) const;
  int line() const;
  YAML::Node raw(const std::string& key) const { return node_[key]; }
  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  /// Converts a scalar node, turning conversion failures into InputErrors at its line.
  template <class T>
  T as(const YAML::Node& n, const std::string& what) const {
    T value;
    try {
      value = n.as<T>();
    } catch (const YAML::Exception&) {
      throw input_error(file_, n.Mark().line + 1, what + ": expected " + type_name<T>());
    }
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(value)) throw input_error(file_, n.Mark().line + 1, what + ": not a finite number");
    }
    return value;
  }
  Vec2 as_vec2(const YAML::Node& n, const std::string& what) const;
  Polygon2 as_polygon(const YAML::Node& n, const std::string& what) const;

 private:
  YAML::Node required(const std::string& key) const;
  template <class T>
  static const char* type_name() {
    if constexpr (std::is_same_v<T, bool>)
      return "true or false";
    else if constexpr (std::is_integral_v<T>)
      return "an integer";
    else if constexpr (std::is_floating_point_v<T>)
      return "a number";
    else
      return "a string";
  }

  YAML::Node node_;
  std::string file_;
  std::string path_;
};

}  // namespace tsgraphs
