// The bird's-eye SVG of a scene: well-formed XML, one panel per level, every wall piece,
// door, window and railing of the scene drawn once on its level, names escaped, the first
// lap of the path with arrows in proportion to its length, and byte-identical output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "tsgraphs/report/scene_svg.hpp"
#include "tsgraphs/report/svg_writer.hpp"
#include "tsgraphs/scene/scene_geometry.hpp"
#include "tsgraphs/sim/scene_mesh.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/trajectory.hpp"

using namespace tsgraphs;
using namespace tsgraphs::sim;
using namespace tsgraphs::scene;

namespace {

// Two storeys joined by a ramp that rises through a void of the upper one; an atrium void
// with railings of both styles; doors and windows; names that need escaping.
const char* kTwoStoreys = R"(
name: "Atrium & <mezzanine> \"test\""
levels:
  - name: L0
    elevation: 0.0
    slab: [[0,0],[20,0],[20,16],[0,16]]
  - name: "Mezz & <1>"
    elevation: 3.5
    slab: [[0,0],[20,0],[20,16],[0,16]]
    voids:
      - [[8,5],[14,5],[14,10],[8,10]]
      - [[0.5,9],[3.5,9],[3.5,13],[0.5,13]]
walls:
  - {level: L0, from: [0,0], to: [20,0], openings: [{at: 5, width: 1.5, height: 1.2, sill: 0.9}, {at: 12, width: 1.5, height: 1.2, sill: 0.9}]}
  - {level: L0, from: [20,0], to: [20,16]}
  - {level: L0, from: [20,16], to: [0,16]}
  - {level: L0, from: [0,16], to: [0,0], openings: [{at: 7, width: 1.0, height: 2.1}]}
  - {level: L0, from: [0,5], to: [7,5], thickness: 0.12, openings: [{at: 4, width: 0.9}]}
  - {level: L0, from: [7,0], to: [7,5], thickness: 0.12, openings: [{at: 2.5, width: 0.9, height: 3.0}]}
  - {level: "Mezz & <1>", from: [0,0], to: [20,0]}
  - {level: "Mezz & <1>", from: [20,0], to: [20,16], openings: [{at: 7, width: 2.0, height: 1.5, sill: 1.0}]}
  - {level: "Mezz & <1>", from: [20,16], to: [0,16]}
  - {level: "Mezz & <1>", from: [0,16], to: [0,0]}
  - {level: "Mezz & <1>", from: [14,0], to: [14,4], openings: [{at: 2, width: 0.9}]}
railings:
  - {level: "Mezz & <1>", from: [8,5], to: [14,5], style: solid}
  - {level: "Mezz & <1>", from: [14,5], to: [14,10], style: bars}
  - {level: "Mezz & <1>", from: [14,10], to: [8,10], style: solid}
  - {level: "Mezz & <1>", from: [8,10], to: [8,5], style: bars}
  - {level: "Mezz & <1>", from: [3.5,9], to: [3.5,13], style: bars}
boxes:
  - {level: L0, min: [1,1,0], max: [1.5,4,2], label: bookshelf}
  - {level: L0, min: [10,5.5,0], max: [12,6.5,0.8], yaw_deg: 30, label: "desk 'A' > B"}
  - {level: "Mezz & <1>", min: [16,8,0], max: [18,9,1], yaw_deg: -20, label: sofa}
ramps:
  - {from_level: L0, to_level: "Mezz & <1>", polygon: [[1,9],[3,9],[3,13],[1,13]], axis: [0, 1]}
rooms:
  - {name: "office & co", level: L0, polygon: [[0,0],[7,0],[7,5],[0,5]]}
  - {name: hall, level: L0, polygon: [[7,0],[20,0],[20,16],[0,16],[0,5],[7,5]]}
  - {name: "<gallery>", level: "Mezz & <1>", polygon: [[0,0],[20,0],[20,16],[0,16]]}
  - {name: "odd\x01name", level: L0, polygon: [[15,12],[19,12],[19,15],[15,15]]}
trajectory:
  level: L0
  waypoints: [[4,2],[4,7.8],[17,7.8],[17,12],[5,12],[2,8.5],[2,14,"Mezz & <1>"],[6,14,"Mezz & <1>"],
              [18.8,14,"Mezz & <1>"],[18.8,2,"Mezz & <1>"],[5,3,"Mezz & <1>"]]
  closed: false
  laps: 2
)";

Scene two_storeys() { return parse_scene(kTwoStoreys, "test.yaml", "."); }

std::string draw(const Scene& scene) { return report::scene_svg(scene, Trajectory(scene)); }

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos;
       at = text.find(needle, at + needle.size()))
    ++n;
  return n;
}

/// The text of each level panel, in page order (the legend, which shows one of everything,
/// is left out).
std::vector<std::string> panels(const std::string& svg) {
  const std::string open = "<g class=\"panel\"";
  const std::size_t legend = svg.find("<g class=\"legend\"");
  std::vector<std::string> out;
  for (std::size_t at = svg.find(open); at != std::string::npos && at < legend;) {
    const std::size_t next = std::min(svg.find(open, at + 1), legend);
    out.push_back(svg.substr(at, next - at));
    at = next;
  }
  return out;
}

std::string all_panels(const std::string& svg) {
  std::string s;
  for (const std::string& p : panels(svg)) s += p;
  return s;
}

/// Checks tags nest: every start tag is closed by the matching end tag (or is empty), the
/// root is <svg>, nothing is left open. Returns "" or what went wrong.
std::string nesting_error(const std::string& svg) {
  std::vector<std::string> open;
  for (std::size_t at = svg.find('<'); at != std::string::npos; at = svg.find('<', at + 1)) {
    const std::size_t end = svg.find('>', at);
    if (end == std::string::npos) return "unterminated tag at " + std::to_string(at);
    const std::string tag = svg.substr(at + 1, end - at - 1);
    if (tag.find('<') != std::string::npos) return "'<' inside a tag at " + std::to_string(at);
    if (tag.empty()) return "empty tag";
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back() != name)
        return "</" + name + "> closes " + (open.empty() ? "nothing" : open.back());
      open.pop_back();
    } else if (tag.back() != '/') {
      const std::string name = tag.substr(0, tag.find_first_of(" \n"));
      if (open.empty() && name != "svg") return "root element is " + name;
      open.push_back(name);
    } else if (open.empty()) {
      return "empty root element";
    }
  }
  return open.empty() ? "" : "<" + open.back() + "> is never closed";
}

struct Translate {
  double x, y;
};
std::vector<Translate> panel_offsets(const std::string& svg) {
  std::vector<Translate> out;
  const std::regex re("<g class=\"panel\" transform=\"translate\\(([-0-9.]+),([-0-9.]+)\\)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it) {
    out.push_back({std::stod((*it)[1]), std::stod((*it)[2])});
  }
  return out;
}

/// A straight corridor walked out and back, `length` m each way.
Scene corridor(double length, int laps) {
  const std::string l = std::to_string(length);
  return parse_scene("name: corridor\nlevels: [{name: L0, slab: [[0,0],[" + std::to_string(length + 2.0) +
                         ",0],[" + std::to_string(length + 2.0) +
                         ",4],[0,4]]}]\n"
                         "trajectory: {waypoints: [[1,2],[" +
                         std::to_string(length + 1.0) +
                         ",2]], closed: false, "
                         "laps: " +
                         std::to_string(laps) + "}\n",
                     "corridor.yaml", ".");
}

}  // namespace

// Issue 18: a scene's slab vertex at 1e12 m made a 4e13-pixel drawing. Scenes are bounded
// (10 km across), and a scene kilometres long is drawn smaller, within svg::kMaxDrawingPx.
TEST(SceneSvg, ASceneKilometresLongFitsThePage) {
  const auto page = [](const std::string& svg) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(svg, m, std::regex("<svg [^>]*width=\"([0-9.]+)\" height=\"([0-9.]+)\"")));
    return std::pair<double, double>(std::stod(m[1].str()), std::stod(m[2].str()));
  };
  EXPECT_NE(draw(corridor(30.0, 1)).find("40 px per metre"),
            std::string::npos);  // a building keeps its scale
  const auto [w, h] = page(draw(corridor(5000.0, 1)));
  EXPECT_LE(w, report::svg::kMaxDrawingPx + 1000.0);
  EXPECT_LE(h, report::svg::kMaxDrawingPx + 1000.0);
  EXPECT_GT(w, 0.9 * report::svg::kMaxDrawingPx);
}

TEST(SceneSvg, IsWellFormedXml) {
  const std::string svg = draw(two_storeys());
  ASSERT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u) << svg.substr(0, 80);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(count(svg, "<"), count(svg, ">"));
  EXPECT_EQ(count(svg, "<g ") + count(svg, "<g>"), count(svg, "</g>"));
  EXPECT_EQ(count(svg, "<text "), count(svg, "</text>"));
  EXPECT_EQ(nesting_error(svg), "");
  // Every '&' starts an entity.
  const std::regex entity("&(amp|lt|gt|quot|apos);");
  std::size_t entities = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), entity); it != std::sregex_iterator(); ++it)
    ++entities;
  EXPECT_EQ(count(svg, "&"), entities);
  EXPECT_GT(entities, 0u);
  // Only bytes XML allows: no control characters besides newlines.
  for (const char c : svg) EXPECT_TRUE(static_cast<unsigned char>(c) >= 0x20 || c == '\n') << int(c);
  // Fixed-point numbers only.
  EXPECT_EQ(count(svg, "nan"), 0u);
  EXPECT_EQ(count(svg, "inf"), 0u);
  EXPECT_EQ(count(svg, "-0.00"), 0u);
  EXPECT_FALSE(std::regex_search(svg, std::regex("[0-9]\\.[0-9]*e[-+]?[0-9]")));
}

TEST(SceneSvg, OnePanelPerLevelTitledWithNameAndElevation) {
  const Scene scene = two_storeys();
  const std::string svg = draw(scene);
  const std::vector<std::string> p = panels(svg);
  ASSERT_EQ(p.size(), scene.levels.size());
  EXPECT_EQ(count(svg, "class=\"panel-title\""), scene.levels.size());
  // Lowest level first; names escaped; elevations printed.
  EXPECT_NE(p[0].find(">L0 \xE2\x80\x94 elevation 0.00 m</text>"), std::string::npos);
  EXPECT_NE(p[1].find(">Mezz &amp; &lt;1&gt; \xE2\x80\x94 elevation 3.50 m</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "Mezz & <1>"), 0u);
  // The scene's name is the document's title.
  EXPECT_NE(svg.find("<title>Atrium &amp; &lt;mezzanine&gt; &quot;test&quot;</title>"), std::string::npos);
}

TEST(SceneSvg, PanelsOrderedByElevationWhateverTheFileOrder) {
  std::string text = kTwoStoreys;
  // Swap the two level entries: the upper storey is listed first.
  const std::size_t l0 = text.find("  - name: L0"), l1 = text.find("  - name: \"Mezz"),
                    walls = text.find("walls:");
  text = text.substr(0, l0) + text.substr(l1, walls - l1) + text.substr(l0, l1 - l0) + text.substr(walls);
  const Scene scene = parse_scene(text, "swapped.yaml", ".");
  ASSERT_EQ(scene.levels[0].name, "Mezz & <1>");
  const std::vector<std::string> p = panels(draw(scene));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NE(p[0].find("elevation 0.00 m"), std::string::npos);
  EXPECT_NE(p[1].find("elevation 3.50 m"), std::string::npos);
}

TEST(SceneSvg, RoomNamesAndLabelsAreEscapedOnTheirLevel) {
  const std::string svg = draw(two_storeys());
  const std::vector<std::string> p = panels(svg);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NE(p[0].find(">office &amp; co</text>"), std::string::npos);
  EXPECT_NE(p[0].find(">hall</text>"), std::string::npos);
  EXPECT_NE(p[1].find(">&lt;gallery&gt;</text>"), std::string::npos);
  EXPECT_EQ(p[0].find("gallery"), std::string::npos);
  // A control character (not allowed in XML) is replaced.
  EXPECT_NE(p[0].find(">odd?name</text>"), std::string::npos);
  // Four rooms, each a polygon on its own level, each a different colour.
  EXPECT_EQ(count(p[0], "class=\"room\""), 3u);
  EXPECT_EQ(count(p[1], "class=\"room\""), 1u);
  std::set<std::string> colours;
  const std::string rooms = all_panels(svg);
  const std::regex fill("class=\"room\" fill=\"(#[0-9a-f]{6})\"");
  for (auto it = std::sregex_iterator(rooms.begin(), rooms.end(), fill); it != std::sregex_iterator(); ++it) {
    colours.insert((*it)[1]);
  }
  EXPECT_EQ(colours.size(), 4u);
  // Box labels, quotes and '>' escaped.
  EXPECT_NE(p[0].find(">desk &apos;A&apos; &gt; B</text>"), std::string::npos);
  EXPECT_NE(p[1].find(">sofa</text>"), std::string::npos);
  EXPECT_EQ(count(p[0], "class=\"box\""), 2u);
  EXPECT_EQ(count(p[1], "class=\"box\""), 1u);
}

TEST(SceneSvg, EveryWallPieceIsOneRectangleOnItsLevel) {
  const Scene scene = two_storeys();
  const std::vector<std::string> p = panels(draw(scene));
  ASSERT_EQ(p.size(), 2u);
  for (int level = 0; level < 2; ++level) {
    std::size_t pieces = 0, full = 0, header = 0, sill = 0;
    for (const Wall& w : scene.walls) {
      if (w.level != level) continue;
      for (const WallPiece& piece : wall_pieces(w)) {
        ++pieces;
        if (piece.z0 > 0.0)
          ++header;
        else if (piece.z1 < w.height)
          ++sill;
        else
          ++full;
      }
    }
    SCOPED_TRACE("level " + scene.levels[level].name);
    EXPECT_EQ(count(p[level], "class=\"wall "), pieces);
    EXPECT_EQ(count(p[level], "class=\"wall full\""), full);
    EXPECT_EQ(count(p[level], "class=\"wall header\""), header);
    EXPECT_EQ(count(p[level], "class=\"wall sill\""), sill);
  }
  // L0: 4 walls without openings' pieces ... worked out by hand for one wall: the south wall
  // with two windows is 3 full pieces, 2 sills and 2 headers.
  EXPECT_EQ(wall_pieces(scene.walls[0]).size(), 7u);
}

TEST(SceneSvg, DoorsAndWindowsAreMarked) {
  const Scene scene = two_storeys();
  const std::vector<std::string> p = panels(draw(scene));
  ASSERT_EQ(p.size(), 2u);
  // By hand: L0 has 3 doors (one full height) and 2 windows, the mezzanine 1 door and 1 window.
  EXPECT_EQ(count(p[0], "class=\"door\""), 3u);
  EXPECT_EQ(count(p[0], "class=\"window\""), 2u);
  EXPECT_EQ(count(p[1], "class=\"door\""), 1u);
  EXPECT_EQ(count(p[1], "class=\"window\""), 1u);
  // A door is its leaf and the arc of its swing, of the door's width (0.9 m = 36 px).
  EXPECT_NE(p[1].find("A36.00,36.00 0 0,"), std::string::npos);
  // A full-height door leaves no wall above it: 2 of the 3 doors of L0 and the 2 windows
  // have a header.
  EXPECT_EQ(count(p[0], "class=\"wall header\""), 4u);
}

TEST(SceneSvg, SolidAndBarsRailingsAreDrawnDifferently) {
  const Scene scene = two_storeys();
  const std::vector<std::string> p = panels(draw(scene));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(count(p[1], "class=\"railing solid\""), 2u);
  EXPECT_EQ(count(p[1], "class=\"railing bars\""), 3u);
  EXPECT_EQ(count(p[0], "class=\"railing"), 0u);
  // Bars are dotted, solid railings are not.
  const std::size_t bars = p[1].find("class=\"railing bars\"");
  EXPECT_NE(p[1].substr(bars, p[1].find("</g>", bars) - bars).find("stroke-dasharray"), std::string::npos);
  const std::size_t solid = p[1].find("class=\"railing solid\"");
  EXPECT_EQ(p[1].substr(solid, p[1].find("/>", solid) - solid).find("stroke-dasharray"), std::string::npos);
}

TEST(SceneSvg, VoidsAndRampsAreMarked) {
  const std::vector<std::string> p = panels(draw(two_storeys()));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(count(p[0], "class=\"void\""), 0u);
  EXPECT_EQ(count(p[1], "class=\"void\""), 2u);
  // The atrium void is labelled; the one the ramp fills is labelled by the ramp instead.
  EXPECT_EQ(count(p[1], ">void</text>"), 1u);
  // The ramp shows on both levels it joins, naming the other one.
  EXPECT_EQ(count(p[0], "class=\"ramp\""), 1u);
  EXPECT_EQ(count(p[1], "class=\"ramp\""), 1u);
  EXPECT_NE(p[0].find(">ramp to Mezz &amp; &lt;1&gt; (up)</text>"), std::string::npos);
  EXPECT_NE(p[1].find(">ramp to L0 (down)</text>"), std::string::npos);
  EXPECT_EQ(count(p[0], "class=\"ramp-arrow\""), 1u);
}

TEST(SceneSvg, PathOfTheFirstLapOnTheLevelsItCrosses) {
  const Scene scene = two_storeys();
  const std::string svg = draw(scene);
  const std::vector<std::string> p = panels(svg);
  ASSERT_EQ(p.size(), 2u);
  // It starts on L0 and climbs the ramp to the mezzanine: drawn on both.
  EXPECT_GT(count(p[0], "class=\"path\""), 5u);
  EXPECT_GT(count(p[1], "class=\"path\""), 5u);
  EXPECT_GT(count(p[0], "class=\"arrow\""), 0u);
  EXPECT_GT(count(p[1], "class=\"arrow\""), 0u);
  // One start (L0) and, the lap ending away from it, one end (on the mezzanine).
  EXPECT_EQ(count(p[0], "class=\"start\""), 1u);
  EXPECT_EQ(count(p[1], "class=\"start\""), 0u);
  EXPECT_EQ(count(p[0], "class=\"end\""), 0u);
  EXPECT_EQ(count(p[1], "class=\"end\""), 1u);
  // Coloured along time: many colours, and the start's differs from the end's.
  const std::string all = all_panels(svg);
  const std::regex stroke("class=\"path\" stroke=\"(#[0-9a-f]{6})\"");
  std::vector<std::string> colours;
  for (auto it = std::sregex_iterator(all.begin(), all.end(), stroke); it != std::sregex_iterator(); ++it) {
    colours.push_back((*it)[1]);
  }
  ASSERT_GE(colours.size(), 2u);
  EXPECT_NE(colours.front(), colours.back());
  EXPECT_GE(std::set<std::string>(colours.begin(), colours.end()).size(), 10u);
  // The lap is ~84 m long at 1 m/s: about one coloured piece per second.
  const Trajectory traj(scene);
  EXPECT_NEAR(static_cast<double>(colours.size()), traj.lap_starts()[1], 6.0);
}

TEST(SceneSvg, ArrowCountGrowsWithThePathLengthAndCoversOneLap) {
  const auto arrows = [](const Scene& s) { return count(all_panels(draw(s)), "class=\"arrow\""); };
  const std::size_t short_path = arrows(corridor(10.0, 1));
  const std::size_t long_path = arrows(corridor(30.0, 1));
  EXPECT_GE(short_path, 2u);
  EXPECT_GT(long_path, short_path);
  // In proportion to the length (three times as long: about three times as many).
  EXPECT_GE(static_cast<double>(long_path), 2.5 * static_cast<double>(short_path));
  EXPECT_LE(static_cast<double>(long_path), 3.5 * static_cast<double>(short_path) + 1.0);
  // Only the first lap is drawn: more laps change nothing.
  EXPECT_EQ(draw(corridor(10.0, 1)), draw(corridor(10.0, 3)));
  EXPECT_EQ(count(all_panels(draw(corridor(10.0, 3))), "class=\"start\""), 1u);
}

TEST(SceneSvg, SameSceneSameBytes) {
  const Scene scene = two_storeys();
  const std::string a = draw(scene);
  EXPECT_EQ(a, draw(scene));
  EXPECT_EQ(a, draw(two_storeys()));
  // A different scene gives a different picture.
  EXPECT_NE(a, draw(corridor(10.0, 1)));
}

TEST(SceneSvg, WideScenesStackTheirPanelsTallOnesSitSideBySide) {
  const auto two_levels = [](double w, double h) {
    const std::string slab = "[[0,0],[" + std::to_string(w) + ",0],[" + std::to_string(w) + "," +
                             std::to_string(h) + "],[0," + std::to_string(h) + "]]";
    return parse_scene("levels:\n  - {name: A, elevation: 0, slab: " + slab +
                           "}\n  - {name: B, elevation: 3, slab: " + slab +
                           "}\ntrajectory: {waypoints: [[1,1],[2,2]]}\n",
                       "layout.yaml", ".");
  };
  const std::vector<Translate> wide = panel_offsets(draw(two_levels(40.0, 5.0)));
  ASSERT_EQ(wide.size(), 2u);
  EXPECT_EQ(wide[0].x, wide[1].x);
  EXPECT_LT(wide[0].y, wide[1].y);
  const std::vector<Translate> tall = panel_offsets(draw(two_levels(5.0, 30.0)));
  ASSERT_EQ(tall.size(), 2u);
  EXPECT_EQ(tall[0].y, tall[1].y);
  EXPECT_LT(tall[0].x, tall[1].x);
}

TEST(SceneSvg, VoxelMapsShowTheirOccupiedCellsButNotTheFloor) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "scene_svg_voxels";
  std::filesystem::create_directories(dir);
  {
    // A row of 21 wall voxels at y = 1 (one run) and a floor patch at y = 3 (left out).
    std::ofstream pcd(dir / "map.pcd");
    const int n = 21 + 10;
    pcd << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << n
        << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA ascii\n";
    for (int k = 0; k <= 20; ++k) pcd << 1.0 + 0.1 * k << " 1.0 1.0\n";
    for (int k = 0; k < 10; ++k) pcd << 1.0 + 0.1 * k << " 3.0 0.0\n";
  }
  const Scene scene = parse_scene(R"(
levels:
  - {name: L0, slab: [[0,0],[6,0],[6,5],[0,5]]}
  - {name: L1, elevation: 3, slab: [[0,0],[6,0],[6,5],[0,5]]}
voxel_maps: [{file: map.pcd, voxel_size: 0.1, level: L1}]
trajectory: {waypoints: [[4,4],[5,4]]}
)",
                                  "voxels.yaml", dir.string());
  const std::vector<std::string> p = panels(draw(scene));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(count(p[0], "class=\"voxels\""), 0u);
  ASSERT_EQ(count(p[1], "class=\"voxels\""), 1u);
  const std::size_t at = p[1].find("class=\"voxels\" d=\"");
  const std::string d = p[1].substr(at, p[1].find("\"/>", at) - at);
  EXPECT_EQ(count(d, "M"), 1u) << d;  // the wall row, merged into one rectangle
  // 21 cells of 0.1 m at 40 px per metre.
  EXPECT_NE(d.find("h84.00"), std::string::npos) << d;
}

// A door whose leaf the scene holds (a box labelled door at its jamb) is drawn as that leaf,
// not as the usual swing; a door without one keeps its swing.
TEST(SceneSvg, ADoorsOwnLeafReplacesItsSwing) {
  Scene scene = parse_scene(R"(name: leaf
levels: [{name: L0, slab: [[0,0],[10,0],[10,8],[0,8]]}]
walls:
  - {level: L0, from: [0, 4], to: [10, 4], thickness: 0.2, openings: [{at: 3, width: 0.9}, {at: 7, width: 0.9}]}
boxes:
  - {level: L0, min: [2.51, 4.14, 0], max: [2.55, 5.0, 2.08], label: door}
trajectory: {waypoints: [[1, 2], [9, 2]]}
)",
                            "leaf.yaml", ".");
  const std::string svg = draw(scene);
  scene.boxes.clear();
  const std::string without = draw(scene);
  EXPECT_EQ(count(svg, "class=\"door leaf\""), 1u);
  EXPECT_EQ(count(without, "class=\"door leaf\""), 0u);
  // One swing fewer (the legend draws one too); the leaf is no box (only the legend's swatch is).
  EXPECT_EQ(count(svg, "<path class=\"door\"") + 1, count(without, "<path class=\"door\""));
  EXPECT_EQ(count(svg, "class=\"box\""), count(without, "class=\"box\""));
}
