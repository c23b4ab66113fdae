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

#include "report_test_support.hpp"
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

using test::read_file;

/// The DOM Chromium builds for `page` (stdout of --dump-dom); its stderr goes to `err`.
std::string dump_dom(const fs::path& page, const fs::path& err) {
  const std::string cmd =
      std::string("timeout 60 ") + kChromium +
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

/// test::two_level_run with a label that needs escaping and metrics with a null figure.
RunView two_level_run() {
  RunView run = test::two_level_run();
  run.label = "run <A> & \"B\"";
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
  EXPECT_EQ(count(html, "http://") + count(html, "https://"),
            count(html, "xmlns=\"http://www.w3.org/2000/svg\""));
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
