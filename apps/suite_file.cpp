// The suite file (suite_file.hpp, docs/suite.md).
#include "suite_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>

#include "methods.hpp"
#include "tsgraphs/core/limits.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/core/yaml_map.hpp"
#include "tsgraphs/io/scan_folder.hpp"
#include "tsgraphs/scene/builtin_scenes.hpp"
#include "tsgraphs/generator/generator.hpp"
#include "tsgraphs/scene/scene_loader.hpp"
#include "tsgraphs/scene/platform_presets.hpp"
#include "tsgraphs/scene/sensor_presets.hpp"

namespace tsgraphs::app {

namespace fs = std::filesystem;

namespace {

/// The default methods: the method and the one it is compared against.
const std::vector<std::string> kDefaultMethods = {"ts-graphs", "s-graphs-plus"};
/// A seed range longer than this is a typo ("1-10000000"), not a suite.
constexpr std::uint64_t kMaxSeedsPerRange = 10000;
using limits::kMaxPlatformHeight;
/// Scan rates a platform may set (Hz): the slowest real sensors turn once a second, the
/// fastest 40 times (and a sweep shorter than 25 ms sees almost no motion).
constexpr double kMinRateHz = 1.0;
constexpr double kMaxRateHz = 40.0;

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// A string scalar of `node`; an InputError at its line otherwise.
std::string scalar(const YamlMap& m, const YAML::Node& node, const std::string& what) {
  if (!node.IsScalar()) throw input_error(m.file(), node.Mark().line + 1, what + ": expected a string");
  return node.Scalar();
}

/// Characters an id may hold: it names a folder and a word of the plan's shell commands.
std::string id_text(std::string text) {
  for (char& c : text) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
    if (!ok) c = '_';
  }
  return text;
}

std::string where(const YamlMap& m, const YAML::Node& node) {
  return m.file() + ":" + std::to_string(node.Mark().line + 1);
}

/// A path of the suite file: absolute as it is, else from the suite file's folder.
fs::path from_suite(const fs::path& suite_dir, const std::string& path) {
  const fs::path p(path);
  return (p.is_absolute() ? p : suite_dir / p).lexically_normal();
}

std::vector<std::uint64_t> read_seeds(const YamlMap& g) {
  const std::string what = g.key_path("seeds");
  const YAML::Node node = g.raw("seeds");
  const int line = node.Mark().line + 1;
  std::vector<std::uint64_t> seeds;
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      seeds.push_back(g.as<std::uint64_t>(node[i], what + "[" + std::to_string(i) + "]"));
  } else if (node.IsScalar()) {
    static const std::regex range(R"(\s*(\d+)\s*-\s*(\d+)\s*)");
    std::smatch match;
    const std::string text = node.Scalar();
    if (std::regex_match(text, match, range)) {
      const std::uint64_t a = std::stoull(match[1]), b = std::stoull(match[2]);
      if (b < a)
        throw input_error(g.file(), line,
                          what + ": '" + printable(text) + "': the range ends before it starts");
      if (b - a >= kMaxSeedsPerRange)
        throw input_error(
            g.file(), line,
            what + ": '" + printable(text) + "': more than " + std::to_string(kMaxSeedsPerRange) + " seeds");
      for (std::uint64_t s = a; s <= b; ++s) seeds.push_back(s);
    } else {
      seeds.push_back(g.as<std::uint64_t>(node, what));
    }
  }
  if (seeds.empty())
    throw input_error(g.file(), line, what + ": expected a list of seeds or a range \"1-6\"");
  return seeds;
}

std::vector<std::string> read_styles(const YamlMap& g) {
  const std::string what = g.key_path("styles");
  const YAML::Node node = g.raw("styles");
  std::vector<std::pair<std::string, int>> styles;  // name, line
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      styles.emplace_back(scalar(g, node[i], what + "[" + std::to_string(i) + "]"), node[i].Mark().line + 1);
  } else {
    styles.emplace_back(scalar(g, node, what), node.Mark().line + 1);
  }
  if (styles.empty()) throw input_error(g.file(), node.Mark().line + 1, what + ": no style");
  const std::vector<std::string>& known = generator::building_style_names();
  std::vector<std::string> out;
  for (const auto& [style, line] : styles) {
    if (std::find(known.begin(), known.end(), style) == known.end())
      throw input_error(g.file(), line,
                        what + ": unknown style '" + printable(style) + "' (styles: " + join(known) + ")");
    out.push_back(style);
  }
  return out;
}

std::vector<SuitePlatform> read_platforms(const YamlMap& g) {
  if (!g.has("platforms")) return {SuitePlatform{}};
  const std::string what = g.key_path("platforms");
  const YAML::Node node = g.raw("platforms");
  if (!node.IsSequence() || node.size() == 0)
    throw input_error(g.file(), node.Mark().line + 1,
                      what +
                          ": expected a list of platforms (default, or {name, mount_height, preset, type, "
                          "rate_hz, record_hz})");
  std::vector<SuitePlatform> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = what + "[" + std::to_string(i) + "]";
    const YAML::Node n = node[i];
    if (n.IsScalar()) {
      if (n.Scalar() != "default")
        throw input_error(g.file(), n.Mark().line + 1,
                          item + ": '" + printable(n.Scalar()) + "': expected default or a mapping");
      out.push_back(SuitePlatform{});
      continue;
    }
    const YamlMap p(n, g.file(), item);
    p.check_keys({"name", "mount_height", "preset", "type", "rate_hz", "record_hz"});
    SuitePlatform platform;
    platform.name = p.require<std::string>("name");
    if (platform.name.empty() || platform.name == "default" || id_text(platform.name) != platform.name)
      throw p.error("name", "'" + printable(platform.name) +
                                "': expected letters, digits, '-', '_' or '.', not default");
    if (p.has("mount_height")) {
      platform.mount_height = p.require<double>("mount_height");
      if (!(*platform.mount_height > 0.0 && *platform.mount_height <= kMaxPlatformHeight))
        throw p.error("mount_height",
                      "must lie in (0, " + std::to_string(kMaxPlatformHeight).substr(0, 3) + "] m");
    }
    if (p.has("preset")) {
      platform.preset = p.require<std::string>("preset");
      const std::vector<std::string>& presets = scene::preset_names();
      if (std::find(presets.begin(), presets.end(), platform.preset) == presets.end())
        throw p.error("preset",
                      "unknown preset '" + printable(platform.preset) + "' (presets: " + join(presets) + ")");
    }
    if (p.has("type")) {
      platform.type = p.require<std::string>("type");
      if (!scene::platform_type(platform.type))
        throw p.error("type", "unknown platform type '" + printable(platform.type) + "' (" +
                                  join(scene::platform_names()) + ")");
    }
    if (p.has("rate_hz")) {
      platform.rate_hz = p.require<double>("rate_hz");
      if (!(*platform.rate_hz >= kMinRateHz && *platform.rate_hz <= kMaxRateHz))
        throw p.error("rate_hz", "must lie in [1, 40] Hz");
    }
    if (p.has("record_hz")) {
      platform.record_hz = p.require<double>("record_hz");
      if (!(*platform.record_hz >= kMinRateHz && *platform.record_hz <= kMaxRateHz))
        throw p.error("record_hz", "must lie in [1, 40] Hz");
    }
    if (!platform.mount_height && platform.preset.empty() && platform.type.empty() && !platform.rate_hz &&
        !platform.record_hz)
      throw p.error_here("a platform sets mount_height, preset, type, rate_hz or record_hz");
    out.push_back(platform);
  }
  return out;
}

void add_generate_cases(const YamlMap& entry, Suite* suite) {
  const YamlMap g = entry.map("generate");
  g.check_keys({"styles", "seeds", "size", "people", "realistic", "platforms"});
  if (!g.has("styles")) throw g.error_here("missing required key 'styles'");
  if (!g.has("seeds")) throw g.error_here("missing required key 'seeds'");
  const std::vector<std::string> styles = read_styles(g);
  const std::vector<std::uint64_t> seeds = read_seeds(g);
  const double size = g.get<double>("size", 1.0);
  if (!(size > 0.0 && size <= 1.0)) throw g.error("size", "must lie in (0, 1]");
  const int people = g.get<int>("people", 0);
  if (people < 0 || people > generator::kMaxGeneratedPeople)
    throw g.error("people", "must lie in [0, " + std::to_string(generator::kMaxGeneratedPeople) + "]");
  const bool realistic = g.get<bool>("realistic", false);
  const std::vector<SuitePlatform> platforms = read_platforms(g);
  for (const std::string& style : styles) {
    for (const std::uint64_t seed : seeds) {
      for (const SuitePlatform& platform : platforms) {
        SuiteCase c;
        c.kind = "generate";
        c.where = where(g, g.raw("styles"));
        c.style = style;
        c.seed = seed;
        c.size = size;
        c.people = people;
        c.realistic = realistic;
        c.platform = platform;
        c.id = style + "-s" + std::to_string(seed) + (platform.name.empty() ? "" : "-" + platform.name) +
               (realistic ? "-realistic" : "");
        suite->cases.push_back(std::move(c));
      }
    }
  }
}

void add_scene_case(const YamlMap& entry, const fs::path& suite_dir, Suite* suite) {
  const YAML::Node node = entry.raw("scene");
  const std::string what = entry.key_path("scene");
  const std::string arg = scalar(entry, node, what);
  SuiteCase c;
  c.kind = "scene";
  c.where = where(entry, node);
  const fs::path file = from_suite(suite_dir, arg);
  if (fs::is_regular_file(file)) {
    c.source = file.string();
    c.id = "scene-" + id_text(file.stem().string());
  } else if (scene::builtin_scene_text(arg)) {
    c.source = arg;
    c.id = "scene-" + id_text(arg);
  } else {
    throw input_error(entry.file(), node.Mark().line + 1,
                      what + ": '" + printable(arg) + "': no such scene file (built-in scenes: " +
                          join(scene::builtin_scene_names()) + ")");
  }
  (void)scene_of(c);  // a scene file with an error is the suite's bad input
  suite->cases.push_back(std::move(c));
}

void add_import_case(const YamlMap& entry, const fs::path& suite_dir, Suite* suite) {
  const YamlMap m = entry.map("import");
  m.check_keys({"map", "rooms", "ceiling", "name"});
  const auto existing_file = [&](const char* key) {
    const fs::path file = from_suite(suite_dir, m.require<std::string>(key));
    if (!fs::is_regular_file(file))
      throw m.error(key, "'" + printable(file.string(), kMaxQuotedPathBytes) + "': no such file");
    return file.string();
  };
  SuiteCase c;
  c.kind = "import";
  c.where = where(m, m.raw("map").IsDefined() ? m.raw("map") : entry.raw("import"));
  c.source = existing_file("map");
  if (m.has("rooms")) c.rooms = existing_file("rooms");
  c.ceiling = m.get<double>("ceiling", c.ceiling);
  if (!(c.ceiling > 0.0)) throw m.error("ceiling", "must be > 0 m");
  const std::string name = m.get<std::string>("name", fs::path(c.source).stem().string());
  if (name.empty() || id_text(name) != name)
    throw m.error("name", "'" + printable(name) + "': expected letters, digits, '-', '_' or '.'");
  c.id = "import-" + name;
  suite->cases.push_back(std::move(c));
}

void add_sequence_case(const YamlMap& entry, const fs::path& suite_dir, Suite* suite) {
  const YAML::Node node = entry.raw("sequence");
  const std::string what = entry.key_path("sequence");
  const fs::path dir = from_suite(suite_dir, scalar(entry, node, what));
  if (!io::is_sequence_folder(dir.string()))
    throw input_error(entry.file(), node.Mark().line + 1,
                      what + ": '" + printable(dir.string(), kMaxQuotedPathBytes) +
                          "': not a sequence folder (times.txt, odom.txt, scans/)");
  SuiteCase c;
  c.kind = "sequence";
  c.where = where(entry, node);
  c.source = dir.string();
  std::string name = dir.filename().string();
  if (name.empty() || name == ".") name = dir.parent_path().filename().string();
  c.id = "seq-" + id_text(name);
  suite->cases.push_back(std::move(c));
}

}  // namespace

std::vector<std::string> check_methods(const std::vector<std::string>& slugs, const std::string& where) {
  if (slugs.empty()) throw InputError(where + ": no method (methods: " + method_slugs() + ")");
  std::vector<std::string> seen;
  for (const std::string& s : slugs) {
    if (find_method(s) == nullptr)
      throw InputError(where + ": unknown method '" + printable(s) + "' (methods: " + method_slugs() + ")");
    if (std::find(seen.begin(), seen.end(), s) != seen.end())
      throw InputError(where + ": method '" + printable(s) + "' twice");
    seen.push_back(s);
  }
  return seen;
}

Suite load_suite(const std::string& file) {
  const YamlMap root = YamlMap::load_file(file);
  root.check_keys({"name", "methods", "laps", "cases"});
  Suite suite;
  suite.file = fs::absolute(file).lexically_normal().string();
  const fs::path suite_dir = fs::path(suite.file).parent_path();
  suite.name = root.require<std::string>("name");
  if (suite.name.empty()) throw root.error("name", "is empty");
  if (root.has("methods")) {
    const YAML::Node node = root.raw("methods");
    const std::string where = file + ":" + std::to_string(root.line_of("methods")) + ": methods";
    if (!node.IsSequence()) throw InputError(where + ": expected a list of methods (" + method_slugs() + ")");
    std::vector<std::string> slugs;
    for (std::size_t i = 0; i < node.size(); ++i)
      slugs.push_back(scalar(root, node[i], "methods[" + std::to_string(i) + "]"));
    suite.methods = check_methods(slugs, where);
  } else {
    suite.methods = kDefaultMethods;
  }
  suite.laps = root.get<int>("laps", 0);
  if (root.has("laps") && (suite.laps < 1 || suite.laps > limits::kMaxLaps))
    throw root.error("laps", "must be in [1, " + std::to_string(limits::kMaxLaps) + "]");

  if (!root.has("cases")) throw root.error_here("missing required key 'cases'");
  const std::vector<YamlMap> entries = root.maps("cases");
  if (entries.empty()) throw root.error("cases", "no case");
  std::map<std::string, std::string> first_of;  // case id -> where it comes from
  for (const YamlMap& entry : entries) {
    entry.check_keys({"generate", "import", "scene", "sequence"});
    const int kinds = int(entry.has("generate")) + int(entry.has("import")) + int(entry.has("scene")) +
                      int(entry.has("sequence"));
    if (kinds != 1) throw entry.error_here("give one of generate, import, scene or sequence");
    const std::size_t first = suite.cases.size();
    if (entry.has("generate")) add_generate_cases(entry, &suite);
    if (entry.has("import")) add_import_case(entry, suite_dir, &suite);
    if (entry.has("scene")) add_scene_case(entry, suite_dir, &suite);
    if (entry.has("sequence")) add_sequence_case(entry, suite_dir, &suite);
    // The entry's cases are one group of the tables (docs/suite.md, "The tables").
    for (std::size_t i = first; i < suite.cases.size(); ++i) {
      SuiteCase& c = suite.cases[i];
      c.group = entry.path() + ": " + c.kind + (c.realistic ? ", realistic" : "");
    }
    // Ids name folders: two cases of one id would share (and overwrite) one.
    for (std::size_t i = first; i < suite.cases.size(); ++i) {
      const SuiteCase& c = suite.cases[i];
      if (const auto [it, fresh] = first_of.emplace(c.id, c.where); !fresh)
        throw InputError(c.where + ": " + entry.path() + ": case '" + c.id + "' again (first from " +
                         it->second + ")");
    }
  }
  return suite;
}

scene::Scene scene_of(const SuiteCase& c) {
  if (fs::path(c.source).is_absolute()) return scene::load_scene(c.source);
  const std::optional<std::string> text = scene::builtin_scene_text(c.source);
  if (!text) throw InputError(c.where + ": no built-in scene '" + c.source + "'");
  return scene::parse_scene(*text, "builtin:" + c.source, ".");
}

const SuiteCase& find_case(const Suite& suite, const std::string& id) {
  for (const SuiteCase& c : suite.cases)
    if (c.id == id) return c;
  throw InputError(suite.file + ": no case '" + id + "' in the suite");
}

}  // namespace tsgraphs::app
