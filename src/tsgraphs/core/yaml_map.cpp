#include "tsgraphs/core/yaml_map.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "tsgraphs/core/printable.hpp"

namespace tsgraphs {

YamlMap::YamlMap(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {
  if (node_.IsNull()) node_ = YAML::Node(YAML::NodeType::Map);
  if (!node_.IsMap()) {
    throw input_error(file_, node_.Mark().line + 1,
                      (path_.empty() ? std::string("document") : path_) + ": expected a mapping of keys");
  }
}

YamlMap YamlMap::load_file(const std::string& file) {
  std::ifstream in(file);
  if (!in || !std::filesystem::is_regular_file(file)) throw input_error(file, 0, "cannot open file");
  try {
    return YamlMap(YAML::Load(in), file, "");
  } catch (const YAML::ParserException& e) {
    throw input_error(file, e.mark.line + 1, "YAML syntax error: " + printable(e.msg, e.msg.size()));
  }
}

YamlMap YamlMap::load_string(const std::string& text, const std::string& file) {
  try {
    return YamlMap(YAML::Load(text), file, "");
  } catch (const YAML::ParserException& e) {
    throw input_error(file, e.mark.line + 1, "YAML syntax error: " + printable(e.msg, e.msg.size()));
  }
}

bool YamlMap::has(const std::string& key) const {
  const YAML::Node n = node_[key];
  return n.IsDefined() && !n.IsNull();
}

int YamlMap::line() const { return node_.Mark().is_null() ? 0 : node_.Mark().line + 1; }

int YamlMap::line_of(const std::string& key) const {
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (it->first.Scalar() == key) return it->first.Mark().line + 1;
  }
  return line();
}

InputError YamlMap::error(const std::string& key, const std::string& what) const {
  return input_error(file_, line_of(key), key_path(key) + ": " + what);
}

InputError YamlMap::error_here(const std::string& what) const {
  return input_error(file_, line(), (path_.empty() ? std::string("document") : path_) + ": " + what);
}

YAML::Node YamlMap::required(const std::string& key) const {
  if (!has(key)) throw error_here("missing required key '" + key + "'");
  return node_[key];
}

YamlMap YamlMap::map(const std::string& key) const {
  return has(key) ? YamlMap(node_[key], file_, key_path(key)) : YamlMap(YAML::Node(), file_, key_path(key));
}

std::vector<YamlMap> YamlMap::maps(const std::string& key) const {
  std::vector<YamlMap> out;
  if (!has(key)) return out;
  const YAML::Node seq = node_[key];
  if (!seq.IsSequence()) throw error(key, "expected a list");
  for (std::size_t i = 0; i < seq.size(); ++i) {
    out.emplace_back(seq[i], file_, key_path(key) + "[" + std::to_string(i) + "]");
  }
  return out;
}

Vec2 YamlMap::as_vec2(const YAML::Node& n, const std::string& what) const {
  if (!n.IsSequence() || n.size() < 2) {
    throw input_error(file_, n.Mark().line + 1, what + ": expected [x, y]");
  }
  const Vec2 v(as<double>(n[0], what), as<double>(n[1], what));
  if (!v.allFinite()) throw input_error(file_, n.Mark().line + 1, what + ": not a finite point");
  return v;
}

Vec2 YamlMap::vec2(const std::string& key) const {
  const YAML::Node n = required(key);
  if (n.size() != 2) throw error(key, "expected [x, y]");
  return as_vec2(n, key_path(key));
}

Polygon2 YamlMap::polygon(const std::string& key) const { return as_polygon(required(key), key_path(key)); }

Polygon2 YamlMap::as_polygon(const YAML::Node& n, const std::string& what) const {
  if (!n.IsSequence() || n.size() < 3) {
    throw input_error(file_, n.Mark().line + 1, what + ": expected a list of at least three [x, y] points");
  }
  Polygon2 poly;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const YAML::Node p = n[i];
    if (!p.IsSequence() || p.size() != 2) {
      throw input_error(file_, p.Mark().line + 1, what + "[" + std::to_string(i) + "]: expected [x, y]");
    }
    poly.push_back(as_vec2(p, what + "[" + std::to_string(i) + "]"));
  }
  return poly;
}

void YamlMap::check_keys(std::initializer_list<const char*> allowed) const {
  check_keys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void YamlMap::check_keys(const std::vector<std::string>& allowed) const {
  std::map<std::string, int> seen;  // key -> 1-based line of its first occurrence
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    const int line = it->first.Mark().line + 1;
    // The key is the file's text, any bytes: quoted printable.
    if (const auto [first, fresh] = seen.emplace(key, line); !fresh) {
      throw input_error(file_, line,
                        "duplicate key '" + key_path(printable(key)) + "' (first at line " +
                            std::to_string(first->second) + ")");
    }
    bool known = false;
    for (const std::string& a : allowed) known = known || key == a;
    if (!known) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw input_error(file_, it->first.Mark().line + 1,
                        "unknown key '" + key_path(printable(key)) + "' (known keys: " + list + ")");
    }
  }
}

}  // namespace tsgraphs
