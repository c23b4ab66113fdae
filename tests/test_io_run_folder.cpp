// The run folder's schema (io/run_folder.hpp): every file round-trips through its formatter and
// reader, byte for byte; the bytes are those `run` has always written; unknown keys and columns
// are ignored; a malformed line, a missing key or a wrong type is an InputError naming the
// file and the line or key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "test_support.hpp"
#include "tsgraphs/io/run_folder.hpp"

using namespace tsgraphs;
using namespace tsgraphs::io;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using tsgraphs::test::input_error_of;

namespace {

// Replaces the first `from` in `text` (which must hold it).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

OrientedRect rect(double cx, double cy, double sx, double sy, double yaw) {
  OrientedRect r;
  r.center = Vec2(cx, cy);
  r.size = Vec2(sx, sy);
  r.yaw = yaw;
  return r;
}

// A graph with one of everything, numbers that are not short decimals, a plane without
// points, a room without a node.
SceneGraph sample_graph() {
  SceneGraph g;
  const Pose3 a = make_pose({1.0 / 3.0, -2.5, 0.55}, 0.7), b = make_pose({4.0, 1e-7, 0.5}, -2.9, 0.01);
  g.keyframes.push_back({0, 0, 0.0, 0.0, PoseRecord::of(a), PoseRecord::of(a)});
  g.keyframes.push_back({1, 17, 1.7000000000000002, 1.0 / 7.0, PoseRecord::of(b), PoseRecord::of(a)});
  g.keyframes.push_back({2, 19, 1.9, 0.5, PoseRecord::of(b), PoseRecord::of(a), 0});  // retired, following 0
  SceneGraph::Plane wall;
  wall.id = 3;
  wall.n = Eigen::Vector3d(0.6, 0.8, 0.0);
  wall.d = -2.0 / 3.0;
  wall.keyframes = {0, 1};
  wall.num_points = 1234;
  wall.centroid = Eigen::Vector3d(1, 2, 1.25);
  wall.segment = std::array<Vec2, 2>{Vec2(0.1, 0.2), Vec2(3.3, -0.4)};
  wall.z_range = std::array<double, 2>{0.02, 2.9};
  g.planes.push_back(wall);
  SceneGraph::Plane floor;
  floor.id = 5;
  floor.kind = "horizontal";
  floor.n = Eigen::Vector3d::UnitZ();
  g.planes.push_back(floor);
  g.traversable_nodes.push_back({7, {1.5, 2.0, 0.01}, {0.0, 0.1, 0.99}, 0.875, 3, 1, {0, 1}});
  SceneGraph::Room room;
  room.id = 2;
  room.level = 1;
  room.rect = rect(2.0, 2.5, 3.0, 4.0, 0.25);
  room.walls = {3, 4, 9, 12};
  room.extractions = 2;
  room.node = 0;
  room.free_space = {{1.5, 2.0, 0.0}, {2.0, 2.5, 0.05}};
  g.rooms.push_back(room);
  SceneGraph::Room corridor;
  corridor.id = 4;
  corridor.kind = "corridor";
  corridor.rect = rect(-1, 0, 6, 2, -1.5);
  g.rooms.push_back(corridor);
  g.room_nodes.push_back({0, "room", 1, {2.0, 2.5}});
  g.floors.push_back({0, 1, {2.0, 2.5}});
  g.levels = {0.0, 1.620951824322115};
  g.odometry_edges.push_back({0, 1, PoseRecord::of(a.inverse() * b)});
  g.loop_edges.push_back({1, 0, 0.0123, PoseRecord::of(b.inverse() * a)});
  g.loop_edges.push_back({0, 1, 0.0125, PoseRecord::of(a.inverse() * b), 2});
  g.loop_closures.push_back({0, 2, 0.0125, PoseRecord::of(a.inverse() * b), "distance"});
  g.loop_closures.push_back({1, 2, 0.0215, PoseRecord::of(a), "room"});
  g.keyframe_plane_edges.push_back({1, 3, Eigen::Vector4d(0.6, 0.8, 0.0, -1.5)});
  g.room_planes_edges.push_back({2, "corridor", {3, 9}, {2.0, 2.5}});
  g.floor_room_edges.push_back({0, 2});
  return g;
}

RoomEvent event(int lap, const OrientedRect& r, bool is_new = true) {
  RoomEvent e;
  e.lap = lap;
  e.rect = r;
  e.center = r.center;
  e.is_new = is_new;
  return e;
}

// Rows as `run` wrote them before the schema existed (a real run's lines, and a skipped scan).
constexpr const char* kTimingsText =
    "kind,index,stamp,keyframe,num_points,prefilter_ms,walls_ms,loop_ms,frontend_ms,optimization_s,full,"
    "n_variables,n_factors,iterations,reason,ground_ms,ground_nodes,ground_tp,ground_fp,ground_fn,rooms_ms\n"
    "scan,0,0.000000,0,6534,1.675,7.240,0.001,15.869,,,,,,,6.285,152,4547,5,740,0.639\n"
    "scan,1,0.100000,-1,0,0.000,0.000,0.000,0.012,,,,,,\"empty scan: skipped\",0.000,0,-1,-1,-1,0.000\n"
    "optimization,0,0.100000,4,,,,,,0.000453,1,19,58,3,loop,,,,,,\n";
// The same as `run` writes them since keyframe retirement: the graph's keyframes after a solve.
constexpr const char* kTimingsTextNow =
    "kind,index,stamp,keyframe,num_points,prefilter_ms,walls_ms,loop_ms,frontend_ms,optimization_s,full,"
    "n_variables,n_factors,iterations,reason,ground_ms,ground_nodes,ground_tp,ground_fp,ground_fn,rooms_ms,"
    "active_keyframes\n"
    "scan,0,0.000000,0,6534,1.675,7.240,0.001,15.869,,,,,,,6.285,152,4547,5,740,0.639,\n"
    "scan,1,0.100000,-1,0,0.000,0.000,0.000,0.012,,,,,,\"empty scan: skipped\",0.000,0,-1,-1,-1,0.000,\n"
    "optimization,0,0.100000,4,,,,,,0.000453,1,19,58,3,loop,,,,,,,57\n";

}  // namespace

// ---- scene_graph.json ---------------------------------------------------------------------

class SceneGraphFile : public test::TempDirTest {};

TEST_F(SceneGraphFile, RoundTripsByteForByte) {
  const std::string text = format_scene_graph(sample_graph());
  const SceneGraph back = read_scene_graph(write_file("scene_graph.json", text));
  EXPECT_EQ(format_scene_graph(back), text);
  // Spot checks of what was read (the text equality covers the rest).
  ASSERT_EQ(back.keyframes.size(), 3u);
  EXPECT_EQ(back.keyframes[1].scan_index, 17u);
  EXPECT_EQ(back.keyframes[1].anchor, -1);
  EXPECT_EQ(back.keyframes[2].anchor, 0);
  EXPECT_EQ(back.keyframes[1].accum_distance, 1.0 / 7.0);
  EXPECT_TRUE(back.keyframes[1].pose.pose().isApprox(make_pose({4.0, 1e-7, 0.5}, -2.9, 0.01), 1e-12));
  ASSERT_EQ(back.planes.size(), 2u);
  EXPECT_EQ(back.planes[0].d, -2.0 / 3.0);
  ASSERT_TRUE(back.planes[0].segment.has_value());
  EXPECT_EQ((*back.planes[0].segment)[1], Vec2(3.3, -0.4));
  EXPECT_FALSE(back.planes[1].num_points.has_value());
  EXPECT_FALSE(back.planes[1].segment.has_value());
  ASSERT_EQ(back.rooms.size(), 2u);
  EXPECT_EQ(back.rooms[0].node, std::optional<int>(0));
  EXPECT_FALSE(back.rooms[1].node.has_value());
  EXPECT_EQ(back.rooms[0].walls, (std::vector<int>{3, 4, 9, 12}));
  EXPECT_EQ(back.rooms[1].kind, "corridor");
  EXPECT_EQ(back.levels, (std::vector<double>{0.0, 1.620951824322115}));
  ASSERT_EQ(back.loop_edges.size(), 2u);
  EXPECT_EQ(back.loop_edges[0].fitness, 0.0123);
  EXPECT_EQ(back.loop_edges[0].folded, 0);
  EXPECT_EQ(back.loop_edges[1].folded, 2);
  ASSERT_EQ(back.loop_closures.size(), 2u);
  EXPECT_EQ(back.loop_closures[1].proposer, "room");
  EXPECT_EQ(back.loop_closures[1].to, 2);
  ASSERT_EQ(back.room_planes_edges.size(), 1u);
  EXPECT_EQ(back.room_planes_edges[0].planes, (std::vector<int>{3, 9}));
  ASSERT_EQ(back.floor_room_edges.size(), 1u);
}

TEST_F(SceneGraphFile, KeepsTheLayoutRunHasAlwaysWritten) {
  // Sorted keys, one space of indent, a final newline, "node": null for a room without one.
  const std::string text = format_scene_graph(sample_graph());
  EXPECT_THAT(text, StartsWith("{\n \"edges\": [\n  {\n   \"from\": 0,\n   \"measurement\": {"));
  EXPECT_THAT(text, HasSubstr("\n \"format\": \"tsgraphs-scene-graph\",\n \"frame\": \"map\",\n"));
  EXPECT_THAT(text, HasSubstr("\"node\": null"));
  EXPECT_THAT(text, HasSubstr("\n \"version\": 1\n}\n"));
}

TEST_F(SceneGraphFile, IgnoresUnknownKeysAndEdgeTypesAndTakesOptionalPartsAway) {
  const std::string text = R"({"format": "tsgraphs-scene-graph", "version": 2, "colour": "blue",
    "keyframes": [], "planes": [{"id": 1, "kind": "wall", "n": [1, 0, 0], "d": 0, "keyframes": [], "new": 1}],
    "edges": [{"type": "hyperedge", "members": [1, 2, 3]}, {"type": "floor_room", "floor": 0, "room": 4}]})";
  const SceneGraph g = read_scene_graph(write_file("scene_graph.json", text));
  EXPECT_EQ(g.planes.size(), 1u);
  EXPECT_TRUE(g.rooms.empty());
  EXPECT_TRUE(g.traversable_nodes.empty());
  EXPECT_TRUE(g.levels.empty());
  ASSERT_EQ(g.floor_room_edges.size(), 1u);
  EXPECT_EQ(g.floor_room_edges[0].room, 4);
}

TEST_F(SceneGraphFile, MissingKeysAndWrongTypesAreNamed) {
  const std::string good = format_scene_graph(sample_graph());
  struct Case {
    std::string from, to, says;
  };
  const std::vector<Case> cases = {
      {"\n \"planes\": [", "\n \"plains\": [", "missing key 'planes'"},
      {"\"d\": -0.6666666666666666", "\"d\": \"far\"", "'planes[0].d' must be a number"},
      {"\"yaw\": 0.25", "\"yaw_deg\": 0.25", "missing key 'rooms[0].rect.yaw'"},
      {"\"kind\": \"corridor\",\n   \"level\": 0", "\"kind\": \"hall\",\n   \"level\": 0",
       "'rooms[1].kind' must be \"room\" or \"corridor\""},
      {"\"scan_index\": 17", "\"scan_index\": -17", "'keyframes[1].scan_index' must not be negative"},
      {"\"probability\": 0.875", "\"probability\": [0.875]",
       "'traversable_nodes[0].probability' must be a number"},
      {"\"fitness\": 0.0123", "\"fitness\": null", "'edges[1].fitness' must be a number"},
      {"\"proposer\": \"room\"", "\"proposer\": 2", "'loop_closures[1].proposer' must be a string"},
      {"\"anchor\": 0", "\"anchor\": 0.5", "'keyframes[2].anchor'"},
  };
  for (const Case& c : cases) {
    const std::string path = write_file("scene_graph.json", replaced(good, c.from, c.to));
    const std::string msg = input_error_of([&] { read_scene_graph(path); });
    EXPECT_THAT(msg, StartsWith(path + ": ")) << c.says;
    EXPECT_THAT(msg, HasSubstr(c.says));
  }
}

// Positions no building has (1e308 made eval divide by zero drawing the bird's-eye) are refused
// where they are read, named by their path; a UTM-sized position is still a position.
TEST_F(SceneGraphFile, CoordinatesBeyondAnyBuildingAreNamed) {
  const nlohmann::json good = nlohmann::json::parse(format_scene_graph(sample_graph()));
  struct Case {
    const char* pointer;
    double value;
    std::string says;
  };
  const std::vector<Case> cases = {
      {"/rooms/0/rect/center/0", 1e308, "'rooms[0].rect.center[0]' is 1e+308: not a coordinate within 1e8 m"},
      {"/rooms/1/rect/size/1", 1e300, "'rooms[1].rect.size[1]' is 1e+300"},
      {"/planes/0/segment/0/0", -1e9, "'planes[0].segment[0][0]' is -1e+09"},
      {"/planes/0/d", 1e308, "'planes[0].d' is 1e+308"},
      {"/traversable_nodes/0/position/2", 1e308, "'traversable_nodes[0].position[2]'"},
      {"/keyframes/1/pose/t/0", -1e308, "'keyframes[1].pose.t[0]'"},
      {"/levels/1", 1e308, "'levels[1]'"},
      {"/room_nodes/0/center/1", 1e308, "'room_nodes[0].center[1]'"},
  };
  for (const Case& c : cases) {
    nlohmann::json bad = good;
    bad[nlohmann::json::json_pointer(c.pointer)] = c.value;
    const std::string path = write_file("scene_graph.json", bad.dump(1));
    const std::string msg = input_error_of([&] { read_scene_graph(path); });
    EXPECT_THAT(msg, StartsWith(path + ": ")) << c.pointer;
    EXPECT_THAT(msg, HasSubstr(c.says));
  }
  nlohmann::json utm = good;
  utm[nlohmann::json::json_pointer("/keyframes/1/pose/t/1")] = 5.8e6;  // a UTM northing
  EXPECT_EQ(read_scene_graph(write_file("scene_graph.json", utm.dump(1))).keyframes[1].pose.t.y(), 5.8e6);
}

// A number beyond a double (nlohmann::json throws out_of_range, not a parse error) names its line.
TEST_F(SceneGraphFile, NumbersBeyondADoubleNameTheLine) {
  const std::string good = format_scene_graph(sample_graph());
  const std::size_t at = good.find("1.620951824322115");
  ASSERT_NE(at, std::string::npos);
  const int line = 1 + static_cast<int>(std::count(good.begin(), good.begin() + static_cast<long>(at), '\n'));
  const std::string path = write_file("scene_graph.json", replaced(good, "1.620951824322115", "1e400"));
  EXPECT_EQ(input_error_of([&] { read_scene_graph(path); }),
            path + ":" + std::to_string(line) + ": number out of the range of a double: '1e400'");
  // A string holding digits is no number: the line is the number's.
  const std::string quoted = write_file("quoted.json", "{\"frame\": \"9e999\",\n \"keyframes\": [-2e400]}");
  EXPECT_THAT(input_error_of([&] { read_scene_graph(quoted); }),
              StartsWith(quoted + ":2: number out of the range"));
}

// Each file of the run folder that is a folder says so (it was read as empty, or as a
// missing file).
TEST_F(SceneGraphFile, FilesThatAreFoldersAreNamed) {
  for (const char* name : {"scene_graph.json", "rooms_events.jsonl", "timings.csv", "run_info.json"}) {
    const std::filesystem::path folder = dir_ / name;
    std::filesystem::create_directories(folder);
    const std::string msg = input_error_of([&] {
      const std::string f = folder.string();
      if (f.find("scene_graph") != std::string::npos) read_scene_graph(f);
      if (f.find("rooms_events") != std::string::npos) read_room_events(f);
      if (f.find("timings") != std::string::npos) read_timings(f);
      if (f.find("run_info") != std::string::npos) read_run_summary(f);
    });
    EXPECT_EQ(msg, folder.string() + ": is a folder, not a file");
  }
}

TEST_F(SceneGraphFile, SyntaxErrorsNameTheLine) {
  const std::string path = write_file("scene_graph.json", "{\n \"keyframes\": [],\n \"planes\": [,\n}\n");
  EXPECT_THAT(input_error_of([&] { read_scene_graph(path); }), StartsWith(path + ":3: malformed JSON"));
  const std::string missing = (dir_ / "none.json").string();
  EXPECT_THAT(input_error_of([&] { read_scene_graph(missing); }), StartsWith(missing + ": cannot open"));
}

// ---- rooms_events.jsonl -------------------------------------------------------------------

TEST(RoomEvents, FormatsTheMetricsMdExampleAsRunWritesIt) {
  // Keys sorted, as `run` has always written them (the order of metrics.md's example is not
  // kept: JSON objects are unordered).
  RoomEvent e;
  e.t = 41.2;
  e.lap = 1;
  e.room_id = 5;
  e.is_new = true;
  e.level = 0;
  e.center = Vec2(12.1, 3.4);
  e.rect = rect(12.1, 3.4, 8.0, 2.6, 0.0);
  e.walls = {17, 18, 22};
  e.kind = "room";
  EXPECT_EQ(
      format_room_event(e),
      R"({"center":[12.1,3.4],"kind":"room","lap":1,"level":0,"new":true,)"
      R"("rect":{"center":[12.1,3.4],"size":[8.0,2.6],"yaw":0.0},"room_id":5,"t":41.2,"walls":[17,18,22]})");
}

class RoomEventsFile : public test::TempDirTest {};

TEST_F(RoomEventsFile, RoundTripsExactly) {
  RoomEvent a = event(1, rect(2.2, 1.95, 4.2, 3.5, 1.0 / 3.0));
  a.t = 0.1 + 0.2;  // not a short decimal: the text must still give back the same double
  a.room_id = 0;
  a.center = Vec2(1.0 / 3.0, -2.0 / 7.0);
  a.walls = {3, 4, 9, 12};
  RoomEvent b = event(2, rect(0, -0.375, 16, 3.25, 0), false);
  b.t = 1234.5678901234567;
  b.room_id = 17;
  b.level = 1;
  b.kind = "corridor";
  const std::string text = format_room_event(a) + "\n\n" + format_room_event(b) + "\n";
  const std::vector<RoomEvent> back = read_room_events(write_file("rooms_events.jsonl", text));
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const RoomEvent& in = i == 0 ? a : b;
    const RoomEvent& out = back[i];
    EXPECT_EQ(out.t, in.t);
    EXPECT_EQ(out.lap, in.lap);
    EXPECT_EQ(out.room_id, in.room_id);
    EXPECT_EQ(out.is_new, in.is_new);
    EXPECT_EQ(out.level, in.level);
    EXPECT_EQ(out.center, in.center);
    EXPECT_EQ(out.rect.center, in.rect.center);
    EXPECT_EQ(out.rect.size, in.rect.size);
    EXPECT_EQ(out.rect.yaw, in.rect.yaw);
    EXPECT_EQ(out.walls, in.walls);
    EXPECT_EQ(out.kind, in.kind);
  }
  EXPECT_EQ(format_room_events(back), format_room_event(a) + "\n" + format_room_event(b) + "\n");
}

TEST_F(RoomEventsFile, MalformedLinesNameTheFileAndLine) {
  const std::string good = format_room_event(event(1, rect(2, 2, 4, 4, 0)));
  struct Case {
    std::string line, says;
  };
  const std::vector<Case> cases = {
      {"{\"t\": 1.0, \"lap\": ", "malformed JSON"},
      {"[1, 2, 3]", "expected a JSON object"},
      {R"({"t":1,"lap":1,"room_id":5,"new":true,"level":0,"center":[1,2],"walls":[],"kind":"room"})",
       "'rect'"},
      {R"({"t":1,"lap":1,"room_id":5,"new":true,"level":0,"center":[1,2],)"
       R"("rect":{"center":[1,2],"size":"big","yaw":0},"walls":[],"kind":"room"})",
       "'rect.size'"},
      {R"({"t":1,"lap":0,"room_id":5,"new":true,"level":0,"center":[1,2],)"
       R"("rect":{"center":[1,2],"size":[1,1],"yaw":0},"walls":[],"kind":"room"})",
       "'lap'"},
      {R"({"t":1,"lap":1,"room_id":5,"new":1,"level":0,"center":[1,2],)"
       R"("rect":{"center":[1,2],"size":[1,1],"yaw":0},"walls":[],"kind":"room"})",
       "'new'"},
      {R"({"t":1,"lap":1,"room_id":5,"new":true,"level":0.5,"center":[1,2],)"
       R"("rect":{"center":[1,2],"size":[1,1],"yaw":0},"walls":[],"kind":"room"})",
       "'level'"},
      {R"({"t":1,"lap":1,"room_id":5,"new":true,"level":0,"center":[1,2],)"
       R"("rect":{"center":[1,2],"size":[1,1],"yaw":0},"walls":[2,"x"],"kind":"room"})",
       "'walls[1]'"},
      {R"({"t":1,"lap":1,"room_id":5,"new":true,"level":0,"center":[1,2],)"
       R"("rect":{"center":[1,2],"size":[1,1],"yaw":0},"walls":[],"kind":"hall"})",
       "'kind'"},
  };
  for (const Case& c : cases) {
    // The bad line is line 3: a good line and a blank line come first.
    const std::string path = write_file("rooms_events.jsonl", good + "\n\n" + c.line + "\n" + good + "\n");
    const std::string msg = input_error_of([&] { read_room_events(path); });
    EXPECT_THAT(msg, StartsWith(path + ":3: "));
    EXPECT_THAT(msg, HasSubstr(c.says));
  }
  // A coordinate beyond any building and a number beyond a double, on the third line.
  const std::string huge =
      write_file("rooms_events.jsonl",
                 good + "\n\n" + replaced(good, "\"center\":[2.0,2.0]", "\"center\":[2.0,1e308]") + "\n");
  EXPECT_THAT(input_error_of([&] { read_room_events(huge); }),
              StartsWith(huge + ":3: 'center[1]' is 1e+308: not a coordinate within 1e8 m"));
  const std::string overflow =
      write_file("rooms_events.jsonl",
                 good + "\n\n" + replaced(good, "\"center\":[2.0,2.0]", "\"center\":[2.0,1e400]") + "\n");
  EXPECT_THAT(input_error_of([&] { read_room_events(overflow); }),
              StartsWith(overflow + ":3: number out of the range of a double"));
  const std::string missing = (dir_ / "none.jsonl").string();
  EXPECT_THAT(input_error_of([&] { read_room_events(missing); }), StartsWith(missing + ": "));
}

TEST_F(RoomEventsFile, IgnoresUnknownKeys) {
  const std::string line =
      replaced(format_room_event(event(2, rect(1, 2, 3, 4, 0))), "{", R"({"score":0.9,)");
  const std::vector<RoomEvent> back = read_room_events(write_file("rooms_events.jsonl", line + "\n"));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].lap, 2);
}

// ---- timings.csv --------------------------------------------------------------------------

class TimingsFile : public test::TempDirTest {};

TEST_F(TimingsFile, ReadsWhatRunWroteAndWritesTheSameBytes) {
  const Timings t = read_timings(write_file("timings.csv", kTimingsText));
  ASSERT_EQ(t.scans.size(), 2u);
  const ScanTiming& s = t.scans[0];
  EXPECT_EQ(s.index, 0u);
  EXPECT_EQ(s.keyframe, 0);
  EXPECT_EQ(s.num_points, 6534u);
  EXPECT_DOUBLE_EQ(s.prefilter_ms, 1.675);
  EXPECT_DOUBLE_EQ(s.walls_ms, 7.24);
  EXPECT_DOUBLE_EQ(s.loop_ms, 0.001);
  EXPECT_DOUBLE_EQ(s.frontend_ms, 15.869);
  EXPECT_EQ(s.warning, "");
  EXPECT_DOUBLE_EQ(s.ground_ms, 6.285);
  EXPECT_EQ(s.ground_nodes, 152u);
  EXPECT_EQ(s.ground_tp, 4547);
  EXPECT_EQ(s.ground_fp, 5);
  EXPECT_EQ(s.ground_fn, 740);
  EXPECT_DOUBLE_EQ(s.rooms_ms, 0.639);
  EXPECT_EQ(t.scans[1].keyframe, -1);
  EXPECT_EQ(t.scans[1].warning, "empty scan: skipped");
  EXPECT_EQ(t.scans[1].ground_tp, -1);
  ASSERT_EQ(t.optimizations.size(), 1u);
  const OptimizationTiming& o = t.optimizations[0];
  EXPECT_DOUBLE_EQ(o.stamp, 0.1);
  EXPECT_EQ(o.keyframe, 4);
  EXPECT_DOUBLE_EQ(o.seconds, 0.000453);
  EXPECT_TRUE(o.full);
  EXPECT_EQ(o.n_variables, 19);
  EXPECT_EQ(o.n_factors, 58);
  EXPECT_EQ(o.iterations, 3);
  EXPECT_EQ(o.reason, "loop");
  EXPECT_EQ(o.active_keyframes, -1);  // not in the older layout
  const Timings now = read_timings(write_file("timings_now.csv", kTimingsTextNow));
  ASSERT_EQ(now.optimizations.size(), 1u);
  EXPECT_EQ(now.optimizations[0].active_keyframes, 57);
  EXPECT_EQ(format_timings(now), kTimingsTextNow);
}

TEST_F(TimingsFile, WarningsWithCommasAndQuotesRoundTrip) {
  Timings t;
  ScanTiming s;
  s.warning = "odd scan, \"really\" odd";
  s.stamp = 2.5;
  t.scans.push_back(s);
  const std::string text = format_timings(t);
  EXPECT_THAT(text, HasSubstr(",\"odd scan, \"\"really\"\" odd\","));
  const Timings back = read_timings(write_file("timings.csv", text));
  ASSERT_EQ(back.scans.size(), 1u);
  EXPECT_EQ(back.scans[0].warning, s.warning);
  EXPECT_DOUBLE_EQ(back.scans[0].ground_ms, 0.0);
  EXPECT_EQ(format_timings(back), text);
}

TEST_F(TimingsFile, FindsColumnsByNameAndIgnoresUnknownOnes) {
  // A newer writer's column at the end.
  std::string text = kTimingsText;
  text = replaced(text, ",rooms_ms\n", ",rooms_ms,gpu_ms\n");
  text = replaced(text, ",0.639\n", ",0.639,9.5\n");
  const Timings t = read_timings(write_file("timings.csv", text));
  ASSERT_EQ(t.scans.size(), 2u);
  EXPECT_DOUBLE_EQ(t.scans[0].rooms_ms, 0.639);
}

TEST_F(TimingsFile, MalformedLinesNameTheLineAndColumn) {
  struct Case {
    std::string from, to;
    int line;
    std::string says;
  };
  const std::vector<Case> cases = {
      {",15.869,", ",15.8x9,", 2, "malformed frontend_ms in a scan row"},
      {",6534,", ",-6534,", 2, "malformed num_points in a scan row"},
      {",4547,5,740,", ",4547,5,,", 2, "malformed ground_fn in a scan row"},
      {",4547,5,740,", ",9000000000000000000,5,740,", 2,
       "ground_tp in a scan row must be -1 (no labels) or a count"},
      {",4547,5,740,", ",4547,-5,740,", 2, "ground_fp in a scan row must be -1"},
      {",0.000453,1,", ",0.000453,2,", 4, "full must be 0 or 1"},
      {",19,58,3,loop", ",19,5.8,3,loop", 4, "malformed n_factors in an optimization row"},
      {"optimization,0,", "optimisation,0,", 4, "expected a scan or optimization row, got 'optimisation'"},
      {"\"empty scan: skipped\"", "\"empty scan: skipped", 3, "unterminated quoted field"},
      {",frontend_ms,", ",front_ms,", 1, "header has no column 'frontend_ms'"},
      {"kind,", "type,", 1, "header must start with 'kind'"},
  };
  for (const Case& c : cases) {
    const std::string path = write_file("timings.csv", replaced(kTimingsText, c.from, c.to));
    const std::string msg = input_error_of([&] { read_timings(path); });
    EXPECT_THAT(msg, StartsWith(path + ":" + std::to_string(c.line) + ": ")) << c.says;
    EXPECT_THAT(msg, HasSubstr(c.says));
  }
  const std::string empty = write_file("empty.csv", "");
  EXPECT_THAT(input_error_of([&] { read_timings(empty); }), StartsWith(empty + ":1: "));
}

// ---- run_info.json ------------------------------------------------------------------------

class RunSummaryFile : public test::TempDirTest {};

TEST_F(RunSummaryFile, RoundTripsAndKeepsItsLayout) {
  RunSummary s;
  s.sequence = "seq";
  s.num_scans = 2123;
  s.odometry = "lidar";
  s.num_keyframes = 319;
  s.num_planes = 33;
  s.num_traversable_nodes = 4602;
  s.num_rooms = 6;
  s.num_room_events = 18;
  s.num_loops = 31;
  s.num_optimizations = 73;
  s.t_pgo_s = 0.5083334669999999;
  s.sequence_duration_s = 212.29999999999998;
  s.wall_time_s = 19.506330882;
  s.rtf = s.sequence_duration_s / s.wall_time_s;
  s.peak_rss_mb = 188.60546875;
  const std::string text = format_run_summary(s);
  EXPECT_THAT(text, StartsWith("{\n \"num_keyframes\": 319,\n \"num_loops\": 31,\n"));
  const RunSummary back = read_run_summary(write_file("run_info.json", text));
  EXPECT_EQ(back.sequence, "seq");
  EXPECT_EQ(back.odometry, "lidar");
  EXPECT_EQ(back.num_scans, 2123u);
  EXPECT_EQ(back.rtf, s.rtf);
  EXPECT_EQ(back.peak_rss_mb, s.peak_rss_mb);
  EXPECT_EQ(format_run_summary(back), text);
}

TEST_F(RunSummaryFile, MissingKeysAndWrongTypesAreNamed) {
  const std::string good = format_run_summary(RunSummary{});
  std::string path = write_file("run_info.json", replaced(good, "\"rtf\"", "\"speed\""));
  EXPECT_THAT(input_error_of([&] { read_run_summary(path); }), StartsWith(path + ": missing key 'rtf'"));
  path = write_file("run_info.json", replaced(good, "\"num_loops\": 0", "\"num_loops\": 1.5"));
  EXPECT_THAT(input_error_of([&] { read_run_summary(path); }), HasSubstr("'num_loops' must be an integer"));
  path = write_file("run_info.json", "[]");
  EXPECT_THAT(input_error_of([&] { read_run_summary(path); }), HasSubstr("expected a JSON object"));
  path = write_file("run_info.json", replaced(good, "\"rtf\": 0.0", "\"rtf\": 1e400"));
  EXPECT_THAT(input_error_of([&] { read_run_summary(path); }), StartsWith(path + ":"));
  EXPECT_THAT(input_error_of([&] { read_run_summary(path); }),
              HasSubstr(": number out of the range of a double: '1e400'"));
  // Extra keys: a newer writer's.
  path = write_file("run_info.json", replaced(good, "{", "{\"gpu\": \"none\", "));
  EXPECT_EQ(read_run_summary(path).num_scans, 0u);
}

// map.ply as run writes it now (double) and wrote it before the map frame (float).
TEST_F(SceneGraphFile, MapPlyOfDoublesOrFloats) {
  const auto ply = [](const std::string& type, std::size_t count, const std::string& body) {
    return "ply\nformat binary_little_endian 1.0\ncomment test\nelement vertex " + std::to_string(count) +
           "\nproperty " + type + " x\nproperty " + type + " y\nproperty " + type +
           " z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n" + body;
  };
  std::string doubles, floats;
  const double d[3] = {512345.125, 4012345.25, 1.5};
  const float f[3] = {1.5f, -2.0f, 0.25f};
  doubles.append(reinterpret_cast<const char*>(d), 24) += std::string("\x01\x02\x03", 3);
  floats.append(reinterpret_cast<const char*>(f), 12) += std::string("\xff\x00\x10", 3);
  const auto a = read_map_ply(write_file("d.ply", ply("double", 1, doubles)));
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].p, Eigen::Vector3d(512345.125, 4012345.25, 1.5));
  EXPECT_EQ(a[0].b, 3);
  const auto b = read_map_ply(write_file("f.ply", ply("float", 1, floats)));
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b[0].p, Eigen::Vector3d(1.5, -2.0, 0.25));
  EXPECT_EQ(b[0].r, 255);
  const std::string short_body = write_file("short.ply", ply("double", 2, doubles));
  EXPECT_THAT(input_error_of([&] { read_map_ply(short_body); }),
              AllOf(StartsWith(short_body + ": holds 1 vertices of 27 bytes from byte "),
                    HasSubstr(", its header says 2")));
  EXPECT_THROW(read_map_ply(write_file("text.ply", "ply\nformat ascii 1.0\nend_header\n")), InputError);
}

// Issue 52: export copied a damaged map.ply through. A header saying float over a body of
// doubles, bytes after the last vertex, a NaN or a coordinate beyond 1e8 m are refused, naming
// the file and the byte (and the vertex).
TEST_F(SceneGraphFile, MapPlyBodyOfAnotherSizeOrBadValuesIsRefusedNamingTheByte) {
  const auto ply = [](const std::string& type, std::size_t count, const std::string& body) {
    return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(count) + "\nproperty " +
           type + " x\nproperty " + type + " y\nproperty " + type +
           " z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n" + body;
  };
  const auto vertex = [](double x, double y, double z) {
    const double d[3] = {x, y, z};
    return std::string(reinterpret_cast<const char*>(d), sizeof d) + std::string("\x01\x02\x03", 3);
  };
  const std::string two = vertex(1.0, 2.0, 3.0) + vertex(4.0, 5.0, 6.0);
  const std::size_t header = ply("double", 2, "").size(), float_header = ply("float", 2, "").size();
  ASSERT_EQ(read_map_ply(write_file("good.ply", ply("double", 2, two))).size(), 2u);

  // Doubles under a float header: 2 x 27 bytes where 2 x 15 are declared.
  std::string path = write_file("float_header.ply", ply("float", 2, two));
  EXPECT_EQ(input_error_of([&] { read_map_ply(path); }),
            path + ": 24 bytes after the last of the header's 2 vertices of 15 bytes, from byte " +
                std::to_string(float_header + 30) + " (are the properties' types the body's?)");
  path = write_file("trailing.ply", ply("double", 2, two + "x"));
  EXPECT_THAT(
      input_error_of([&] { read_map_ply(path); }),
      StartsWith(path + ": 1 bytes after the last of the header's 2 vertices of 27 bytes, from byte " +
                 std::to_string(header + 54)));

  path = write_file("nan.ply", ply("double", 2, vertex(1.0, 2.0, 3.0) + vertex(4.0, std::nan(""), 6.0)));
  EXPECT_EQ(input_error_of([&] { read_map_ply(path); }),
            path + ": byte " + std::to_string(header + 27) + ": 'vertex[1].y' must be finite");
  path = write_file("far.ply", ply("double", 2, vertex(2e8, 2.0, 3.0) + vertex(4.0, 5.0, 6.0)));
  EXPECT_EQ(
      input_error_of([&] { read_map_ply(path); }),
      path + ": byte " + std::to_string(header) + ": 'vertex[0].x' is 2e+08: not a coordinate within 1e8 m");
  // A float body whose bytes make a float beyond the bound (an old run's map.ply, damaged).
  const float big[3] = {1.0f, 2.0f, 3e38f};
  path = write_file("far_float.ply",
                    ply("float", 1, std::string(reinterpret_cast<const char*>(big), sizeof big) + "abc"));
  EXPECT_THAT(input_error_of([&] { read_map_ply(path); }),
              StartsWith(path + ": byte " + std::to_string(float_header) + ": 'vertex[0].z' is 3e+38"));
}
