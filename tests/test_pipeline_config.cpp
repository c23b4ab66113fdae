// The parameter file: config/params.yaml lists every key with the code's default; unknown
// keys, wrong types and impossible values are errors naming the file, line and key.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>
#include <vector>

#include "test_support.hpp"
#include "tsgraphs/pipeline/pipeline.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"

using namespace tsgraphs;
using namespace tsgraphs::pipeline;

namespace {

// "section.key" for every leaf of a YAML document.
std::set<std::string> leaf_keys(const YAML::Node& node, const std::string& prefix = "") {
  std::set<std::string> keys;
  for (const auto& kv : node) {
    const std::string k = prefix + kv.first.as<std::string>();
    if (kv.second.IsMap()) {
      const auto sub = leaf_keys(kv.second, k + ".");
      keys.insert(sub.begin(), sub.end());
    } else {
      keys.insert(k);
    }
  }
  return keys;
}

const std::string kParams = std::string(TSGRAPHS_SOURCE_DIR) + "/config/params.yaml";

template <class T>
struct Unwrapped {
  using type = T;
};
template <class T>
struct Unwrapped<std::optional<T>> {
  using type = T;
};

// Every field's declarations (config_fields.hpp), by "section.key": the numeric fields' limits,
// and the fields that break the protocol (a number without limits, a field without a comment,
// an enum whose comment leaves out one of its words).
struct DeclaredLimits {
  struct Numeric {
    std::string path;
    Range range;
    bool integer = false;
  };
  std::string prefix;
  std::vector<Numeric> numeric;
  std::vector<std::string> undeclared;
  std::vector<std::string> uncommented;
  std::vector<std::string> enums;

  void comment(const std::string& path, const char* text) {
    if (text == nullptr || std::string(text).empty()) uncommented.push_back(path);
  }
  template <class T>
  void operator()(const char* key, const T&, const char* text) {
    if constexpr (!std::is_same_v<T, bool>) undeclared.push_back(prefix + key);
    comment(prefix + key, text);
  }
  template <class T, class L>
  void operator()(const char* key, const T&, const L& limits, const char* text) {
    comment(prefix + key, text);
    if constexpr (std::is_same_v<L, Range>) {
      numeric.push_back({prefix + key, limits, std::is_integral_v<typename Unwrapped<T>::type>});
    } else if constexpr (std::is_enum_v<T>) {
      enums.push_back(prefix + key);
      for (const std::string& word : limits.words())
        if (std::string(text).find(word) == std::string::npos)
          undeclared.push_back(prefix + key + " " + word);
    }
  }
  template <class S>
  void section(const char* key, S& sub, const char* text) {
    comment(prefix + key, text);
    DeclaredLimits inner{prefix + key + ".", {}, {}, {}, {}};
    sub.visit(inner);
    numeric.insert(numeric.end(), inner.numeric.begin(), inner.numeric.end());
    undeclared.insert(undeclared.end(), inner.undeclared.begin(), inner.undeclared.end());
    uncommented.insert(uncommented.end(), inner.uncommented.begin(), inner.uncommented.end());
    enums.insert(enums.end(), inner.enums.begin(), inner.enums.end());
  }
  void require(bool, const char*, const std::string&) {}
};

DeclaredLimits declared_limits() {
  DeclaredLimits limits;
  PipelineConfig config;
  config.visit(limits);
  return limits;
}

// A parameter file setting `path` ("a.b.c") to `value`.
std::string file_setting(const std::string& path, const std::string& value) {
  std::string text, indent;
  std::size_t from = 0;
  for (std::size_t dot = path.find('.'); dot != std::string::npos; dot = path.find('.', from)) {
    text += indent + path.substr(from, dot - from) + ":\n";
    indent += "  ";
    from = dot + 1;
  }
  return text + indent + path.substr(from) + ": " + value + "\n";
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace

TEST(PipelineConfig, ShippedParamsFileIsTheDocumentedDefaults) {
  std::ifstream in(kParams);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), documented_pipeline_config(PipelineConfig{}))
      << "config/params.yaml differs from the code's declarations: ./build/tsgraphs params > "
         "config/params.yaml";
  const PipelineConfig loaded = load_pipeline_config(kParams);
  EXPECT_EQ(dump_pipeline_config(loaded), dump_pipeline_config(PipelineConfig{}))
      << "config/params.yaml and the config structs' defaults disagree";
  EXPECT_EQ(leaf_keys(YAML::LoadFile(kParams)), leaf_keys(YAML::Load(dump_pipeline_config(PipelineConfig{}))))
      << "config/params.yaml must list every key";
}

TEST(PipelineConfig, DumpReadsBackToTheSameConfig) {
  PipelineConfig c;
  c.prefilter.voxel_size = 0.15;
  c.optimizer.linear_solver = graph::LinearSolver::dense_schur;
  c.loop_closure.registration.max_iterations = 7;
  c.schedule.merge_duplicate_planes = false;
  const std::string text = dump_pipeline_config(c);
  EXPECT_EQ(dump_pipeline_config(parse_pipeline_config(text, "dumped.yaml")), text);
}

TEST(PipelineConfig, PartialFileKeepsDefaultsForTheRest) {
  const PipelineConfig c = parse_pipeline_config("prefilter:\n  voxel_size: 0.2\n", "p.yaml");
  EXPECT_DOUBLE_EQ(c.prefilter.voxel_size, 0.2);
  EXPECT_DOUBLE_EQ(c.prefilter.max_range, PrefilterConfig{}.max_range);
  EXPECT_EQ(c.optimizer.local_window, graph::GraphOptimizerConfig{}.local_window);
}

TEST(PipelineConfig, ErrorsNameFileLineAndKey) {
  using test::input_error_of;
  EXPECT_EQ(
      input_error_of([] { parse_pipeline_config("prefilter:\n  voxel: 0.2\n", "p.yaml"); }).substr(0, 30),
      "p.yaml:2: unknown key 'prefilt");
  EXPECT_NE(
      input_error_of([] { parse_pipeline_config("walls: {}\n", "p.yaml"); }).find("unknown key 'walls'"),
      std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("keyframes:\n  delta_trans: far\n", "p.yaml");
            }).find("p.yaml:2: keyframes.delta_trans: expected a number"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("keyframes:\n  delta_trans: -1\n", "p.yaml");
            }).find("p.yaml:2"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("optimizer:\n  linear_solver: magic\n", "p.yaml");
            }).find("p.yaml:2: optimizer.linear_solver: must be sparse_normal_cholesky, sparse_schur"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("loop_closure:\n  registration:\n    voxel_size: .nan\n", "p.yaml");
            }).find("p.yaml:3"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              load_pipeline_config("/nonexistent/params.yaml");
            }).find("/nonexistent/params.yaml"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("room_layer:\n  free_space_method: voxblox\n", "p.yaml");
            }).find("p.yaml:2: room_layer.free_space_method: must be traversable or esdf, not 'voxblox'"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("room_layer:\n\n  room_trigger: often\n", "p.yaml");
            }).find("p.yaml:3: room_layer.room_trigger"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("room_association:\n  footprint: big\n", "p.yaml");
            }).find("p.yaml:2: room_association.footprint"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("room_association:\n  min_overlap: 1.5\n", "p.yaml");
            }).find("p.yaml:2: room_association.min_overlap: must be > 0 and <= 1, not 1.5"),
            std::string::npos);
  EXPECT_NE(input_error_of([] {
              parse_pipeline_config("room_segmentation:\n  wall_joint_gap: -1\n", "p.yaml");
            }).find("p.yaml:2: room_segmentation.wall_joint_gap"),
            std::string::npos);
}

TEST(PipelineConfig, EveryFieldDeclaresItsLimitsAndComment) {
  const DeclaredLimits limits = declared_limits();
  EXPECT_TRUE(limits.undeclared.empty())
      << "no limits (or an enum word not in the comment) in visit() for " << limits.undeclared.front();
  EXPECT_TRUE(limits.uncommented.empty()) << "no comment in visit() for " << limits.uncommented.front();
  EXPECT_GE(limits.enums.size(), 7u);  // the choices are enums, parsed once
  EXPECT_GT(limits.numeric.size(), 200u);
  // Every limit is finite at both ends: a value can neither be negative nonsense nor make a
  // loop run 2e9 times or a grid hold 1e12 cells.
  for (const DeclaredLimits::Numeric& n : limits.numeric) {
    EXPECT_TRUE(std::isfinite(n.range.min) && std::isfinite(n.range.max)) << n.path;
    EXPECT_GE(n.range.min, 0.0) << n.path;
  }
}

TEST(PipelineConfig, AValueOutsideItsLimitsIsAnErrorAtItsLine) {
  // For every field: the nearest value outside its limits below and above.
  for (const DeclaredLimits::Numeric& n : declared_limits().numeric) {
    const double step = n.integer ? 1.0 : std::max(1e-3, 1e-3 * std::abs(n.range.max));
    const double below = n.range.min_open ? n.range.min : n.range.min - step;
    const double above = n.range.max_open ? n.range.max : n.range.max + step;
    for (const double bad : {below, above}) {
      const std::string text = file_setting(n.path, n.integer ? number(std::round(bad)) : number(bad));
      const int line = static_cast<int>(std::count(n.path.begin(), n.path.end(), '.')) + 1;
      const std::string message = test::input_error_of([&] { parse_pipeline_config(text, "p.yaml"); });
      EXPECT_NE(message.find("p.yaml:" + std::to_string(line) + ": " + n.path + ": must be"),
                std::string::npos)
          << text << " -> " << message;
    }
  }
}

TEST(PipelineConfig, ValuesThatWouldHangOrCrashARunAreRefused) {
  // Found by trying every numeric key with extreme values: each hung or crashed a run.
  for (const auto& [path, value] : std::vector<std::pair<std::string, std::string>>{
           {"ground.resolution", "1e-9"},
           {"ground.num_iter", "2000000000"},
           {"aisle.width_directions", "100000000"},
           {"loop_closure.registration.max_iterations", "2000000000"},
           {"esdf_free_space.voxel_size", "1e-6"},
           {"sight_map.cell", "1e-9"},
           {"room_segmentation.cell", "1e-9"},
           {"plane_extraction.max_planes", "0"},
           {"plane_extraction.max_range", "-1"},
           {"ground.resolution", "0"},
           // Issue 52: each of these emptied a layer at 0.
           {"ground.seed_height_tolerance", "0"},
           {"ground.seed_max_slope", "0"},
           {"ground.bgk_max_height_gap", "0"},
           {"esdf_free_space.slice_height", "0"},
           {"esdf_free_space.robot_radius", "0"},
           {"esdf_free_space.robot_height_tolerance", "0"},
           {"sgraphs_room_extraction.max_normal_z", "0"}}) {
    const std::string text = file_setting(path, value);  // (clang: a lambda captures no structured binding)
    EXPECT_NE(test::input_error_of([&] { parse_pipeline_config(text, "p.yaml"); }).find(path + ": must be"),
              std::string::npos)
        << path << ": " << value;
  }
}

TEST(PipelineConfig, ConfigsBuiltInCodeAreCheckedAgainstTheSameDeclarations) {
  odometry::LidarOdometryConfig odometry;
  odometry.max_iterations = 0;
  try {
    odometry::LidarOdometry check(odometry);
    FAIL() << "max_iterations 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "LidarOdometryConfig: max_iterations must be in [1, 1000]");
  }
  odometry::DeskewConfig deskew;
  deskew.registration.final_distance = 2.0 * deskew.registration.initial_distance;
  try {
    check_config(deskew, "DeskewConfig");
    FAIL() << "final_distance above initial_distance accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "DeskewConfig: final_distance must be <= initial_distance");
  }
  EXPECT_NO_THROW(check_config(PipelineConfig{}, "PipelineConfig"));  // the defaults lie within
  PipelineConfig c;
  c.loop_closure.registration.voxel_size = -1.0;
  try {
    check_config(c, "PipelineConfig");
    FAIL() << "voxel_size -1 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "PipelineConfig: loop_closure.registration.voxel_size must be in [0, 100]");
  }
}

TEST(PipelineConfig, APipelineBuiltInCodeIsCheckedAsAFileIs) {
  PipelineConfig c;
  c.ground.max_range = c.ground.min_range;  // no module checks the ground's config itself
  try {
    Pipeline pipeline(c);
    FAIL() << "ground.max_range == min_range accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "PipelineConfig: ground.max_range must be > min_range");
  }
}

TEST(PipelineConfig, RulesBetweenFieldsAreErrorsAtTheKeyTheyName) {
  for (const auto& [text, where] : std::vector<std::pair<std::string, std::string>>{
           {"prefilter:\n  max_range: 0.2\n", "p.yaml:2: prefilter.max_range: must be > min_range"},
           {"lidar_odometry:\n  min_range: 60\n", "p.yaml:2: lidar_odometry.max_range: must be > min_range"},
           {"ground:\n  max_range: 0.4\n", "p.yaml:2: ground.max_range: must be > min_range"},
           {"floor_levelling:\n  max_range: 0.5\n",
            "p.yaml:2: floor_levelling.max_range: must be > min_range"},
           {"deskew:\n  final_distance: 2.0\n",
            "p.yaml:2: deskew.final_distance: must be <= initial_distance"},
           {"free_space:\n  obstacle_max_height: 0.1\n",
            "p.yaml:2: free_space.obstacle_max_height: must be > obstacle_min_height"},
           {"optimizer:\n  sparse_library: accelerate_sparse\n",
            "p.yaml:2: optimizer.sparse_library: must be one this Ceres was built with"}}) {
    const std::string message = test::input_error_of([&, t = text] { parse_pipeline_config(t, "p.yaml"); });
    EXPECT_NE(message.find(where), std::string::npos) << text << " -> " << message;
  }
}

TEST(PipelineConfig, BaselineModeIsTwoKeys) {
  const PipelineConfig c =
      parse_pipeline_config("room_layer:\n  free_space_method: esdf\n  room_trigger: timer\n", "p.yaml");
  EXPECT_EQ(c.rooms.layer.free_space_method, room_layer::FreeSpaceMethod::esdf);
  EXPECT_EQ(c.rooms.layer.room_trigger, room_layer::RoomTrigger::timer);
  EXPECT_DOUBLE_EQ(c.rooms.timer.period_s, 1.0);
}

TEST(PipelineConfig, SensorFilesMatchTheGroundPresets) {
  for (const std::string preset : {"vlp-16", "hesai-xt32"}) {
    const PipelineConfig c =
        load_pipeline_config(std::string(TSGRAPHS_SOURCE_DIR) + "/config/sensors/" + preset + ".yaml");
    PipelineConfig expected;
    expected.ground = ground::per_sensor_preset(preset);
    EXPECT_EQ(dump_pipeline_config(c), dump_pipeline_config(expected)) << preset;
  }
}
