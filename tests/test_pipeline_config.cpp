// The parameter file: config/params.yaml lists every key with the code's default; unknown
// keys, wrong types and impossible values are errors naming the file, line and key.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <set>
#include <sstream>

#include "test_support.hpp"
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

}  // namespace

TEST(PipelineConfig, ShippedParamsFileHasEveryKeyWithTheCodeDefault) {
  const PipelineConfig loaded = load_pipeline_config(kParams);
  EXPECT_EQ(dump_pipeline_config(loaded), dump_pipeline_config(PipelineConfig{}))
      << "config/params.yaml and the config structs' defaults disagree";
  EXPECT_EQ(leaf_keys(YAML::LoadFile(kParams)), leaf_keys(YAML::Load(dump_pipeline_config(PipelineConfig{}))))
      << "config/params.yaml must list every key";
}

TEST(PipelineConfig, DumpReadsBackToTheSameConfig) {
  PipelineConfig c;
  c.prefilter.voxel_size = 0.15;
  c.optimizer.linear_solver = "dense_schur";
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
  EXPECT_EQ(input_error_of([] { parse_pipeline_config("prefilter:\n  voxel: 0.2\n", "p.yaml"); }).substr(0, 30),
            "p.yaml:2: unknown key 'prefilt");
  EXPECT_NE(input_error_of([] { parse_pipeline_config("walls: {}\n", "p.yaml"); }).find("unknown key 'walls'"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("keyframes:\n  delta_trans: far\n", "p.yaml"); })
                .find("p.yaml:2: keyframes.delta_trans: expected a number"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("keyframes:\n  delta_trans: -1\n", "p.yaml"); })
                .find("p.yaml:2"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("optimizer:\n  linear_solver: magic\n", "p.yaml"); })
                .find("unknown linear_solver 'magic'"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("loop_closure:\n  registration:\n    voxel_size: .nan\n", "p.yaml"); })
                .find("p.yaml:3"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { load_pipeline_config("/nonexistent/params.yaml"); }).find("/nonexistent/params.yaml"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("room_layer:\n  free_space_method: voxblox\n", "p.yaml"); })
                .find("p.yaml:2: room_layer.free_space_method: free_space_method must be traversable or esdf"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("room_layer:\n\n  room_trigger: often\n", "p.yaml"); })
                .find("p.yaml:3: room_layer.room_trigger"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("room_association:\n  footprint: big\n", "p.yaml"); })
                .find("p.yaml:2: room_association.footprint"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("room_association:\n  min_overlap: 1.5\n", "p.yaml"); })
                .find("p.yaml:2: room_association.min_overlap: min_overlap must be in (0, 1]"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { parse_pipeline_config("room_segmentation:\n  wall_joint_gap: -1\n", "p.yaml"); })
                .find("p.yaml:2: room_segmentation.wall_joint_gap"),
            std::string::npos);
}

TEST(PipelineConfig, BaselineModeIsTwoKeys) {
  const PipelineConfig c =
      parse_pipeline_config("room_layer:\n  free_space_method: esdf\n  room_trigger: timer\n", "p.yaml");
  EXPECT_EQ(c.rooms.layer.free_space_method, "esdf");
  EXPECT_EQ(c.rooms.layer.room_trigger, "timer");
  EXPECT_DOUBLE_EQ(c.rooms.timer.period_s, 1.0);
}

TEST(PipelineConfig, SensorFilesMatchTheGroundPresets) {
  for (const std::string preset : {"vlp-16", "hesai-xt32"}) {
    const PipelineConfig c = load_pipeline_config(std::string(TSGRAPHS_SOURCE_DIR) + "/config/sensors/" + preset + ".yaml");
    PipelineConfig expected;
    expected.ground = ground::per_sensor_preset(preset);
    EXPECT_EQ(dump_pipeline_config(c), dump_pipeline_config(expected)) << preset;
  }
}
