// The pictures of a run: what the bird's-eye draws on each level (and only there), its
// labels and escaping, deterministic bytes, the side view's points and slabs, and one
// marker per optimisation in the time plot.
#include <gtest/gtest.h>

#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "report_test_support.hpp"
#include "tsgraphs/report/run_svg.hpp"
#include "tsgraphs/report/svg_writer.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/sim/scene_mesh.hpp"
#include "tsgraphs/scene/scene_loader.hpp"

namespace tsgraphs {
namespace {

using report::RunView;

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + what.size())) ++n;
  return n;
}

/// The value of attribute `attr` of the first element of class `cls`, or "".
std::string attribute(const std::string& svg, const std::string& cls, const std::string& attr) {
  std::smatch m;
  const std::regex re("class=\"" + cls + "\"[^>]*? " + attr + "=\"([^\"]*)\"");
  return std::regex_search(svg, m, re) ? m[1].str() : "";
}

/// Start tags and end tags nest, the root is <svg>. Returns "" or what went wrong.
std::string nesting_error(const std::string& svg) {
  std::vector<std::string> open;
  for (std::size_t at = svg.find('<'); at != std::string::npos; at = svg.find('<', at + 1)) {
    const std::size_t end = svg.find('>', at);
    if (end == std::string::npos) return "unterminated tag";
    const std::string tag = svg.substr(at + 1, end - at - 1);
    if (tag.empty() || tag.find('<') != std::string::npos) return "bad tag at " + std::to_string(at);
    if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1))
        return "</" + tag.substr(1) + "> closes the wrong element";
      open.pop_back();
    } else if (tag.back() != '/') {
      const std::string name = tag.substr(0, tag.find_first_of(" \n"));
      if (open.empty() && name != "svg") return "root element is " + name;
      open.push_back(name);
    }
  }
  return open.empty() ? "" : "<" + open.back() + "> is never closed";
}

constexpr const char* kScene = R"(name: two floors
levels:
  - {name: ground, elevation: 0.0, slab: [[0,0],[10,0],[10,8],[0,8]]}
  - name: upper
    elevation: 3.0
    slab: [[0,0],[10,0],[10,8],[0,8]]
    voids: [[[4,3],[6,3],[6,5],[4,5]]]
walls:
  - {level: ground, from: [0,0], to: [10,0]}
  - level: ground
    from: [0,8]
    to: [10,8]
    openings: [{at: 5, width: 1.0, height: 2.1, sill: 0.0}]
  - {level: upper, from: [0,0], to: [0,8]}
railings:
  - {level: upper, from: [4,3], to: [6,3], style: bars}
trajectory: {waypoints: [[1,1],[9,1]], closed: false, laps: 1}
)";

using test::two_level_run;

TEST(ReportRunSvg, BirdseyeCountsWhatIsOnTheLevel) {
  const RunView run = two_level_run();
  const std::string svg = report::birdseye_svg(run, 0);
  EXPECT_EQ(nesting_error(svg), "");
  EXPECT_EQ(count(svg, "class=\"room\""), 2u);
  EXPECT_EQ(count(svg, "class=\"corridor\""), 1u);
  EXPECT_EQ(count(svg, "class=\"truth-room\""), 2u);
  EXPECT_EQ(count(svg, "class=\"wall\""), 3u);
  EXPECT_EQ(count(svg, "class=\"free-space\""), 3u);
  EXPECT_EQ(attribute(svg, "node", "data-count"), "4");
  EXPECT_EQ(count(svg, "class=\"trajectory-estimated\""), 1u);
  EXPECT_EQ(count(svg, "class=\"trajectory-true\""), 1u);
  EXPECT_EQ(count(svg, "class=\"start\""), 1u);
  // Labels: "id · lap N", and a room without events says so.
  EXPECT_NE(svg.find(">0 \xC2\xB7 lap 1</text>"), std::string::npos);
  EXPECT_NE(svg.find(">1 \xC2\xB7 lap 2</text>"), std::string::npos);
  EXPECT_NE(svg.find(">2 \xC2\xB7 no event</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "class=\"room-label halo\""), 3u);
  // Ground-truth names and the run's label are escaped.
  EXPECT_NE(svg.find(">hall &amp; &lt;1&gt;</text>"), std::string::npos);
  EXPECT_NE(svg.find(">office</text>"), std::string::npos);
  EXPECT_NE(svg.find("TS-graphs &amp; &lt;co&gt;"), std::string::npos);
  EXPECT_EQ(svg.find("hall & <1>"), std::string::npos);
  // A legend and a scale bar.
  EXPECT_EQ(count(svg, "<g class=\"legend\">"), 1u);
  EXPECT_EQ(count(svg, "<g class=\"scale-bar\">"), 1u);
  // Rooms are cyan-ish, corridors orange-ish: blue above red, and red above blue.
  const std::regex fill(
      "class=\"(room|corridor)\" data-id=\"[0-9]+\" fill=\"#([0-9a-f]{2})[0-9a-f]{2}([0-9a-f]{2})\"");
  std::size_t checked = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), fill); it != std::sregex_iterator();
       ++it, ++checked) {
    const int red = std::stoi((*it)[2].str(), nullptr, 16), blue = std::stoi((*it)[3].str(), nullptr, 16);
    if ((*it)[1] == "room") {
      EXPECT_GT(blue, red);
    } else {
      EXPECT_GT(red, blue);
    }
  }
  EXPECT_EQ(checked, 3u);
}

TEST(ReportRunSvg, NothingOfAnotherLevelIsDrawn) {
  const RunView run = two_level_run();
  const std::string lower = report::birdseye_svg(run, 0);
  EXPECT_EQ(lower.find("7 \xC2\xB7 lap"), std::string::npos);
  EXPECT_EQ(lower.find("loft"), std::string::npos);
  EXPECT_EQ(lower.find("data-id=\"7\""), std::string::npos);
  EXPECT_EQ(lower.find("data-room=\"7\""), std::string::npos);
  const std::string upper = report::birdseye_svg(run, 1);
  EXPECT_EQ(nesting_error(upper), "");
  EXPECT_EQ(count(upper, "class=\"room\""), 1u);
  EXPECT_EQ(count(upper, "class=\"corridor\""), 0u);
  EXPECT_EQ(count(upper, "class=\"truth-room\""), 1u);
  EXPECT_EQ(count(upper, "class=\"wall\""), 1u);
  EXPECT_EQ(count(upper, "class=\"free-space\""), 1u);
  EXPECT_EQ(attribute(upper, "node", "data-count"), "2");
  EXPECT_NE(upper.find(">7 \xC2\xB7 lap 1</text>"), std::string::npos);
  EXPECT_NE(upper.find(">loft</text>"), std::string::npos);
  for (const char* other :
       {"0 \xC2\xB7 lap", "1 \xC2\xB7 lap", "office", "hall", "data-id=\"1\"", "data-room=\"0\""}) {
    EXPECT_EQ(upper.find(other), std::string::npos) << other;
  }
  // The trajectory starts on level 0: its start marker is not on level 1.
  EXPECT_EQ(count(upper, "class=\"start\""), 0u);
  // Points far from every floor are on no level.
  RunView stray = run;
  stray.nodes.push_back({Eigen::Vector3d(1, 1, -2.0)});
  stray.nodes.push_back({Eigen::Vector3d(1, 1, 9.0)});
  EXPECT_EQ(attribute(report::birdseye_svg(stray, 0), "node", "data-count"), "4");
  EXPECT_EQ(attribute(report::birdseye_svg(stray, 1), "node", "data-count"), "2");
  EXPECT_THROW(report::birdseye_svg(run, 2), std::invalid_argument);
  EXPECT_THROW(report::birdseye_svg(run, -1), std::invalid_argument);
}

TEST(ReportRunSvg, SceneIsDrawnOnlyOnItsLevel) {
  RunView run = two_level_run();
  run.scene = scene::parse_scene(kScene, "two_floors.yaml", ".");
  const std::string lower = report::birdseye_svg(run, 0);
  const std::string upper = report::birdseye_svg(run, 1);
  // Ground: two walls, the second cut in two by its door (the header above it is not drawn).
  std::size_t pieces = 0;
  for (const scene::Wall& w : run.scene->walls) {
    if (w.level != 0) continue;
    for (const scene::WallPiece& p : scene::wall_pieces(w)) pieces += p.z0 > 0.0 ? 0 : 1;
  }
  EXPECT_EQ(pieces, 3u);
  EXPECT_EQ(count(lower, "class=\"scene-wall\""), pieces);
  EXPECT_EQ(count(lower, "class=\"scene-railing"), 0u);
  EXPECT_EQ(count(lower, "class=\"scene-void\""), 0u);
  EXPECT_EQ(count(lower, "class=\"scene-slab\""), 1u);
  EXPECT_EQ(count(upper, "class=\"scene-wall\""), 1u);
  EXPECT_EQ(count(upper, "class=\"scene-railing bars\""), 1u);
  EXPECT_EQ(count(upper, "class=\"scene-void\""), 1u);
  // The run's own elements are unchanged by the scene.
  EXPECT_EQ(count(lower, "class=\"wall\""), 3u);
  EXPECT_EQ(count(lower, "class=\"room\""), 2u);
}

TEST(ReportRunSvg, SameRunSameBytes) {
  RunView run = two_level_run();
  run.scene = scene::parse_scene(kScene, "two_floors.yaml", ".");
  const std::string a = report::birdseye_svg(run, 0);
  EXPECT_EQ(a, report::birdseye_svg(run, 0));
  EXPECT_EQ(a, report::birdseye_svg(RunView(run), 0));
  EXPECT_NE(a, report::birdseye_svg(run, 1));
  EXPECT_EQ(report::side_view_svg(run), report::side_view_svg(run));
  EXPECT_EQ(report::timing_svg(run), report::timing_svg(run));
  // Fixed-point numbers only.
  for (const std::string& svg : {a, report::side_view_svg(run), report::timing_svg(run)}) {
    EXPECT_EQ(count(svg, "nan"), 0u);
    EXPECT_EQ(count(svg, "inf"), 0u);
    EXPECT_EQ(count(svg, "-0.00"), 0u);
    EXPECT_FALSE(std::regex_search(svg, std::regex("[0-9]\\.[0-9]*e[-+]?[0-9]")));
  }
}

TEST(ReportRunSvg, ManyNodesStayOnePathWithTheirCount) {
  RunView run = two_level_run();
  run.nodes.clear();
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) run.nodes.push_back({Eigen::Vector3d(0.05 * i, 0.05 * j, 0.0)});
  }
  const std::string svg = report::birdseye_svg(run, 0);
  EXPECT_EQ(count(svg, "class=\"node\""), 1u);
  EXPECT_EQ(attribute(svg, "node", "data-count"), "10000");
  // 0.05 m apart is 1.2 px at the plan's scale: thinned to one dot per 2 px cell.
  const std::string d = attribute(svg, "node", "d");
  EXPECT_LT(count(d, "h0"), 10000u);
  EXPECT_GT(count(d, "h0"), 2000u);
  EXPECT_LT(svg.size(), 200000u);
}

// Issue 18: a run kilometres long (up to 10 km is accepted) was drawn at 24 px per metre, a
// page of 240,000 px. A building keeps its scale; a longer run is drawn smaller, within
// report::svg::kMaxDrawingPx, and says so.
TEST(ReportRunSvg, ARunKilometresLongFitsThePage) {
  const RunView building = two_level_run();
  EXPECT_NE(report::birdseye_svg(building, 0).find("24 px per metre"), std::string::npos);
  RunView run = two_level_run();
  run.nodes.push_back({Eigen::Vector3d(8000.0, 3000.0, 0.0)});
  for (const std::string& svg : {report::birdseye_svg(run, 0), report::side_view_svg(run)}) {
    EXPECT_EQ(nesting_error(svg), "");
    const std::smatch w = [&] {
      std::smatch m;
      std::regex_search(svg, m, std::regex("<svg [^>]*width=\"([0-9.]+)\" height=\"([0-9.]+)\""));
      return m;
    }();
    ASSERT_EQ(w.size(), 3u);
    EXPECT_LE(std::stod(w[1].str()), report::svg::kMaxDrawingPx + 1000.0);
    EXPECT_LE(std::stod(w[2].str()), report::svg::kMaxDrawingPx + 1000.0);
    EXPECT_GT(std::stod(w[1].str()), 0.9 * report::svg::kMaxDrawingPx);  // the long side fills it
  }
}

TEST(ReportRunSvg, SideViewShowsEveryLevelsPointsAndTheSlabsGaps) {
  RunView run = two_level_run();
  run.scene = scene::parse_scene(kScene, "two_floors.yaml", ".");
  const std::string svg = report::side_view_svg(run);
  EXPECT_EQ(nesting_error(svg), "");
  EXPECT_EQ(attribute(svg, "node", "data-count"), "6");
  EXPECT_EQ(count(svg, "class=\"free-space\""), 4u);
  // Ground: one bar; upper: two bars, split by the void (x 4 to 6).
  EXPECT_EQ(count(svg, "class=\"scene-slab\""), 3u);
  EXPECT_EQ(count(svg, "class=\"level-line\""), 2u);
  EXPECT_EQ(count(svg, "class=\"trajectory-true\""), 1u);
  EXPECT_EQ(count(svg, "class=\"trajectory-estimated\""), 1u);
}

TEST(ReportRunSvg, TimingHasOneMarkerPerSolve) {
  RunView run = two_level_run();
  const std::string svg = report::timing_svg(run);
  EXPECT_EQ(nesting_error(svg), "");
  EXPECT_EQ(count(svg, "class=\"solve "), run.solves.size());
  EXPECT_EQ(count(svg, "class=\"solve local\""), 2u);
  EXPECT_EQ(count(svg, "class=\"solve full\""), 1u);
  EXPECT_EQ(count(svg, "class=\"frontend\""), 1u);
  EXPECT_EQ(attribute(svg, "frontend", "data-count"), "32");
  // Axes labelled.
  EXPECT_NE(svg.find(">time (s)</text>"), std::string::npos);
  EXPECT_GE(count(svg, "class=\"tick-label v\""), 4u);
  for (int i = 0; i < 5; ++i) run.solves.push_back({3.0 + i, 0.001, i % 2 == 0});
  EXPECT_EQ(count(report::timing_svg(run), "class=\"solve "), 8u);
  // An empty run still gives a valid picture.
  EXPECT_EQ(nesting_error(report::timing_svg(RunView())), "");
  EXPECT_EQ(nesting_error(report::birdseye_svg(RunView(), 0)), "");
  EXPECT_EQ(nesting_error(report::side_view_svg(RunView())), "");
}

}  // namespace
}  // namespace tsgraphs
