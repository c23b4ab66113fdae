// evaluate_run on small hand-made run and sequence folders (written through io/run_folder):
// the ground-truth room figures, unsupported rooms from the scene or from the true rooms, the
// IPA figures, and null figures (not a crash) for a run without rooms.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "tsgraphs/eval/run_evaluation.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/run_folder.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs {
namespace {

namespace fs = std::filesystem;

// A 20 m x 10 m floor with a void [14,18] x [2,8] and a wall on x = 6 (door at y 7..8).
constexpr const char* kScene = R"(name: eval_toy
levels:
  - {name: L0, elevation: 0.0, slab: [[0, 0], [20, 0], [20, 10], [0, 10]],
     voids: [[[14, 2], [18, 2], [18, 8], [14, 8]]]}
walls:
  - level: L0
    from: [6, 0]
    to: [6, 10]
    openings:
      - {at: 7.5, width: 1.0, height: 2.1, sill: 0.0}
trajectory: {level: L0, waypoints: [[2, 5], [10, 5]], closed: false, laps: 1}
)";

Polygon2 box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

OrientedRect rect(double x0, double y0, double x1, double y1) {
  OrientedRect r;
  r.center = Vec2(0.5 * (x0 + x1), 0.5 * (y0 + y1));
  r.size = Vec2(x1 - x0, y1 - y0);
  return r;
}

class EvalRun : public test::TempDirTest {
 protected:
  // A sequence of 5 scans walking from the west room into the east one; the run's map frame is
  // the world shifted by (1, -2) and turned by 90 degrees, so that placing the rooms matters.
  void SetUp() override {
    TempDirTest::SetUp();
    seq_ = (dir_ / "seq").string();
    run_ = (dir_ / "run").string();
    T_map_world_ = make_pose({1.0, -2.0, 0.0}, M_PI / 2);
    io::SequenceInfo info;
    for (int i = 0; i < 5; ++i) {
      info.times.push_back(0.1 * i);
      const Pose3 truth = make_pose({2.0 + 2.0 * i, 5.0, 0.55}, 0.0);
      info.groundtruth.push_back(truth);
      info.odometry.push_back(T_map_world_ * truth);
    }
    info.has_rooms = true;
    info.rooms = {{"west", "L0", box(0, 0, 5.9, 10), 0.0}, {"east", "L0", box(6.1, 0, 14, 10), 0.0}};
    info.scene_yaml = kScene;
    io::SequenceWriter writer(seq_);
    for (std::size_t i = 0; i < 5; ++i) writer.write_scan(i, PointCloud());
    writer.commit(info);
    truth_ = info.groundtruth;
  }

  // The run folder: one keyframe at scan 0, and `rooms` given in the world frame.
  void write_run(const std::vector<OrientedRect>& world_rooms, bool with_scene_graph_levels = true) {
    fs::create_directories(run_);
    std::vector<io::StampedPose> trajectory;
    io::Timings timings;
    for (std::size_t i = 0; i < truth_.size(); ++i) {
      trajectory.push_back({0.1 * i, T_map_world_ * truth_[i]});
      io::ScanTiming s;
      s.index = i;
      s.stamp = 0.1 * i;
      s.frontend_ms = 10.0;
      timings.scans.push_back(s);
    }
    io::write_file_atomic(run_ + "/" + io::run_files::kTrajectory, io::format_tum(trajectory));
    io::write_file_atomic(run_ + "/" + io::run_files::kTimings, io::format_timings(timings));
    io::RunSummary summary;
    summary.rtf = 5.0;
    io::write_file_atomic(run_ + "/" + io::run_files::kRunInfo, io::format_run_summary(summary));
    io::SceneGraph graph;
    graph.keyframes.push_back({0, 0, 0.0, 0.0, io::PoseRecord::of(T_map_world_ * truth_[0]),
                               io::PoseRecord::of(T_map_world_ * truth_[0])});
    for (std::size_t i = 0; i < world_rooms.size(); ++i) {
      io::SceneGraph::Room room;
      room.id = static_cast<int>(i);
      room.rect = world_rooms[i];
      room.rect.center =
          (T_map_world_ * Eigen::Vector3d(room.rect.center.x(), room.rect.center.y(), 0)).head<2>();
      room.rect.yaw += M_PI / 2;
      graph.rooms.push_back(room);
    }
    if (with_scene_graph_levels) graph.levels = {0.0};
    io::write_file_atomic(run_ + "/" + io::run_files::kSceneGraph, io::format_scene_graph(graph));
  }

  eval::Metrics evaluate(bool with_sequence = true) {
    eval::EvalOptions options;
    options.run_dir = run_;
    if (with_sequence) options.seq_dir = seq_;
    return eval::evaluate_run(options);
  }

  std::string seq_, run_;
  Pose3 T_map_world_;
  std::vector<Pose3> truth_;
};

TEST_F(EvalRun, ARunWithoutRoomsHasNullFiguresNotACrash) {
  write_run({});
  const eval::Metrics m = evaluate();
  EXPECT_EQ(m.rooms_gt.n_rooms_final, 0.0);
  EXPECT_EQ(m.rooms_gt.n_truth_visited, 2.0);
  EXPECT_EQ(m.rooms_gt.unsupported, 0.0);  // no room stands on a void
  EXPECT_FALSE(m.rooms_gt.unsupported_fraction_max);
  EXPECT_FALSE(m.rooms_gt.ipa_precision_micro);
  EXPECT_FALSE(m.rooms_gt.ipa_precision_macro);
  EXPECT_EQ(m.rooms_gt.ipa_recall_micro, 0.0);  // two rooms the path entered, none found
  EXPECT_EQ(m.rooms_gt.ipa_recall_macro, 0.0);
  const auto j = nlohmann::json::parse(eval::metrics_json(m));
  EXPECT_TRUE(j["rooms_gt"]["unsupported_fraction_max"].is_null());
  EXPECT_TRUE(j["rooms_gt"]["ipa_precision_micro"].is_null());
  EXPECT_NE(eval::metrics_table(m).find("unsupported (max share)      0 (-)"), std::string::npos)
      << eval::metrics_table(m);
  // Without the sequence nothing of the ground truth is known.
  const eval::Metrics alone = evaluate(false);
  EXPECT_FALSE(alone.rooms_gt.unsupported);
  EXPECT_FALSE(alone.rooms_gt.ipa_recall_micro);
}

TEST_F(EvalRun, RoomsArePlacedInTheTruthFrameAndJudged) {
  // West exactly; east's west 7.9 m (x 6.1..14); a room half over the void (x 12..16).
  write_run({rect(0, 0, 5.9, 10), rect(6.1, 0, 14, 10), rect(12, 3, 16, 5)});
  const eval::Metrics m = evaluate();
  EXPECT_EQ(m.rooms_gt.n_rooms_final, 3.0);
  EXPECT_EQ(m.rooms_gt.unsupported, 1.0);
  ASSERT_TRUE(m.rooms_gt.unsupported_fraction_max);
  EXPECT_NEAR(*m.rooms_gt.unsupported_fraction_max, 0.5, 1e-9);
  // IPA: the small room (x 12..14 in the free space: 40 x 40 = 1600 cells) takes its cells from
  // east (158 x 200 = 31600 cells), which keeps 30000; all three lie in one room each.
  // precision 1; recall_micro = (1 + 30000/31600) / 2, recall_macro = (23600 + 30000) / (23600 + 31600).
  ASSERT_TRUE(m.rooms_gt.ipa_precision_micro && m.rooms_gt.ipa_recall_micro && m.rooms_gt.ipa_recall_macro);
  EXPECT_NEAR(*m.rooms_gt.ipa_precision_micro, 1.0, 1e-12);
  EXPECT_NEAR(*m.rooms_gt.ipa_precision_macro, 1.0, 1e-12);
  EXPECT_NEAR(*m.rooms_gt.ipa_recall_micro, (1.0 + 30000.0 / 31600.0) / 2.0, 1e-12);
  EXPECT_NEAR(*m.rooms_gt.ipa_recall_macro, 53600.0 / 55200.0, 1e-12);
}

TEST_F(EvalRun, WithoutASceneTheTrueRoomsJudgeSupport) {
  write_run({rect(0, 0, 5.9, 10), rect(12, 3, 16, 5)});
  fs::remove(fs::path(seq_) / "scene.yaml");
  const eval::Metrics m = evaluate();
  EXPECT_EQ(m.rooms_gt.unsupported, 1.0);
  EXPECT_NEAR(*m.rooms_gt.unsupported_fraction_max, 0.5, 1e-9);  // x 14..16 is in no true room
}

TEST_F(EvalRun, AnAbsurdFootprintIsAnInputErrorNamingIt) {
  write_run({rect(0, 0, 5.9, 10), rect(0, 0, 1e4, 1e4)});
  const std::string msg = test::input_error_of([&] { evaluate(); });
  EXPECT_NE(msg.find("scene_graph.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("rooms[1]"), std::string::npos) << msg;
}

}  // namespace
}  // namespace tsgraphs
