#include <yaml-cpp/yaml.h>

#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "tsgraphs/core/config_fields.hpp"
#include "tsgraphs/core/yaml_map.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"

namespace tsgraphs::pipeline {
namespace {

using detail::IsOptional;

// A value as the message about it shows it.
template <class T>
std::string shown(const T& value) {
  if constexpr (IsOptional<T>::value) {
    return value ? shown(*value) : kAutoWord;
  } else if constexpr (std::is_same_v<T, std::string>) {
    return "'" + value + "'";
  } else {
    std::ostringstream out;
    out << value;
    return out.str();
  }
}

// Reads each visited field from a YAML mapping, keeping the default when the key is absent,
// and checks it against its declaration as it goes: a value outside its limits, or a rule
// between fields broken, is an error at the key's line. An optional field reads `auto` as unset.
struct Reader {
  const YamlMap& map;
  std::vector<std::string> keys;

  template <class T>
  void operator()(const char* key, T& field, const char*) {
    keys.emplace_back(key);
    if constexpr (IsOptional<T>::value) {
      if (!map.has(key)) return;
      const YAML::Node node = map.raw(key);
      if (node.IsScalar() && node.Scalar() == kAutoWord) {
        field.reset();
      } else {
        try {
          field = map.as<typename T::value_type>(node, map.key_path(key));
        } catch (const InputError&) {
          throw map.error(key, "expected a number or auto");
        }
      }
    } else {
      field = map.get<T>(key, field);
    }
  }
  template <class T, class L>
  void operator()(const char* key, T& field, const L& limits, const char* comment) {
    if constexpr (std::is_enum_v<T>) {
      keys.emplace_back(key);
      if (!map.has(key)) return;
      const std::string word = map.get<std::string>(key, "");
      const std::optional<T> value = limits.parse(word);
      if (!value) throw map.error(key, limits.describe() + ", not '" + word + "'");
      field = *value;
    } else {
      (*this)(key, field, comment);
      if (!detail::within(field, limits)) throw map.error(key, limits.describe() + ", not " + shown(field));
    }
  }
  template <class S>
  void section(const char* key, S& sub, const char*) {
    keys.emplace_back(key);
    Reader inner{map.map(key), {}};
    sub.visit(inner);
    inner.map.check_keys(inner.keys);
  }
  void require(bool holds, const char* key, const std::string& what) {
    if (!holds) throw map.error(key, what);
  }
};

// Keys that moved to another section: an old parameter file gets told where.
void check_moved_keys(const YamlMap& root) {
  const YamlMap ground = root.map("ground");
  for (const char* key : {"sensor_height", "seed_radius"})
    if (ground.has(key))
      throw ground.error(key, std::string("ground.") + key + " is now platform." + key +
                                  " (measured from the scans unless given)");
}

PipelineConfig read(const YamlMap& root) {
  check_moved_keys(root);
  PipelineConfig config;
  Reader reader{root, {}};
  config.visit(reader);
  root.check_keys(reader.keys);
  if (root.has("ground")) {
    const YAML::Node ground = root.raw("ground");
    if (ground.IsMap())
      for (const auto& kv : ground) config.ground_keys_given.insert(kv.first.as<std::string>());
  }
  return config;
}

}  // namespace

PipelineConfig load_pipeline_config(const std::string& file) { return read(YamlMap::load_file(file)); }

PipelineConfig parse_pipeline_config(const std::string& text, const std::string& name) {
  return read(YamlMap::load_string(text, name));
}

}  // namespace tsgraphs::pipeline
