#include "tsgraphs/pipeline/pipeline_config.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "tsgraphs/core/yaml_map.hpp"

namespace tsgraphs::pipeline {
namespace {

template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

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
  template <class S>
  void section(const char* key, S& sub) {
    out << YAML::Key << key << YAML::Value << YAML::BeginMap;
    sub.visit(*this);
    out << YAML::EndMap;
  }
};

}  // namespace

void DeskewConfig::validate() const {
  if (motion != "auto" && motion != "poses" && motion != "registration")
    throw std::invalid_argument("DeskewConfig: motion must be auto, poses or registration, not '" + motion + "'");
  if (!(max_interval_ratio >= 1.0 && max_interval_ratio <= 1e3))
    throw std::invalid_argument("DeskewConfig: max_interval_ratio must be in [1, 1000]");
  try {
    registration.validate();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    throw std::invalid_argument("DeskewConfig: " + what.substr(what.find(": ") + 2));
  }
}

namespace {

void check_positive(const YamlMap& root, const char* section, const char* key, double value) {
  if (!(value > 0.0)) throw root.map(section).error(key, std::string(key) + " must be > 0");
}

void validate(const YamlMap& root, const PipelineConfig& c) {
  check_positive(root, "prefilter", "max_range", c.prefilter.max_range);
  if (c.prefilter.min_range < 0.0 || c.prefilter.min_range >= c.prefilter.max_range)
    throw root.map("prefilter").error("min_range", "min_range must be >= 0 and below max_range");
  if (c.prefilter.voxel_size < 0.0) throw root.map("prefilter").error("voxel_size", "voxel_size must be >= 0");
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
  check_positive(root, "ground", "sparse_min_pts", c.ground.sparse_min_pts);
  if (!(c.ground.foot_rings >= 0.0)) throw root.map("ground").error("foot_rings", "foot_rings must be >= 0");
  if (!(c.ground.seed_max_slope >= 0.0)) throw root.map("ground").error("seed_max_slope", "seed_max_slope must be >= 0");
  check_positive(root, "keyframes", "delta_trans", c.keyframes.delta_trans);
  check_positive(root, "keyframes", "delta_angle_deg", c.keyframes.delta_angle_deg);
  check_positive(root, "plane_extraction", "distance_threshold", c.plane_extraction.distance_threshold);
  check_positive(root, "plane_extraction", "min_inliers", c.plane_extraction.min_inliers);
  check_positive(root, "plane_mapping", "sigma_distance", c.plane_mapping.sigma_distance);
  check_positive(root, "plane_mapping", "sigma_angle_deg", c.plane_mapping.sigma_angle_deg);
  check_positive(root, "optimizer", "odometry_sigma_trans", c.optimizer.odometry_sigma_trans);
  check_positive(root, "optimizer", "odometry_sigma_rot_deg", c.optimizer.odometry_sigma_rot_deg);
  check_positive(root, "optimizer", "loop_sigma_trans", c.optimizer.loop_sigma_trans);
  check_positive(root, "optimizer", "loop_sigma_rot_deg", c.optimizer.loop_sigma_rot_deg);
  check_positive(root, "optimizer", "plane_sigma_angle_deg", c.optimizer.plane_sigma_angle_deg);
  check_positive(root, "optimizer", "plane_sigma_distance", c.optimizer.plane_sigma_distance);
  check_positive(root, "optimizer", "huber_plane", c.optimizer.huber_plane);
  check_positive(root, "optimizer", "huber_loop", c.optimizer.huber_loop);
  check_positive(root, "optimizer", "room_sigma", c.optimizer.room_sigma);
  check_positive(root, "optimizer", "corridor_sigma", c.optimizer.corridor_sigma);
  check_positive(root, "optimizer", "corridor_along_sigma", c.optimizer.corridor_along_sigma);
  check_positive(root, "optimizer", "floor_sigma", c.optimizer.floor_sigma);
  check_positive(root, "optimizer", "huber_room", c.optimizer.huber_room);
  check_positive(root, "optimizer", "huber_floor", c.optimizer.huber_floor);
  check_positive(root, "optimizer", "local_window", c.optimizer.local_window);
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
  if (c.diagnostics.empty_layer_keyframes < 0)
    throw root.map("diagnostics").error("empty_layer_keyframes", "empty_layer_keyframes must be >= 0");
  check_positive(root, "room_loop_closure", "max_candidates", c.room_loop_closure.max_candidates);
  check_positive(root, "room_loop_closure", "min_common_walls", c.room_loop_closure.min_common_walls);
  check_positive(root, "room_loop_closure", "max_height_difference", c.room_loop_closure.max_height_difference);
  check_positive(root, "keyframe_retirement", "radius", c.keyframe_retirement.radius);
  check_positive(root, "keyframe_retirement", "min_travel", c.keyframe_retirement.min_travel);
  check_positive(root, "schedule", "optimize_every_keyframes", c.schedule.optimize_every_keyframes);
  if (!(c.schedule.full_solve_loop_sigmas >= 0.0))
    throw root.map("schedule").error("full_solve_loop_sigmas", "full_solve_loop_sigmas must be >= 0");
  if (c.schedule.full_every_keyframes < 0)
    throw root.map("schedule").error("full_every_keyframes", "full_every_keyframes must be >= 0");
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
