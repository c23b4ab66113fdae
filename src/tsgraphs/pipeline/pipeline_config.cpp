#include "tsgraphs/pipeline/pipeline_config.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "tsgraphs/core/config_range.hpp"
#include "tsgraphs/core/yaml_map.hpp"

namespace tsgraphs::pipeline {
namespace {

using detail::IsOptional;

// A value as the message about it shows it.
template <class T>
std::string shown(const T& value) {
  if constexpr (IsOptional<T>::value) {
    return value ? shown(*value) : "auto";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return "'" + value + "'";
  } else {
    std::ostringstream out;
    out << value;
    return out.str();
  }
}

// The value an optional field has when it is measured rather than given.
constexpr const char* kAuto = "auto";

// Reads each visited field from a YAML mapping, keeping the default when the key is absent.
// An optional field reads `auto` as unset.
struct Reader {
  const YamlMap& map;
  std::vector<std::string> keys;

  template <class T>
  void operator()(const char* key, T& field) {
    keys.emplace_back(key);
    if constexpr (IsOptional<T>::value) {
      if (!map.has(key)) return;
      const YAML::Node node = map.raw(key);
      if (node.IsScalar() && node.Scalar() == kAuto) {
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
  // A field with declared limits (config_range.hpp): a value outside them is an error at its line.
  template <class T, class L>
  void operator()(const char* key, T& field, const L& limits) {
    (*this)(key, field);
    if (!detail::within(field, limits)) throw map.error(key, limits.describe() + ", not " + shown(field));
  }
  template <class S>
  void section(const char* key, S& sub) {
    keys.emplace_back(key);
    Reader inner{map.map(key), {}};
    sub.visit(inner);
    inner.map.check_keys(inner.keys);
  }
};

// Collects the names of the visited fields.
struct KeyNames {
  std::vector<std::string> keys;
  template <class T>
  void operator()(const char* key, const T&) {
    keys.emplace_back(key);
  }
  template <class T, class L>
  void operator()(const char* key, const T&, const L&) {
    keys.emplace_back(key);
  }
  template <class S>
  void section(const char* key, S&) {
    keys.emplace_back(key);
  }
};

// Emits each visited field.
struct Writer {
  YAML::Emitter& out;

  template <class T>
  void operator()(const char* key, const T& field) {
    if (key != nullptr) out << YAML::Key << key << YAML::Value;
    if constexpr (IsOptional<T>::value) {
      if (field) {
        (*this)(nullptr, *field);
      } else {
        out << kAuto;
      }
    } else if constexpr (std::is_floating_point_v<T>) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.10g", field);
      std::string s = buf;
      if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // keep it a float when read back
      out << s;
    } else {
      out << field;
    }
  }
  template <class T, class L>
  void operator()(const char* key, const T& field, const L&) {
    (*this)(key, field);
  }
  template <class S>
  void section(const char* key, S& sub) {
    out << YAML::Key << key << YAML::Value << YAML::BeginMap;
    sub.visit(*this);
    out << YAML::EndMap;
  }
};

}  // namespace

void DeskewConfig::validate() const {
  check_ranges(*this, "DeskewConfig");  // each field's limits (and the registration's), declared in visit()
  if (!(registration.initial_distance >= registration.final_distance))
    throw std::invalid_argument("DeskewConfig: initial_distance must be >= final_distance");
}

namespace {

// What the fields' declared limits (config_range.hpp, checked as they are read) cannot say:
// limits between fields, and the names the modules check themselves.
void validate(const YamlMap& root, const PipelineConfig& c) {
  if (c.prefilter.min_range < 0.0 || c.prefilter.min_range >= c.prefilter.max_range)
    throw root.map("prefilter").error("min_range", "min_range must be >= 0 and below max_range");
  // The odometry's configs check their fields themselves; a message names the key after the
  // struct's name ("LidarOdometryConfig: max_range must be ...").
  const auto check_at_key = [&root](const char* section, const auto& config) {
    try {
      config.validate();
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      const std::size_t from = what.find(": ") + 2;
      throw root.map(section).error(what.substr(from, what.find(' ', from) - from), what.substr(from));
    }
  };
  check_at_key("platform", c.platform);
  check_at_key("deskew", c.deskew);
  check_at_key("lidar_odometry", c.lidar_odometry);
  check_at_key("floor_levelling", c.floor_levelling);
  check_at_key("room_segmentation", c.rooms.segmentation);
  // The optimiser checks its solver names itself; its message is placed at the key it names.
  try {
    graph::GraphOptimizer check(c.optimizer);
  } catch (const std::invalid_argument& e) {
    const YamlMap section = root.map("optimizer");
    KeyNames names;
    graph::GraphOptimizerConfig copy = c.optimizer;
    copy.visit(names);
    for (const std::string& key : names.keys)
      if (std::string(e.what()).find(key) != std::string::npos) throw section.error(key, e.what());
    throw section.error_here(e.what());
  }
  // The room layer checks its method names itself; each message starts with the key it names.
  try {
    RoomLayer check(c.rooms);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    const std::string key = what.substr(0, what.find(' '));
    const bool association = key == "footprint" || key == "min_overlap" || key == "room_dist_threshold";
    throw root.map(association ? "room_association" : "room_layer").error(key, what);
  }
}

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
  validate(root, config);
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

std::string dump_pipeline_config(const PipelineConfig& config) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  Writer writer{out};
  PipelineConfig copy = config;
  copy.visit(writer);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace tsgraphs::pipeline
