// `tsgraphs demo` end to end on a small two-room scene with one seed (the built-in scenes take
// minutes: their figures are in docs/benchmarks.md), and `tsgraphs eval --against`.
// ctest: slow (seconds a test: simulated runs or generated buildings)
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

using tsgraphs::test::read_file;

/// Runs the tsgraphs binary; stdout and stderr into `out` and `err`; returns the exit status.
int cli(const std::string& args, std::string* out, std::string* err) {
  return tsgraphs::test::run_tsgraphs(args, out, err);
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(text);
  while (std::getline(in, field, sep)) out.push_back(field);
  if (!text.empty() && text.back() == sep) out.emplace_back();
  return out;
}

const char* const kMethods[] = {"ts-graphs", "s-graphs-plus", "traversable-timer", "esdf-flush"};

/// The table has every column filled for every method.
void check_table(const fs::path& demo) {
  const std::string csv = read_file(demo / "table.csv");
  std::vector<std::string> lines = split(csv, '\n');
  ASSERT_FALSE(lines.empty());
  if (lines.back().empty()) lines.pop_back();
  ASSERT_EQ(lines.size(), 5u) << csv;  // the header and four methods
  const std::vector<std::string> header = split(lines[0], ',');
  constexpr std::size_t kColumns =
      3 + 2 * (8 + 9);  // scene, method, seeds; mean and sd of Table 1 and the rest
  ASSERT_EQ(header.size(), kColumns);
  for (std::size_t row = 1; row < lines.size(); ++row) {
    const std::vector<std::string> cells = split(lines[row], ',');
    ASSERT_EQ(cells.size(), kColumns) << lines[row];
    std::map<std::string, std::string> cell;
    for (std::size_t c = 0; c < kColumns; ++c) cell[header[c]] = cells[c];
    EXPECT_EQ(cell["scene"], "two_rooms");
    EXPECT_EQ(cell["seeds"], "1");
    for (std::size_t c = 3; c < kColumns; ++c) {
      const std::string& key = header[c];
      if (key.size() > 3 && key.compare(key.size() - 3, 3, "_sd") == 0) {
        EXPECT_EQ(cells[c], "") << key << ": no spread over one seed";
        continue;
      }
      // DCS and d_center are means over the paired rooms: none without a pair.
      const bool over_pairs = key == "dcs_mean" || key == "d_center_mean";
      if (over_pairs && std::stod(cell["N_re_mean"]) == 0.0) continue;
      ASSERT_FALSE(cells[c].empty()) << cell["method"] << ": " << key;
      EXPECT_NO_THROW((void)std::stod(cells[c])) << key;
    }
  }
  // TS-graphs finds the three rooms again in the second lap, and they are the true ones.
  const std::vector<std::string> ts = split(lines[1], ',');
  std::map<std::string, double> v;
  for (std::size_t c = 3; c < kColumns; ++c)
    if (!ts[c].empty()) v[header[c]] = std::stod(ts[c]);
  EXPECT_EQ(ts[1], "TS-graphs");
  EXPECT_EQ(v["N_re_mean"], 3.0);
  EXPECT_GE(v["f_re_mean"], 0.99);
  EXPECT_GE(v["rooms_f1_mean"], 0.99);
}

/// The tables, the runs and the platform comparison are written, and stdout is the table.
void check_files(const fs::path& demo, const std::string& printed) {
  const std::string md = read_file(demo / "table.md");
  EXPECT_EQ(printed, md);  // the demo prints what it writes
  for (const char* method : {"| TS-graphs |", "| S-Graphs+ |", "| ablation: traversable + timer |",
                             "| ablation: esdf + flush |"}) {
    std::size_t count = 0;
    for (std::size_t at = md.find(method); at != std::string::npos; at = md.find(method, at + 1)) ++count;
    EXPECT_EQ(count, 2u) << method << " in both tables";
  }
  EXPECT_NE(md.find("the sensor at 0.55 m against 1.00 m"), std::string::npos) << md;
  for (const char* method : kMethods) {
    const fs::path run = demo / (std::string("two_rooms_seed1_") + method);
    const auto metrics = nlohmann::json::parse(read_file(run / "metrics.json"));
    EXPECT_TRUE(metrics["trajectory"]["ate_rmse"].is_number()) << method;
  }
  // The page: both tables, and a bird's-eye of each method's seed-1 run captioned with its name.
  const std::string page = read_file(demo / "report.html");
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(page.find("<script"), std::string::npos);
  std::size_t tables = 0;
  for (std::size_t at = page.find("<table class=\"metrics\">"); at != std::string::npos;
       at = page.find("<table class=\"metrics\">", at + 1))
    ++tables;
  EXPECT_EQ(tables, 2u);
  for (const char* name :
       {"TS-graphs", "S-Graphs+", "ablation: traversable + timer", "ablation: esdf + flush"})
    EXPECT_NE(page.find("<figcaption>" + std::string(name)), std::string::npos) << name;
  // Every run has its own report and bird's-eye.
  EXPECT_TRUE(fs::exists(demo / "two_rooms_seed1_ts-graphs" / "report.html"));
  EXPECT_NE(read_file(demo / "two_rooms_seed1_ts-graphs" / "birdseye.svg").find("class=\"room\""),
            std::string::npos);

  const auto comparison =
      nlohmann::json::parse(read_file(demo / "two_rooms_seed1_ts-graphs" / "comparison.json"));
  EXPECT_EQ(comparison["N_a"], 3);
  EXPECT_GE(comparison["N_re"].get<int>(), 2);  // the same rooms from a sensor 0.45 m higher
  EXPECT_GE(comparison["dcs"].get<double>(), 0.9);
}

/// `eval --against` pairs the rooms of two runs; bad input is one clear error.
void check_against(const fs::path& demo, const fs::path& scratch) {
  const std::string a = (demo / "two_rooms_seed1_ts-graphs").string();
  std::string out, err;
  ASSERT_EQ(cli("-q eval " + a + " --against " + a, &out, &err), 0) << err;
  const auto same = nlohmann::json::parse(read_file(fs::path(a) / "comparison.json"));
  EXPECT_EQ(same["N_a"], same["N_b"]);
  EXPECT_EQ(same["N_re"], same["N_a"]);
  EXPECT_DOUBLE_EQ(same["f_re"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(same["d_center"].get<double>(), 0.0);
  EXPECT_NE(out.find("f_re 1.00"), std::string::npos) << out;

  // A missing run is one clear error, exit status 2; --against and --seq do not go together.
  const std::string missing = (scratch / "no_such_run").string();
  EXPECT_EQ(cli("-q eval " + a + " --against " + missing, &out, &err), 2);
  EXPECT_NE(err.find(missing), std::string::npos) << err;
  EXPECT_EQ(cli("-q eval " + a + " --against " + a + " --seq " + a, &out, &err), 2);
}

}  // namespace

// One demo run (simulate, four methods, a second platform: about 30 s), then its outputs.
TEST(DemoCli, OneSeedOnASmallSceneEndToEnd) {
  const fs::path dir = tsgraphs::test::fresh_temp_dir("demo");
  const std::string scene = std::string(TSGRAPHS_TEST_DATA_DIR) + "/scenes/two_rooms.yaml";
  std::string out, err;
  ASSERT_EQ(cli("-q demo --out " + (dir / "demo").string() + " --seeds 1 --scenes " + scene +
                    " --platform-height 1.0",
                &out, &err),
            0)
      << err;
  {
    SCOPED_TRACE("table");
    check_table(dir / "demo");
  }
  {
    SCOPED_TRACE("files");
    check_files(dir / "demo", out);
  }
  {
    SCOPED_TRACE("eval --against");
    check_against(dir / "demo", dir);
  }
  fs::remove_all(dir);
}
