// `tsgraphs eval` on a damaged run folder or sequence: one line naming the file and the place,
// exit status 2, no crash, and the run folder left as it was (no metrics.json appears, an
// earlier one stays).
// ctest: slow (seconds a test: simulated runs or generated buildings)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "small_room_test_support.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;

namespace {

using test::cli;
using test::read_file;

class EvalCli : public test::TempDirTest {
 protected:
  // One sequence and one run of it, shared; each test damages its own copies.
  static void SetUpTestSuite() {
    base_ = test::fresh_temp_dir("eval_cli_base");
    std::string err;
    ASSERT_TRUE(test::simulate_small_room(base_, &err)) << err;
    ASSERT_EQ(cli("-q run " + (base_ / "seq").string() + " --out " + (base_ / "run").string(), &err), 0)
        << err;
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }

  void SetUp() override {
    TempDirTest::SetUp();
    run_ = dir_ / "run";
    seq_ = dir_ / "seq";
    fs::copy(base_ / "run", run_, fs::copy_options::recursive);
    fs::copy(base_ / "seq", seq_, fs::copy_options::recursive);
    fs::remove(run_ / "metrics.json");
  }

  // Sets the value at the JSON pointer `at` of the run's scene_graph.json to the literal `text`
  // (one key a line, so that the line of a number is found).
  void set_in_scene_graph(const std::string& at, const std::string& text) const {
    nlohmann::json g = nlohmann::json::parse(read_file(run_ / "scene_graph.json"));
    g[nlohmann::json::json_pointer(at)] = "@@";
    std::string doc = g.dump(1);
    doc.replace(doc.find("\"@@\""), 4, text);
    std::ofstream(run_ / "scene_graph.json") << doc;
  }

  // Replaces the second word of line `line` (from 1) of a TUM file with `word`.
  static void set_tum_x(const fs::path& file, int line, const std::string& word) {
    std::istringstream in(read_file(file));
    std::string text, out;
    for (int n = 1; std::getline(in, text); ++n) {
      if (n == line) {
        const std::size_t a = text.find(' '), b = text.find(' ', a + 1);
        text = text.substr(0, a + 1) + word + text.substr(b);
      }
      out += text + "\n";
    }
    std::ofstream(file) << out;
  }

  // Runs eval; expects exit 2, one line holding each of `says`, and no metrics.json.
  void expect_refused(const std::vector<std::string>& says) const {
    std::string err;
    EXPECT_EQ(cli("-q eval " + run_.string() + " --seq " + seq_.string(), &err), 2) << err;
    for (const std::string& s : says)
      EXPECT_NE(err.find(s), std::string::npos) << "wanted: " << s << "\ngot: " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_EQ(err.find("internal error"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(run_ / "metrics.json"));
  }

  static fs::path base_;
  fs::path run_, seq_;
};
fs::path EvalCli::base_;

}  // namespace

TEST_F(EvalCli, TheUndamagedRunIsEvaluated) {
  std::string err;
  ASSERT_EQ(cli("-q eval " + run_.string() + " --seq " + seq_.string(), &err), 0) << err;
  EXPECT_TRUE(nlohmann::json::parse(read_file(run_ / "metrics.json"))["trajectory"]["ate_rmse"].is_number());
}

// A coordinate of 1e308 divided by zero drawing the bird's-eye (SIGFPE), after metrics.json was
// written; a room centre of 1e308 was evaluated as if it were a room.
TEST_F(EvalCli, ACoordinateNoBuildingHasIsNamedWithItsPath) {
  struct Case {
    std::string at, value, says;
  };
  const std::vector<Case> cases = {
      {"/rooms/0/rect/center/0", "1e308",
       "'rooms[0].rect.center[0]' is 1e+308: not a coordinate within 1e8 m"},
      {"/planes/0/segment/0/0", "1e308", "'planes[0].segment[0][0]' is 1e+308"},
      {"/traversable_nodes/0/position/0", "-1e308", "'traversable_nodes[0].position[0]' is -1e+308"},
      {"/keyframes/2/pose/t/1", "1e12", "'keyframes[2].pose.t[1]' is 1e+12"},
  };
  const std::string graph = read_file(run_ / "scene_graph.json");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.at);
    std::ofstream(run_ / "scene_graph.json") << graph;
    set_in_scene_graph(c.at, c.value);
    expect_refused({(run_ / "scene_graph.json").string() + ": ", c.says});
  }
}

TEST_F(EvalCli, APositionNoPlaceHasInATrajectoryIsNamedWithItsLine) {
  set_tum_x(run_ / "trajectory.txt", 3, "1e308");
  expect_refused({(run_ / "trajectory.txt").string() + ":3: x is 1e308: not a coordinate within 1e8 m"});
  fs::copy_file(base_ / "run" / "trajectory.txt", run_ / "trajectory.txt",
                fs::copy_options::overwrite_existing);
  set_tum_x(seq_ / "groundtruth.txt", 4, "-1e308");
  expect_refused({(seq_ / "groundtruth.txt").string() + ":4: x is -1e308"});
}

// Numbers beyond a double were an "internal error" (exit 1) from the JSON parser, or "expected 8
// numbers" from the trajectory reader.
TEST_F(EvalCli, ANumberBeyondADoubleIsNamedWithItsLine) {
  set_in_scene_graph("/levels/0", "1e400");
  const std::string doc = read_file(run_ / "scene_graph.json");
  const int line =
      1 + static_cast<int>(std::count(doc.begin(), doc.begin() + static_cast<long>(doc.find("1e400")), '\n'));
  expect_refused({(run_ / "scene_graph.json").string() + ":" + std::to_string(line) +
                  ": number out of the range of a double: '1e400'"});
  fs::copy_file(base_ / "run" / "scene_graph.json", run_ / "scene_graph.json",
                fs::copy_options::overwrite_existing);

  std::string info = read_file(run_ / "run_info.json");
  info.replace(info.find("\"rtf\": ") + 7, 1, "1e400,\"was\": ");
  std::ofstream(run_ / "run_info.json") << info;
  expect_refused({(run_ / "run_info.json").string() + ":", "number out of the range of a double: '1e400'"});
  fs::copy_file(base_ / "run" / "run_info.json", run_ / "run_info.json",
                fs::copy_options::overwrite_existing);

  set_tum_x(seq_ / "groundtruth.txt", 2, "1e400");
  expect_refused({(seq_ / "groundtruth.txt").string() + ":2: x is 1e400: out of the range of a double"});
}

// A folder where a file should be was read as an empty file ("0 poses") or as a missing one.
TEST_F(EvalCli, AFileThatIsAFolderIsNamed) {
  for (const fs::path& file :
       {run_ / "scene_graph.json", run_ / "trajectory.txt", run_ / "odometry.txt",
        run_ / "rooms_events.jsonl", seq_ / "groundtruth.txt", seq_ / "times.txt", seq_ / "laps.txt"}) {
    SCOPED_TRACE(file.string());
    const fs::path saved = dir_ / "saved";
    fs::rename(file, saved);
    fs::create_directories(file / "inside");
    expect_refused({file.string() + ": is a folder, not a file"});
    fs::remove_all(file);
    fs::rename(saved, file);
  }
  fs::create_directories(seq_ / "rooms_gt.json" / "inside");  // optional, so absent until now
  expect_refused({(seq_ / "rooms_gt.json").string() + ": is a folder, not a file"});
}

// A true room at 1e308 was blamed on the sequence folder ("ground truth: polygon too large").
TEST_F(EvalCli, ATrueRoomNoBuildingHasIsNamed) {
  std::ofstream(seq_ / "rooms_gt.json")
      << R"([{"name": "hall", "level": "L0", "elevation": 0, "polygon": [[0, 0], [1e308, 0], [6, 5]]}])";
  expect_refused({(seq_ / "rooms_gt.json").string() +
                  ": room 0 (hall): polygon vertex 1 is not a coordinate within 1e8 m"});
}

// metrics.json is written last, after the report: a report that cannot be written left a new
// metrics.json beside the old report.
TEST_F(EvalCli, AReportThatCannotBeWrittenLeavesNoMetrics) {
  const std::string birdseye = read_file(run_ / "birdseye.svg");
  fs::remove(run_ / "report.html");
  fs::create_directories(run_ / "report.html" / "inside");
  expect_refused({(run_ / "report.html").string() + ": is a folder"});
  EXPECT_EQ(read_file(run_ / "birdseye.svg"), birdseye);
}

// A failed eval leaves the run folder as it was: an earlier metrics.json and its report stay
// (they describe the run as it was evaluated then). A malformed earlier one is replaced.
TEST_F(EvalCli, AFailedEvalKeepsTheEarlierMetricsAndReport) {
  std::string err;
  ASSERT_EQ(cli("-q eval " + run_.string() + " --seq " + seq_.string(), &err), 0) << err;
  const std::string metrics = read_file(run_ / "metrics.json"), html = read_file(run_ / "report.html"),
                    birdseye = read_file(run_ / "birdseye.svg");
  set_in_scene_graph("/rooms/0/rect/center/0", "1e308");
  EXPECT_EQ(cli("-q eval " + run_.string() + " --seq " + seq_.string(), &err), 2) << err;
  EXPECT_EQ(read_file(run_ / "metrics.json"), metrics);
  EXPECT_EQ(read_file(run_ / "report.html"), html);
  EXPECT_EQ(read_file(run_ / "birdseye.svg"), birdseye);
  fs::copy_file(base_ / "run" / "scene_graph.json", run_ / "scene_graph.json",
                fs::copy_options::overwrite_existing);

  // Failing after the figures are made (the report cannot be written): the earlier file stays.
  std::ofstream(run_ / "metrics.json") << "{\"written\": \"earlier\"}\n";
  fs::remove(run_ / "report.html");
  fs::create_directories(run_ / "report.html" / "inside");
  EXPECT_EQ(cli("-q eval " + run_.string() + " --seq " + seq_.string(), &err), 2) << err;
  EXPECT_EQ(read_file(run_ / "metrics.json"), "{\"written\": \"earlier\"}\n");
  fs::remove_all(run_ / "report.html");

  std::ofstream(run_ / "metrics.json") << "{ half a file";
  ASSERT_EQ(cli("-q eval " + run_.string() + " --seq " + seq_.string(), &err), 0) << err;
  EXPECT_EQ(read_file(run_ / "metrics.json"), metrics);
}

// A loop closure's keyframe whose scan lies beyond the sequence was read out of bounds
// (SIGSEGV): only the first keyframe's scan was checked.
TEST_F(EvalCli, AKeyframeScanBeyondTheSequenceIsNamed) {
  nlohmann::json g = nlohmann::json::parse(read_file(run_ / "scene_graph.json"));
  ASSERT_GE(g["keyframes"].size(), 2u);
  g["keyframes"][1]["scan_index"] = 1000000000;
  g["loop_closures"].push_back({{"from", 0},
                                {"to", 1},
                                {"fitness", 0.01},
                                {"measurement", {{"t", {0, 0, 0}}, {"q", {0, 0, 0, 1}}}},
                                {"proposer", "distance"}});
  std::ofstream(run_ / "scene_graph.json") << g.dump(1);
  expect_refused({(run_ / "scene_graph.json").string() +
                  ": 'keyframes[1].scan_index' is 1000000000: beyond the sequence's "});
}

// A room polygon too large to rasterise was blamed on the sequence ("ground truth: polygon too
// large to rasterise").
TEST_F(EvalCli, ARoomPolygonTooLargeIsBlamedOnTheRun) {
  nlohmann::json g = nlohmann::json::parse(read_file(run_ / "scene_graph.json"));
  ASSERT_GE(g["rooms"].size(), 1u);
  g["rooms"][0]["polygon"] = {{0, 0}, {9e7, 0}, {9e7, 9e7}, {0, 9e7}};
  std::ofstream(run_ / "scene_graph.json") << g.dump(1);
  std::ofstream(seq_ / "rooms_gt.json")
      << R"([{"name": "hall", "level": "L0", "elevation": 0, "polygon": [[0, 0], [6, 0], [6, 5], [0, 5]]}])";
  expect_refused({(run_ / "scene_graph.json").string() + ": 'rooms[0].polygon' is too large for a room"});
}
