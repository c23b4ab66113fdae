// The run report as a browser sees it: headless Chromium loads the page, and the DOM it
// builds has the rooms and walls the report draws, with no console message or script
// error. Skipped when Chromium is not installed.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_support.hpp"
#include "tsgraphs/report/report_html.hpp"
#include "tsgraphs/report/run_view.hpp"

namespace tsgraphs {
namespace {

namespace fs = std::filesystem;
using report::RunView;

constexpr const char* kChromium = "/usr/bin/chromium";

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + what.size())) ++n;
  return n;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The DOM Chromium builds for `page` (stdout of --dump-dom); its stderr goes to `err`.
std::string dump_dom(const fs::path& page, const fs::path& err) {
  const std::string cmd = std::string("timeout 60 ") + kChromium +
                          " --headless --no-sandbox --disable-gpu --enable-logging=stderr --v=0 --dump-dom 'file://" +
                          page.string() + "' 2>'" + err.string() + "'";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return "";
  std::string out;
  std::array<char, 4096> buf{};
  for (std::size_t n; (n = fread(buf.data(), 1, buf.size(), pipe)) > 0;) out.append(buf.data(), n);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << cmd << "\n" << read_file(err);
  return out;
}

RunView::Room room(int id, const std::string& kind, int level, const Vec2& center, int first_lap) {
  RunView::Room r;
  r.id = id;
  r.kind = kind;
  r.level = level;
  r.rect.center = center;
  r.rect.size = Vec2(3.0, 2.0);
  r.first_lap = first_lap;
  r.free_space = {Eigen::Vector3d(center.x(), center.y(), level * 3.0)};
  return r;
}

/// Two levels, both walked: level 0 has 2 rooms, a corridor and 3 walls, level 1 a room
/// and 1 wall. Metrics with a null figure, a label that needs escaping.
RunView two_level_run() {
  RunView run;
  run.label = "run <A> & \"B\"";
  run.levels = {0.0, 3.0};
  run.walls = {{1, {0, 0}, {9, 0}, 0.0, 2.8}, {2, {0, 0}, {0, 7}, 0.05, 2.9}, {4, {9, 0}, {9, 7}, -0.1, 2.5},
               {7, {1, 1}, {1, 6}, 3.0, 5.5}};
  for (int i = 0; i < 4; ++i) run.nodes.push_back({Eigen::Vector3d(1.0 + i, 1.0, 0.02)});
  for (int i = 0; i < 2; ++i) run.nodes.push_back({Eigen::Vector3d(2.0 + i, 6.0, 3.01)});
  run.rooms = {room(0, "room", 0, {2, 2}, 1), room(1, "corridor", 0, {6, 2}, 2), room(2, "room", 0, {2, 6}, 1),
               room(7, "room", 1, {7, 6}, 1)};
  run.truth_rooms = {{"hall", "ground", {{0, 0}, {5, 0}, {5, 4}, {0, 4}}, 0.0}};
  for (int i = 0; i <= 20; ++i) run.estimated.push_back({0.1 * i, Eigen::Vector3d(1.0 + 0.4 * i, 1.0, 0.55)});
  for (int i = 0; i <= 10; ++i) run.estimated.push_back({2.1 + 0.1 * i, Eigen::Vector3d(8.0 - 0.5 * i, 6.0, 3.55)});
  for (int i = 0; i < 32; ++i) run.scans.push_back({0.1 * i, 10.0 + (i % 5)});
  run.solves = {{0.5, 0.002, false}, {1.5, 0.004, false}, {2.5, 0.020, true}};
  run.metrics_json = R"({"consistency": {"N1st": 3, "N2nd": 3, "N_re": 2, "f_re": 0.6667, "dcs": null},
                         "trajectory": {"ate_rmse": 0.0123}, "speed": {"rtf": 9.5}})";
  return run;
}

class ReportChromium : public test::TempDirTest {
 protected:
  void SetUp() override {
    if (!fs::exists(kChromium)) {
      GTEST_SKIP() << kChromium << " is not installed: run scripts/install-deps.sh (CI installs it)";
    }
    TempDirTest::SetUp();
  }
};

TEST_F(ReportChromium, RunReportLoadsWithItsRoomsAndWallsAndNoErrors) {
  const RunView run = two_level_run();
  const std::string html = report::run_report_html(run, "Report of <A> & co");
  // Self-contained: no script, no URL of any kind besides the SVG namespace.
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(count(html, "<script"), 0u);
  EXPECT_EQ(count(html, "http://") + count(html, "https://"), count(html, "xmlns=\"http://www.w3.org/2000/svg\""));
  EXPECT_EQ(count(html, "url("), 0u);
  EXPECT_EQ(count(html, " href="), 0u);
  EXPECT_EQ(count(html, " src="), 0u);
  // Escaped title and label.
  EXPECT_NE(html.find("<title>Report of &lt;A&gt; &amp; co</title>"), std::string::npos);
  EXPECT_EQ(html.find("run <A>"), std::string::npos);
  // The metrics table: a figure, and "-" for the null one and the absent ones.
  EXPECT_NE(html.find("<td>ate_rmse</td><td class=\"value\">0.0123</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>dcs</td><td class=\"value\">-</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>t_pgo_s</td><td class=\"value\">-</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>N1st</td><td class=\"value\">3</td>"), std::string::npos);

  const fs::path page = dir_ / "report.html";
  std::ofstream(page, std::ios::binary) << html;
  const fs::path err = dir_ / "chromium.err";
  const std::string dom = dump_dom(page, err);
  const std::string log = read_file(err);
  ASSERT_NE(dom.find("</html>"), std::string::npos) << "no DOM from Chromium; stderr:\n" << log;
  // Both levels are walked: a bird's-eye of each, then the time plot (no scene: no side view).
  EXPECT_EQ(count(dom, "class=\"tsg-birdseye\""), 2u);
  EXPECT_EQ(count(dom, "class=\"tsg-timing\""), 1u);
  EXPECT_EQ(count(dom, "class=\"tsg-side-view\""), 0u);
  EXPECT_EQ(count(dom, "class=\"room\""), 3u);
  EXPECT_EQ(count(dom, "class=\"corridor\""), 1u);
  EXPECT_EQ(count(dom, "class=\"wall\""), 4u);
  EXPECT_EQ(count(dom, "class=\"solve "), 3u);
  EXPECT_NE(dom.find("0 \xC2\xB7 lap 1"), std::string::npos);
  EXPECT_NE(dom.find("7 \xC2\xB7 lap 1"), std::string::npos);
  // The same counts as the page Chromium was given: nothing dropped by the parser.
  EXPECT_EQ(count(dom, "class=\"room\""), count(html, "class=\"room\""));
  EXPECT_EQ(count(dom, "class=\"wall\""), count(html, "class=\"wall\""));
  EXPECT_EQ(log.find(":CONSOLE"), std::string::npos) << log;
  EXPECT_EQ(log.find("Uncaught"), std::string::npos) << log;
}

TEST_F(ReportChromium, DemoPageLoadsWithOneBirdseyePerRun) {
  RunView a = two_level_run(), b = two_level_run();
  a.label = "TS-graphs";
  b.label = "S-Graphs+";
  b.rooms.pop_back();  // b has no room on level 1
  // a walks level 1 longer than level 0: its main level is 1; b's rooms are all on level 0.
  for (int i = 0; i < 30; ++i) a.estimated.push_back({3.5 + 0.1 * i, Eigen::Vector3d(3.0, 6.0, 3.55)});
  const std::string html = report::demo_report_html("Demo", "<p class=\"intro\">Two runs.</p>",
                                                    "<table class=\"given\"><tr><td>1</td></tr></table>",
                                                    {{"Scene & one", {a, b}}});
  const fs::path page = dir_ / "demo.html";
  std::ofstream(page, std::ios::binary) << html;
  const fs::path err = dir_ / "chromium.err";
  const std::string dom = dump_dom(page, err);
  const std::string log = read_file(err);
  ASSERT_NE(dom.find("</html>"), std::string::npos) << log;
  EXPECT_NE(dom.find("<p class=\"intro\">Two runs.</p>"), std::string::npos);
  EXPECT_NE(dom.find("<table class=\"given\">"), std::string::npos);
  EXPECT_NE(dom.find("<h2>Scene &amp; one</h2>"), std::string::npos);
  EXPECT_EQ(count(dom, "class=\"tsg-birdseye\""), 2u);
  EXPECT_EQ(count(dom, "class=\"tsg-timing\""), 1u);
  EXPECT_NE(dom.find("<figcaption>TS-graphs, level 1 (floor at 3.00 m)</figcaption>"), std::string::npos);
  EXPECT_NE(dom.find("<figcaption>S-Graphs+, level 0 (floor at 0.00 m)</figcaption>"), std::string::npos);
  // a's level 1 (one room, one wall) and b's level 0 (two rooms, a corridor, three walls).
  EXPECT_EQ(count(dom, "class=\"room\""), 3u);
  EXPECT_EQ(count(dom, "class=\"wall\""), 4u);
  EXPECT_EQ(log.find(":CONSOLE"), std::string::npos) << log;
  EXPECT_EQ(log.find("Uncaught"), std::string::npos) << log;
}

}  // namespace
}  // namespace tsgraphs
