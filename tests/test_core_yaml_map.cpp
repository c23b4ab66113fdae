// YamlMap: typed access with defaults, and errors that name the file, the line and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/yaml_map.hpp"

#include "test_support.hpp"

using namespace tsgraphs;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using tsgraphs::test::input_error_of;
using tsgraphs::test::TempDirTest;

namespace {

const std::string kDoc = R"(name: lab
seed: 7
ratio: 0.25
enabled: true
nothing:
sensor:
  channels: 64
  range: 60.5
  colour: red
point: [1.5, -2]
poly: [[0, 0], [1, 0], [1, 1]]
walls:
  - from: [0, 0]
    to: [4, 0]
  - from: [4, 0]
)";

YamlMap doc(const std::string& text = kDoc) { return YamlMap::load_string(text, "test.yaml"); }

using YamlMapFile = TempDirTest;

}  // namespace

// ---------------------------------------------------------------- values

TEST(YamlMap, GetReturnsValuesAndDefaults) {
  const YamlMap m = doc();
  EXPECT_EQ(m.get<std::string>("name", "x"), "lab");
  EXPECT_EQ(m.get<int>("seed", 0), 7);
  EXPECT_DOUBLE_EQ(m.get<double>("ratio", 0.0), 0.25);
  EXPECT_TRUE(m.get<bool>("enabled", false));
  EXPECT_EQ(m.get<int>("absent", 42), 42);
  EXPECT_DOUBLE_EQ(m.get<double>("absent", -1.5), -1.5);
  EXPECT_EQ(m.get<std::string>("absent", "fallback"), "fallback");
  // A key with no value reads as absent.
  EXPECT_FALSE(m.has("nothing"));
  EXPECT_EQ(m.get<int>("nothing", 3), 3);
  EXPECT_TRUE(m.has("seed"));
  EXPECT_FALSE(m.has("absent"));
}

TEST(YamlMap, RequireReturnsValues) {
  const YamlMap m = doc();
  EXPECT_EQ(m.require<int>("seed"), 7);
  EXPECT_DOUBLE_EQ(m.require<double>("seed"), 7.0);  // an integer is a number
  EXPECT_EQ(m.require<std::string>("name"), "lab");
  const YamlMap sensor = m.map("sensor");
  EXPECT_EQ(sensor.path(), "sensor");
  EXPECT_EQ(sensor.file(), "test.yaml");
  EXPECT_EQ(sensor.require<int>("channels"), 64);
  EXPECT_DOUBLE_EQ(sensor.require<double>("range"), 60.5);
}

TEST(YamlMap, MissingNestedMappingIsEmpty) {
  const YamlMap absent = doc().map("odometry");
  EXPECT_FALSE(absent.has("anything"));
  EXPECT_DOUBLE_EQ(absent.get<double>("trans_noise_per_m", 0.01), 0.01);
  EXPECT_NO_THROW(absent.check_keys({}));
}

TEST(YamlMap, LineOfKeys) {
  const YamlMap m = doc();
  EXPECT_EQ(m.line_of("name"), 1);
  EXPECT_EQ(m.line_of("ratio"), 3);
  EXPECT_EQ(m.line_of("walls"), 12);
  EXPECT_EQ(m.map("sensor").line_of("colour"), 9);
}

TEST(YamlMap, MapsOfAList) {
  const std::vector<YamlMap> walls = doc().maps("walls");
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_EQ(walls[0].path(), "walls[0]");
  EXPECT_EQ(walls[1].path(), "walls[1]");
  EXPECT_TRUE(walls[0].has("to"));
  EXPECT_FALSE(walls[1].has("to"));
  EXPECT_TRUE(doc().maps("absent").empty());
}

TEST(YamlMap, Vec2AndPolygon) {
  const YamlMap m = doc();
  const Vec2 p = m.vec2("point");
  EXPECT_DOUBLE_EQ(p.x(), 1.5);
  EXPECT_DOUBLE_EQ(p.y(), -2.0);
  const Polygon2 poly = m.polygon("poly");
  ASSERT_EQ(poly.size(), 3u);
  EXPECT_DOUBLE_EQ(poly[0].x(), 0.0);
  EXPECT_DOUBLE_EQ(poly[1].x(), 1.0);
  EXPECT_DOUBLE_EQ(poly[1].y(), 0.0);
  EXPECT_DOUBLE_EQ(poly[2].x(), 1.0);
  EXPECT_DOUBLE_EQ(poly[2].y(), 1.0);
  const Vec2 to = m.maps("walls")[0].vec2("to");
  EXPECT_DOUBLE_EQ(to.x(), 4.0);
  EXPECT_DOUBLE_EQ(to.y(), 0.0);
}

// ---------------------------------------------------------------- errors

TEST(YamlMapErrors, RequireOfAMissingKeyNamesFileLineAndKey) {
  const std::string root = input_error_of([] { doc().require<int>("frames"); });
  EXPECT_THAT(root, StartsWith("test.yaml:1: "));
  EXPECT_THAT(root, HasSubstr("'frames'"));

  const std::string nested = input_error_of([] { doc().map("sensor").require<double>("max_range"); });
  EXPECT_THAT(nested, StartsWith("test.yaml:7: "));  // the mapping's first line
  EXPECT_THAT(nested, HasSubstr("sensor"));
  EXPECT_THAT(nested, HasSubstr("max_range"));

  const std::string entry = input_error_of([] { doc().maps("walls")[1].vec2("to"); });
  EXPECT_THAT(entry, StartsWith("test.yaml:15: "));
  EXPECT_THAT(entry, HasSubstr("walls[1]"));
  EXPECT_THAT(entry, HasSubstr("'to'"));
}

TEST(YamlMapErrors, UnknownKeyNamesTheKeyAndItsLine) {
  const std::string root = input_error_of([] {
    doc().check_keys(
        {"name", "seed", "ratio", "enabled", "nothing", "sensor", "point", "poly", "walls_typo"});
  });
  EXPECT_THAT(root, StartsWith("test.yaml:12: "));
  EXPECT_THAT(root, HasSubstr("'walls'"));
  EXPECT_THAT(root, HasSubstr("walls_typo"));  // the known keys are listed

  const std::string nested = input_error_of([] { doc().map("sensor").check_keys({"channels", "range"}); });
  EXPECT_THAT(nested, StartsWith("test.yaml:9: "));
  EXPECT_THAT(nested, HasSubstr("'sensor.colour'"));

  EXPECT_NO_THROW(doc().map("sensor").check_keys({"channels", "range", "colour"}));
  EXPECT_NO_THROW(
      doc().check_keys({"name", "seed", "ratio", "enabled", "nothing", "sensor", "point", "poly", "walls"}));
}

// Issue 52 (found by the map_import fuzz target): an unknown or repeated key was quoted with
// the file's raw bytes. Keys are quoted printable (other bytes as \xNN), as every text of a file.
TEST(YamlMapErrors, KeysAreQuotedPrintable) {
  const std::string unknown =
      input_error_of([] { doc("name: a\nre\xff\x1b[2Jsolution: 1\n").check_keys({"name"}); });
  EXPECT_EQ(unknown, "test.yaml:2: unknown key 're\\xff\\x1b[2Jsolution' (known keys: name)");
  const std::string nested =
      input_error_of([] { doc("sensor:\n  \"\\x07\": 1\n").map("sensor").check_keys({"range"}); });
  EXPECT_EQ(nested, "test.yaml:2: unknown key 'sensor.\\x07' (known keys: range)");
  const std::string twice = input_error_of([] { doc("\"a\\tb\": 1\n\"a\\tb\": 2\n").check_keys({"a\tb"}); });
  EXPECT_EQ(twice, "test.yaml:2: duplicate key 'a\\x09b' (first at line 1)");
}

TEST(YamlMapErrors, TypeErrorsNameTheLine) {
  const std::string text = "a: 1\nb: abc\nc: maybe\nd: [1, 2]\ne: 2.5\n";
  const std::string number = input_error_of([&] { doc(text).require<double>("b"); });
  EXPECT_THAT(number, StartsWith("test.yaml:2: "));
  EXPECT_THAT(number, HasSubstr("b: expected a number"));

  const std::string defaulted = input_error_of([&] { doc(text).get<double>("b", 1.0); });
  EXPECT_THAT(defaulted, StartsWith("test.yaml:2: "));

  const std::string boolean = input_error_of([&] { doc(text).require<bool>("c"); });
  EXPECT_THAT(boolean, StartsWith("test.yaml:3: "));
  EXPECT_THAT(boolean, HasSubstr("true or false"));

  const std::string list = input_error_of([&] { doc(text).require<int>("d"); });
  EXPECT_THAT(list, StartsWith("test.yaml:4: "));

  const std::string fraction = input_error_of([&] { doc(text).require<int>("e"); });
  EXPECT_THAT(fraction, StartsWith("test.yaml:5: "));
  EXPECT_THAT(fraction, HasSubstr("an integer"));

  const std::string nested =
      input_error_of([] { doc("s:\n  x: 1\n  y: one\n").map("s").require<double>("y"); });
  EXPECT_THAT(nested, StartsWith("test.yaml:3: "));
  EXPECT_THAT(nested, HasSubstr("s.y"));
}

TEST(YamlMapErrors, NonFiniteNumbersAreRejected) {
  const std::string text = "a: 1\nb: .nan\nc: .inf\nd: -.inf\ne: [0, .nan]\n";
  for (const auto& [key, line] : {std::pair<std::string, int>{"b", 2}, {"c", 3}, {"d", 4}}) {
    const std::string msg = input_error_of([&, k = key] { doc(text).require<double>(k); });
    EXPECT_THAT(msg, StartsWith("test.yaml:" + std::to_string(line) + ": ")) << key;
    EXPECT_THAT(msg, HasSubstr("finite")) << key;
    EXPECT_THAT(input_error_of([&, k = key] { doc(text).get<double>(k, 0.0); }), HasSubstr("finite")) << key;
    EXPECT_THAT(input_error_of([&, k = key] { doc(text).require<float>(k); }), HasSubstr("finite")) << key;
  }
  const std::string point = input_error_of([&] { doc(text).vec2("e"); });
  EXPECT_THAT(point, StartsWith("test.yaml:5: "));
  EXPECT_THAT(point, HasSubstr("finite"));
}

TEST(YamlMapErrors, BadVec2) {
  const std::string text = "three: [1, 2, 3]\nscalar: 5\nword: [1, x]\nmap: {x: 1, y: 2}\n";
  EXPECT_THAT(input_error_of([&] { doc(text).vec2("three"); }), StartsWith("test.yaml:1: "));
  EXPECT_THAT(input_error_of([&] { doc(text).vec2("scalar"); }), StartsWith("test.yaml:2: "));
  const std::string word = input_error_of([&] { doc(text).vec2("word"); });
  EXPECT_THAT(word, StartsWith("test.yaml:3: "));
  EXPECT_THAT(word, HasSubstr("word"));
  EXPECT_THAT(input_error_of([&] { doc(text).vec2("map"); }), StartsWith("test.yaml:4: "));
  EXPECT_THAT(input_error_of([&] { doc(text).vec2("absent"); }), HasSubstr("'absent'"));
}

TEST(YamlMapErrors, BadPolygon) {
  const std::string text = R"(two: [[0, 0], [1, 0]]
bad_point:
  - [0, 0]
  - [1, 0]
  - [1, x]
flat: [0, 1, 2, 3]
)";
  const std::string two = input_error_of([&] { doc(text).polygon("two"); });
  EXPECT_THAT(two, StartsWith("test.yaml:1: "));
  EXPECT_THAT(two, HasSubstr("three"));
  const std::string bad = input_error_of([&] { doc(text).polygon("bad_point"); });
  EXPECT_THAT(bad, StartsWith("test.yaml:5: "));
  EXPECT_THAT(bad, HasSubstr("bad_point[2]"));
  const std::string flat = input_error_of([&] { doc(text).polygon("flat"); });
  EXPECT_THAT(flat, StartsWith("test.yaml:6: "));
  EXPECT_THAT(flat, HasSubstr("flat[0]"));
}

TEST(YamlMapErrors, MapsOfANonListAndNonMappingEntries) {
  const std::string text = "walls: 3\nrooms:\n  - 5\n";
  const std::string walls = input_error_of([&] { doc(text).maps("walls"); });
  EXPECT_THAT(walls, StartsWith("test.yaml:1: "));
  EXPECT_THAT(walls, HasSubstr("list"));
  const std::string rooms = input_error_of([&] { doc(text).maps("rooms"); });
  EXPECT_THAT(rooms, StartsWith("test.yaml:3: "));
  EXPECT_THAT(rooms, HasSubstr("rooms[0]"));
  EXPECT_THAT(input_error_of([&] { doc(text).map("walls"); }), HasSubstr("walls"));
}

TEST(YamlMapErrors, DocumentThatIsNotAMapping) {
  const std::string msg = input_error_of([] { doc("- 1\n- 2\n"); });
  EXPECT_THAT(msg, StartsWith("test.yaml:1: "));
  EXPECT_THAT(msg, HasSubstr("mapping"));
  EXPECT_NO_THROW(doc(""));  // an empty document is an empty mapping
}

TEST(YamlMapErrors, CustomErrors) {
  const YamlMap m = doc();
  EXPECT_STREQ(m.error("ratio", "must be above 1").what(), "test.yaml:3: ratio: must be above 1");
  EXPECT_STREQ(m.map("sensor").error("range", "too far").what(), "test.yaml:8: sensor.range: too far");
  EXPECT_STREQ(m.maps("walls")[1].error_here("too short").what(), "test.yaml:15: walls[1]: too short");
}

TEST(YamlMapErrors, SyntaxErrorInAString) {
  const std::string msg =
      input_error_of([] { YamlMap::load_string("a: 1\nb: 2\nc: d: e\n", "broken.yaml"); });
  EXPECT_THAT(msg, StartsWith("broken.yaml:3: "));
  EXPECT_THAT(msg, HasSubstr("syntax"));
}

// Issue 52: yaml-cpp's message quotes the byte it stumbled on, raw; it reaches the user printable.
TEST(YamlMapErrors, SyntaxErrorQuotesNoRawByte) {
  EXPECT_EQ(input_error_of([] { YamlMap::load_string("a: 1\nb: \"\\\x01\"\n", "broken.yaml"); }),
            "broken.yaml:2: YAML syntax error: unknown escape character: \\x01");
}

TEST(YamlMapErrors, OutOfRangeIntegers) {
  EXPECT_THAT(input_error_of([] { doc("a: 1\nx: -1\n").require<unsigned>("x"); }),
              StartsWith("test.yaml:2: "));
  EXPECT_THAT(input_error_of([] { doc("x: -1\n").require<std::size_t>("x"); }), StartsWith("test.yaml:1: "));
  EXPECT_THAT(input_error_of([] { doc("x: 99999999999\n").require<int>("x"); }), StartsWith("test.yaml:1: "));
}

// YAML mapping keys must be unique, but yaml-cpp keeps the first of two equal keys and drops
// the second without a word: editing the later "seed: 2" changes nothing. check_keys, which
// every mapping of a scene goes through, is the place to reject it.
TEST(YamlMapErrors, DuplicateKeyIsRejected) {
  const YamlMap m = doc("name: a\nseed: 1\nseed: 2\n");
  const std::string msg = input_error_of([&] { m.check_keys({"name", "seed"}); });
  EXPECT_THAT(msg, StartsWith("test.yaml:3: "));
  EXPECT_THAT(msg, HasSubstr("seed"));
}

TEST_F(YamlMapFile, LoadsAFile) {
  const std::string path = write_file("scene.yaml", kDoc);
  const YamlMap m = YamlMap::load_file(path);
  EXPECT_EQ(m.file(), path);
  EXPECT_EQ(m.require<int>("seed"), 7);
  EXPECT_THAT(input_error_of([&] { m.require<int>("absent"); }), StartsWith(path + ":1: "));
}

TEST_F(YamlMapFile, MissingFileNamesTheFile) {
  const std::string path = (dir_ / "nope.yaml").string();
  const std::string msg = input_error_of([&] { YamlMap::load_file(path); });
  EXPECT_THAT(msg, StartsWith(path + ": "));
}

TEST_F(YamlMapFile, SyntaxErrorNamesFileAndLine) {
  const std::string path = write_file("broken.yaml", "name: x\nseed: 1\nwalls: [1, 2\nrooms: 3: 4\n");
  const std::string msg = input_error_of([&] { YamlMap::load_file(path); });
  EXPECT_THAT(msg, ::testing::MatchesRegex(".*broken\\.yaml:[0-9]+: .*"));
  EXPECT_THAT(msg, StartsWith(path + ":"));

  const std::string path2 = write_file("broken2.yaml", "a: 1\nb: 2\nc: d: e\n");
  EXPECT_THAT(input_error_of([&] { YamlMap::load_file(path2); }), StartsWith(path2 + ":3: "));
}

// A folder opens as an ifstream on Linux; reading it then throws std::ios_base::failure
// ("basic_filebuf::underflow error reading the file: Is a directory"), which escapes load_file
// as a plain std::exception instead of an InputError naming the file.
TEST_F(YamlMapFile, FolderInsteadOfAFile) {
  const std::string msg = input_error_of([&] { YamlMap::load_file(dir_.string()); });
  EXPECT_THAT(msg, HasSubstr(dir_.string()));
}
