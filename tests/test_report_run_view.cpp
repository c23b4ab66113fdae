// read_run_view: every field read from a small run folder and the sequence folder it ran
// on; missing and malformed files named in the InputError; level_of_height, visited_levels
// and main_level.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/run_folder.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/report/run_view.hpp"

namespace tsgraphs {
namespace {

namespace fs = std::filesystem;
using report::read_run_view;
using report::RunView;

// Two walls and a floor plane (left out), three nodes, a room and a corridor with free
// space (the corridor on level 1), two levels.
constexpr const char* kSceneGraph = R"({
  "format": "tsgraphs-scene-graph", "version": 1, "frame": "map",
  "keyframes": [],
  "planes": [
    {"id": 4, "kind": "wall", "n": [1, 0, 0], "d": -1, "keyframes": [0], "num_points": 100,
     "centroid": [1, 2, 1], "segment": [[1.0, 0.5], [1.0, 3.5]], "z_range": [0.02, 2.9]},
    {"id": 5, "kind": "horizontal", "n": [0, 0, 1], "d": 0, "keyframes": [0], "num_points": 900,
     "centroid": [2, 2, 0]},
    {"id": 9, "kind": "wall", "n": [0, 1, 0], "d": -4, "keyframes": [0, 1], "num_points": 80,
     "centroid": [3, 4, 4], "segment": [[0.5, 4.0], [5.5, 4.25]], "z_range": [3.1, 5.75]}
  ],
  "traversable_nodes": [
    {"id": 0, "position": [1.5, 2.0, 0.01], "normal": [0, 0, 1], "probability": 0.9},
    {"id": 1, "position": [2.0, 2.5, -0.02], "normal": [0, 0, 1], "probability": 0.8},
    {"id": 2, "position": [2.5, 3.0, 3.0], "normal": [0, 0, 1], "probability": 0.7}
  ],
  "rooms": [
    {"id": 1, "kind": "room", "level": 0, "node": 0, "walls": [4],
     "rect": {"center": [2.0, 2.5], "size": [3.0, 4.0], "yaw": 0.25},
     "free_space": [[1.5, 2.0, 0.0], [2.0, 2.5, 0.05]]},
    {"id": 3, "kind": "corridor", "level": 1, "node": null, "walls": [],
     "rect": {"center": [4.0, 1.0], "size": [6.0, 2.0], "yaw": -1.5},
     "free_space": [[4.0, 1.0, 3.0]]},
    {"id": 6, "kind": "room", "level": 0, "node": null, "walls": [],
     "rect": {"center": [0.0, 0.0], "size": [1.0, 1.0], "yaw": 0.0}}
  ],
  "room_nodes": [], "floors": [],
  "levels": [0.0, 3.0],
  "edges": []
})";

constexpr const char* kTrajectory =
    "0.0 1.0 2.0 0.55 0 0 0 1\n"
    "0.1 1.25 2.0 0.56 0 0 0 1\n"
    "0.2 1.5 2.0 3.55 0 0 0 1\n";

// The header of a real timings.csv (pipeline/run_app).
constexpr const char* kTimingsHeader =
    "kind,index,stamp,keyframe,num_points,prefilter_ms,walls_ms,loop_ms,frontend_ms,optimization_s,full,"
    "n_variables,n_factors,iterations,reason,ground_ms,ground_nodes,ground_tp,ground_fp,ground_fn,rooms_ms\n";
constexpr const char* kTimingsRows =
    "scan,0,0.000000,0,11760,1.941,13.981,0.001,24.151,,,,,,,6.718,453,12365,6,897,1.451\n"
    "scan,1,0.100000,-1,11768,1.928,0.000,0.000,8.781,,,,,,,6.851,465,12425,4,836,0.000\n"
    "optimization,0,0.100000,4,,,,,,0.000453,1,19,58,3,loop,,,,,,\n";

constexpr const char* kMetrics = R"({"consistency": {"N1st": 1.0, "dcs": null}})";

constexpr const char* kScene = R"(name: tiny
levels:
  - {name: ground, elevation: 0.0, slab: [[0,0],[6,0],[6,5],[0,5]]}
  - {name: upper, elevation: 3.0, slab: [[0,0],[6,0],[6,5],[0,5]]}
trajectory: {waypoints: [[1,2],[5,2]], closed: false, laps: 1}
)";

io::RoomEvent event(int room_id, int lap) {
  io::RoomEvent e;
  e.room_id = room_id;
  e.lap = lap;
  e.t = 1.0 * lap;
  e.rect.size = Vec2(2.0, 2.0);
  return e;
}

class ReportRunView : public test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    run_ = dir_ / "run_A";
    seq_ = dir_ / "seq";
    fs::create_directories(run_);
    write_file("run_A/scene_graph.json", kSceneGraph);
    write_file("run_A/trajectory.txt", kTrajectory);
    write_file("run_A/timings.csv", std::string(kTimingsHeader) + kTimingsRows);
    // Room 1 is first extracted in lap 2 (and again in lap 3); room 3 in lap 1.
    std::string events;
    for (const auto& e : {event(1, 3), event(3, 1), event(1, 2), event(3, 2)}) {
      events += io::format_room_event(e) + "\n";
    }
    write_file("run_A/rooms_events.jsonl", events);
    write_file("run_A/metrics.json", kMetrics);

    io::SequenceInfo info;
    info.times = {0.0, 0.1, 0.2};
    for (int i = 0; i < 3; ++i) {
      info.odometry.push_back(make_pose(Eigen::Vector3d(1.0 + 0.25 * i, 2.0, 0.55), 0.0));
      info.groundtruth.push_back(make_pose(Eigen::Vector3d(1.0 + 0.25 * i, 2.1, 0.55 + i), 0.0));
    }
    info.has_rooms = true;
    info.rooms.push_back({"hall", "ground", {{0, 0}, {4, 0}, {4, 5}, {0, 5}}, 0.0});
    info.rooms.push_back({"loft", "upper", {{0, 0}, {6, 0}, {6, 5}}, 3.0});
    info.scene_yaml = kScene;
    io::SequenceWriter writer(seq_.string());
    for (std::size_t i = 0; i < 3; ++i) writer.write_scan(i, PointCloud());
    writer.commit(info);
  }

  fs::path run_, seq_;
};

TEST_F(ReportRunView, ReadsEveryPartOfTheRunFolder) {
  const RunView run = read_run_view(run_.string());
  EXPECT_EQ(run.label, "run_A");

  ASSERT_EQ(run.walls.size(), 2u);  // the horizontal plane is not a wall
  EXPECT_EQ(run.walls[0].id, 4);
  EXPECT_EQ(run.walls[0].a, Vec2(1.0, 0.5));
  EXPECT_EQ(run.walls[0].b, Vec2(1.0, 3.5));
  EXPECT_DOUBLE_EQ(run.walls[0].z0, 0.02);
  EXPECT_DOUBLE_EQ(run.walls[0].z1, 2.9);
  EXPECT_EQ(run.walls[1].id, 9);
  EXPECT_EQ(run.walls[1].b, Vec2(5.5, 4.25));
  EXPECT_DOUBLE_EQ(run.walls[1].z0, 3.1);

  ASSERT_EQ(run.nodes.size(), 3u);
  EXPECT_EQ(run.nodes[1].p, Eigen::Vector3d(2.0, 2.5, -0.02));
  EXPECT_EQ(run.nodes[2].p, Eigen::Vector3d(2.5, 3.0, 3.0));

  ASSERT_EQ(run.rooms.size(), 3u);
  const RunView::Room& room = run.rooms[0];
  EXPECT_EQ(room.id, 1);
  EXPECT_EQ(room.kind, "room");
  EXPECT_EQ(room.level, 0);
  EXPECT_EQ(room.rect.center, Vec2(2.0, 2.5));
  EXPECT_EQ(room.rect.size, Vec2(3.0, 4.0));
  EXPECT_DOUBLE_EQ(room.rect.yaw, 0.25);
  EXPECT_EQ(room.first_lap, 2);  // the lowest lap of its events, whatever their order
  ASSERT_EQ(room.free_space.size(), 2u);
  EXPECT_EQ(room.free_space[1], Eigen::Vector3d(2.0, 2.5, 0.05));
  const RunView::Room& corridor = run.rooms[1];
  EXPECT_EQ(corridor.id, 3);
  EXPECT_EQ(corridor.kind, "corridor");
  EXPECT_EQ(corridor.level, 1);
  EXPECT_DOUBLE_EQ(corridor.rect.yaw, -1.5);
  EXPECT_EQ(corridor.first_lap, 1);
  ASSERT_EQ(corridor.free_space.size(), 1u);
  // A room without events or free space.
  EXPECT_EQ(run.rooms[2].first_lap, 0);
  EXPECT_TRUE(run.rooms[2].free_space.empty());

  EXPECT_EQ(run.levels, (std::vector<double>{0.0, 3.0}));

  ASSERT_EQ(run.estimated.size(), 3u);
  EXPECT_DOUBLE_EQ(run.estimated[1].t, 0.1);
  EXPECT_EQ(run.estimated[1].p, Eigen::Vector3d(1.25, 2.0, 0.56));

  ASSERT_EQ(run.scans.size(), 2u);
  EXPECT_DOUBLE_EQ(run.scans[0].t, 0.0);
  EXPECT_DOUBLE_EQ(run.scans[0].frontend_ms, 24.151);
  EXPECT_DOUBLE_EQ(run.scans[1].t, 0.1);
  EXPECT_DOUBLE_EQ(run.scans[1].frontend_ms, 8.781);
  ASSERT_EQ(run.solves.size(), 1u);
  EXPECT_DOUBLE_EQ(run.solves[0].t, 0.1);
  EXPECT_DOUBLE_EQ(run.solves[0].seconds, 0.000453);
  EXPECT_TRUE(run.solves[0].full);

  EXPECT_EQ(run.metrics_json, kMetrics);
  // Without the sequence: no ground truth and no scene.
  EXPECT_TRUE(run.truth.empty());
  EXPECT_TRUE(run.truth_rooms.empty());
  EXPECT_FALSE(run.scene.has_value());
}

TEST_F(ReportRunView, ReadsTheSequencesGroundTruthAndScene) {
  const RunView run = read_run_view(run_.string(), seq_.string());
  ASSERT_EQ(run.truth.size(), 3u);
  EXPECT_DOUBLE_EQ(run.truth[2].t, 0.2);
  EXPECT_TRUE(run.truth[2].p.isApprox(Eigen::Vector3d(1.5, 2.1, 2.55)));
  ASSERT_EQ(run.truth_rooms.size(), 2u);
  EXPECT_EQ(run.truth_rooms[0].name, "hall");
  EXPECT_EQ(run.truth_rooms[1].level, "upper");
  EXPECT_DOUBLE_EQ(run.truth_rooms[1].elevation, 3.0);
  EXPECT_EQ(run.truth_rooms[1].polygon.size(), 3u);
  ASSERT_TRUE(run.scene.has_value());
  EXPECT_EQ(run.scene->name, "tiny");
  EXPECT_EQ(run.scene->levels.size(), 2u);
  // The run's own parts are read as without the sequence.
  EXPECT_EQ(run.walls.size(), 2u);
  EXPECT_EQ(run.rooms[0].first_lap, 2);
}

TEST_F(ReportRunView, OptionalFilesMayBeMissing) {
  fs::remove(run_ / "rooms_events.jsonl");
  fs::remove(run_ / "metrics.json");
  const RunView run = read_run_view(run_.string());
  for (const RunView::Room& r : run.rooms) EXPECT_EQ(r.first_lap, 0) << r.id;
  EXPECT_EQ(run.metrics_json, "");
  EXPECT_EQ(run.rooms.size(), 3u);
}

TEST_F(ReportRunView, MissingRequiredFilesAreNamed) {
  for (const char* name : {"scene_graph.json", "trajectory.txt", "timings.csv"}) {
    SCOPED_TRACE(name);
    const fs::path moved = dir_ / (std::string(name) + ".away");
    fs::rename(run_ / name, moved);
    const std::string msg = test::input_error_of([&] { read_run_view(run_.string()); });
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
    fs::rename(moved, run_ / name);
  }
  EXPECT_NE(test::input_error_of([&] { read_run_view((dir_ / "nowhere").string()); }).find("nowhere"),
            std::string::npos);
}

TEST_F(ReportRunView, MalformedTimingsLineIsNamedWithItsLine) {
  // Line 3 (the second scan row) has a broken front-end time.
  const std::string rows =
      "scan,0,0.000000,0,11760,1.941,13.981,0.001,24.151,,,,,,,6.718,453,12365,6,897,1.451\n"
      "scan,1,0.100000,-1,11768,1.928,0.000,0.000,8.7x1,,,,,,,6.851,465,12425,4,836,0.000\n";
  write_file("run_A/timings.csv", std::string(kTimingsHeader) + rows);
  std::string msg = test::input_error_of([&] { read_run_view(run_.string()); });
  EXPECT_NE(msg.find("timings.csv:3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("frontend_ms"), std::string::npos) << msg;
  // An unknown row kind, and a header without the needed columns.
  write_file("run_A/timings.csv",
             std::string(kTimingsHeader) + "scan,0,0.0,0,1,1,1,1,1.0,,,,,,,1,1,1,1,1,1\nbogus,1\n");
  msg = test::input_error_of([&] { read_run_view(run_.string()); });
  EXPECT_NE(msg.find("timings.csv:3:"), std::string::npos) << msg;
  write_file("run_A/timings.csv", "kind,index,stamp\nscan,0,0.0\n");
  msg = test::input_error_of([&] { read_run_view(run_.string()); });
  EXPECT_NE(msg.find("timings.csv:1:"), std::string::npos) << msg;
}

TEST_F(ReportRunView, MalformedJsonFilesAreNamed) {
  write_file("run_A/scene_graph.json", "{\"planes\": [");
  EXPECT_NE(test::input_error_of([&] { read_run_view(run_.string()); }).find("scene_graph.json"),
            std::string::npos);
  // Valid JSON of the wrong shape: a node position with two coordinates.
  std::string graph = kSceneGraph;
  graph.replace(graph.find("[2.5, 3.0, 3.0]"), 15, "[2.5, 3.0]");
  write_file("run_A/scene_graph.json", graph);
  const std::string msg = test::input_error_of([&] { read_run_view(run_.string()); });
  EXPECT_NE(msg.find("scene_graph.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("traversable_nodes"), std::string::npos) << msg;
  write_file("run_A/scene_graph.json", kSceneGraph);
  write_file("run_A/metrics.json", "{nope");
  EXPECT_NE(test::input_error_of([&] { read_run_view(run_.string()); }).find("metrics.json"),
            std::string::npos);
}

TEST_F(ReportRunView, MalformedTrajectoryAndEventsAreNamedWithTheirLine) {
  write_file("run_A/trajectory.txt", "0.0 1 2 0.55 0 0 0 1\n0.1 1 2\n");
  EXPECT_NE(test::input_error_of([&] { read_run_view(run_.string()); }).find("trajectory.txt:2"),
            std::string::npos);
  write_file("run_A/trajectory.txt", kTrajectory);
  write_file("run_A/rooms_events.jsonl", io::format_room_event(event(1, 1)) + "\n{broken\n");
  EXPECT_NE(test::input_error_of([&] { read_run_view(run_.string()); }).find("rooms_events.jsonl:2"),
            std::string::npos);
}

TEST(ReportRunViewLevels, HeightsBelongToTheFloorBelowThem) {
  RunView run;
  EXPECT_EQ(report::level_of_height(run, -7.0), 0);  // no levels: everything on level 0
  run.levels = {3.0, 0.0};                           // not sorted: the index is the level
  EXPECT_EQ(report::level_of_height(run, 0.55), 1);
  EXPECT_EQ(report::level_of_height(run, -0.3), 1);   // a floor point's noise
  EXPECT_EQ(report::level_of_height(run, -1.0), -1);  // far below the lowest floor
  EXPECT_EQ(report::level_of_height(run, 2.9), 0);    // a wall plane starting under the slab
  EXPECT_EQ(report::level_of_height(run, 3.55), 0);
  EXPECT_EQ(report::level_of_height(run, 6.5), -1);  // above the top storey
}

TEST(ReportRunViewLevels, VisitedAndMainLevels) {
  RunView run;
  EXPECT_EQ(report::visited_levels(run), std::vector<int>{0});
  EXPECT_EQ(report::main_level(run), 0);
  run.levels = {0.0, 3.0, 6.0};
  for (int i = 0; i < 3; ++i) run.estimated.push_back({0.1 * i, Eigen::Vector3d(0, 0, 3.55)});
  run.estimated.push_back({0.5, Eigen::Vector3d(0, 0, 0.55)});
  EXPECT_EQ(report::visited_levels(run), (std::vector<int>{0, 1}));
  EXPECT_EQ(report::main_level(run), 1);
  RunView::Room room;
  room.level = 2;
  run.rooms.push_back(room);
  EXPECT_EQ(report::visited_levels(run), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(report::main_level(run), 1);
}

}  // namespace
}  // namespace tsgraphs
