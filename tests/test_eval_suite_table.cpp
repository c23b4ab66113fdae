// The suite's figures over its cases (eval/suite_table.hpp) and the suite folder's files
// (eval/suite_folder.hpp), on hand-made numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "tsgraphs/eval/metrics.hpp"
#include "tsgraphs/eval/suite_folder.hpp"
#include "tsgraphs/eval/suite_table.hpp"

using namespace tsgraphs;
using namespace tsgraphs::eval;

namespace {

const SuiteFigure& figure(const std::string& key) {
  for (const SuiteFigure& f : suite_figures())
    if (f.key == key) return f;
  ADD_FAILURE() << "no figure " << key;
  return suite_figures().front();
}

std::size_t index_of(const std::string& key) {
  for (std::size_t i = 0; i < suite_figures().size(); ++i)
    if (suite_figures()[i].key == key) return i;
  ADD_FAILURE() << "no figure " << key;
  return 0;
}

CaseMethod run(const std::string& slug, const std::string& name, std::map<std::string, Figure> figures) {
  CaseMethod m;
  m.method = {slug, name};
  m.wall_s = 10.0;
  m.figures = std::move(figures);
  return m;
}

CaseRecord done_case(const std::string& id, double ts_f1, double ts_f_re, double sg_f1) {
  CaseRecord c;
  c.id = id;
  c.kind = "generate";
  c.spec = "generate style=office seed=1";
  c.status = kCaseDone;
  c.wall_s = 42.0;
  c.info = {{"style", "office"}, {"seed", "1"}};
  c.methods.push_back(run("ts-graphs", "TS-graphs",
                          {{"rooms_gt.f1", ts_f1},
                           {"rooms_gt.recall", 1.0},
                           {"consistency.f_re", ts_f_re},
                           {"consistency.dcs", 0.9},
                           {"consistency.d_center", 0.2}}));
  c.methods.push_back(run("s-graphs-plus", "S-Graphs+", {{"rooms_gt.f1", sg_f1}, {"rooms_gt.recall", 1.0}}));
  return c;
}

CaseRecord failed_case(const std::string& id) {
  CaseRecord c;
  c.id = id;
  c.kind = "scene";
  c.status = kCaseFailed;
  c.message = "x.yaml:3: walls[0]: bad, \"quoted\"";
  return c;
}

SuiteResults three_cases() {
  SuiteResults r;
  r.name = "hand-made";
  r.methods = {{"ts-graphs", "TS-graphs"}, {"s-graphs-plus", "S-Graphs+"}};
  r.cases = {done_case("a", 0.9, 1.0, 0.5), failed_case("b"), done_case("c", 0.4, 0.5, 0.7),
             done_case("d", 0.9, 0.8, 0.6)};
  r.pending = {"e"};
  return r;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + what.size())) ++n;
  return n;
}

}  // namespace

TEST(SuiteTable, PercentileInterpolatesBetweenRanks) {
  // Type 7: rank p/100 (n-1) over the sorted values.
  EXPECT_DOUBLE_EQ(percentile({3.0, 1.0, 2.0, 4.0, 5.0}, 50), 3.0);
  EXPECT_DOUBLE_EQ(percentile({1.0, 2.0, 3.0, 4.0}, 50), 2.5);
  EXPECT_DOUBLE_EQ(percentile({1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0}, 10), 2.0);
  EXPECT_NEAR(percentile({0.0, 10.0}, 90), 9.0, 1e-12);
  EXPECT_DOUBLE_EQ(percentile({7.0}, 10), 7.0);
  EXPECT_DOUBLE_EQ(percentile({5.0, 1.0}, 0), 1.0);
  EXPECT_DOUBLE_EQ(percentile({5.0, 1.0}, 100), 5.0);
  EXPECT_THROW((void)percentile({}, 50), std::invalid_argument);
}

TEST(SuiteTable, WorstDecileIsTheBadTail) {
  const std::vector<double> v = {0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0};
  EXPECT_DOUBLE_EQ(worst_decile(v, Better::kHigher), 1.0);  // the 10th percentile
  EXPECT_DOUBLE_EQ(worst_decile(v, Better::kLower), 9.0);   // the 90th
  EXPECT_EQ(worst_decile_percentile(Better::kHigher), 10);
  EXPECT_EQ(worst_decile_percentile(Better::kLower), 90);
  EXPECT_EQ(better_text(Better::kHigher), "higher (p10)");
  EXPECT_EQ(better_text(Better::kLower), "lower (p90)");
}

TEST(SuiteTable, FiguresHaveTheirDirections) {
  for (const char* key :
       {"consistency.f_re", "consistency.dcs", "rooms_gt.precision", "rooms_gt.recall", "rooms_gt.f1",
        "rooms_gt.mean_iou", "rooms_gt.ipa_precision_micro", "rooms_gt.ipa_recall_micro",
        "rooms_gt.ipa_precision_macro", "rooms_gt.ipa_recall_macro", "speed.rtf"})
    EXPECT_EQ(figure(key).better, Better::kHigher) << key;
  for (const char* key : {"consistency.d_center", "rooms_gt.under_segmented", "rooms_gt.over_segmented",
                          "rooms_gt.unsupported", "trajectory.ate_rmse", "pgo.t_pgo_s"})
    EXPECT_EQ(figure(key).better, Better::kLower) << key;
  EXPECT_EQ(suite_figures().size(), 17u);
  // Every figure is a key of metrics.json.
  for (const SuiteFigure& f : suite_figures())
    EXPECT_NE(std::find(metrics_keys().begin(), metrics_keys().end(), f.key), metrics_keys().end()) << f.key;
}

TEST(SuiteTable, StatsTakeTheWorstByDirectionAndItsFirstCase) {
  const std::vector<std::pair<std::string, double>> v = {{"a", 0.5}, {"b", 0.2}, {"c", 0.9}, {"d", 0.2}};
  const FigureStats hi = figure_stats(v, Better::kHigher);
  EXPECT_EQ(hi.n, 4);
  EXPECT_DOUBLE_EQ(*hi.median, 0.35);
  EXPECT_DOUBLE_EQ(*hi.worst, 0.2);
  EXPECT_EQ(hi.worst_case, "b");  // the first of the two at 0.2
  EXPECT_NEAR(*hi.worst_decile, 0.2, 1e-12);
  const FigureStats lo = figure_stats(v, Better::kLower);
  EXPECT_DOUBLE_EQ(*lo.worst, 0.9);
  EXPECT_EQ(lo.worst_case, "c");
  EXPECT_NEAR(*lo.worst_decile, 0.5 + 0.7 * 0.4, 1e-12);  // rank 2.7 between 0.5 and 0.9
  const FigureStats none = figure_stats({}, Better::kHigher);
  EXPECT_EQ(none.n, 0);
  EXPECT_FALSE(none.median);
  EXPECT_FALSE(none.worst);
  EXPECT_TRUE(none.worst_case.empty());
}

TEST(SuiteTable, MissingFiguresAreLeftOutAndCounted) {
  SuiteResults r = three_cases();
  // Case d's TS-graphs run paired no room: no DCS; and it has no final room: F1 null, recall 0.
  CaseMethod& d = r.cases[3].methods[0];
  d.figures["consistency.dcs"] = std::nullopt;
  d.figures["rooms_gt.f1"] = std::nullopt;
  d.figures["rooms_gt.recall"] = 0.0;
  const std::vector<MethodSummary> s = summarise(r);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].method.slug, "ts-graphs");
  EXPECT_EQ(s[0].counted, 3);
  EXPECT_EQ(s[0].failed, 1);
  const FigureStats& dcs = s[0].stats[index_of("consistency.dcs")];
  EXPECT_EQ(dcs.n, 2);  // left out
  // F1 without a final room counts as 0 (recall is known), so it is the worst case.
  const FigureStats& f1 = s[0].stats[index_of("rooms_gt.f1")];
  EXPECT_EQ(f1.n, 3);
  EXPECT_DOUBLE_EQ(*f1.worst, 0.0);
  EXPECT_EQ(f1.worst_case, "d");
  EXPECT_DOUBLE_EQ(*f1.median, 0.4);
  // A figure no case has: no statistics, n 0 (ATE is not in the hand-made runs).
  const FigureStats& ate = s[0].stats[index_of("trajectory.ate_rmse")];
  EXPECT_EQ(ate.n, 0);
  EXPECT_FALSE(ate.median);
  // Without recall there is no rule to apply: F1 stays missing.
  CaseMethod bare = run("x", "X", {});
  EXPECT_FALSE(suite_value(bare, figure("rooms_gt.f1")));
  EXPECT_EQ(case_figure_text(bare, "rooms_gt.f1"), "-");
}

TEST(SuiteTable, WorstFirstPutsFailuresThenLowF1ThenLowFre) {
  SuiteResults r = three_cases();
  r.cases.push_back(done_case("f", 0.4, 0.2, 0.9));  // as low an F1 as c, a lower f_re; d before a likewise
  std::vector<std::string> order;
  for (const CaseRecord* c : worst_first(r)) order.push_back(c->id);
  EXPECT_EQ(order, (std::vector<std::string>{"b", "f", "c", "d", "a"}));
  EXPECT_EQ(key_method(r), "ts-graphs");
  r.methods = {{"s-graphs-plus", "S-Graphs+"}};
  EXPECT_EQ(key_method(r), "s-graphs-plus");
}

TEST(SuiteTable, CaseLineHasTheKeyFigures) {
  const SuiteResults r = three_cases();
  EXPECT_EQ(case_line(r.cases[0], r),
            "a: TS-graphs F1 0.90, f_re 1.00, DCS 0.90, d_center 0.20 m; S-Graphs+ F1 0.50; 42 s");
  EXPECT_EQ(case_line(r.cases[1], r), "b: failed: x.yaml:3: walls[0]: bad, \"quoted\"");
}

TEST(SuiteTable, CsvHasARowPerCaseAndMethodWithEveryFigure) {
  const SuiteResults r = three_cases();
  const std::vector<std::string> lines = lines_of(suite_csv(r));
  // Header, then 3 done cases x 2 methods and the failed case once per method; pending cases none.
  ASSERT_EQ(lines.size(), 1u + 4 * 2);
  const std::string& header = lines[0];
  EXPECT_EQ(header.rfind("case,status,message,kind,source,style,seed,", 0), 0u) << header;
  for (const std::string& key : metrics_keys()) EXPECT_NE(header.find("," + key), std::string::npos) << key;
  EXPECT_EQ(count(header, ","), 4 + case_info_keys().size() + 2 + metrics_keys().size() - 1);
  EXPECT_EQ(lines[1].rfind("a,done,,generate,,office,1,", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find(",TS-graphs,10,"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find(",S-Graphs+,10,"), std::string::npos) << lines[2];
  // The failed case's message is quoted (a comma and quotes in it), its figures empty.
  EXPECT_EQ(lines[3].rfind("b,failed,\"x.yaml:3: walls[0]: bad, \"\"quoted\"\"\",scene,", 0), 0u) << lines[3];
}

TEST(SuiteTable, TpgoRatiosAndLoopTotalsPerMethod) {
  SuiteResults r = three_cases();
  // a: 0.2 s against 1.0 s; c: 0.6 against 1.0; d: S-Graphs+ has no T_PGO.
  r.cases[0].methods[0].figures["pgo.t_pgo_s"] = 0.2;
  r.cases[0].methods[1].figures["pgo.t_pgo_s"] = 1.0;
  r.cases[2].methods[0].figures["pgo.t_pgo_s"] = 0.6;
  r.cases[2].methods[1].figures["pgo.t_pgo_s"] = 1.0;
  r.cases[3].methods[0].figures["pgo.t_pgo_s"] = 0.6;
  const auto ratios = pgo_ratios(r, "s-graphs-plus");
  ASSERT_EQ(ratios.size(), 2u);
  EXPECT_EQ(ratios[0].first, "a");
  EXPECT_DOUBLE_EQ(ratios[0].second, 0.2);
  EXPECT_DOUBLE_EQ(ratios[1].second, 0.6);
  r.cases[0].methods[0].figures.insert({{"loops.n_loops", 5.0},
                                        {"loops.n_loops_correct", 4.0},
                                        {"loops.n_loops_room", 2.0},
                                        {"loops.n_loops_room_correct", 2.0}});
  r.cases[2].methods[0].figures.insert({{"loops.n_loops", 3.0}, {"loops.n_loops_correct", 3.0}});
  const LoopTotals t = loop_totals(r, "ts-graphs");
  EXPECT_EQ(t.cases, 2);
  EXPECT_EQ(t.found, 8.0);
  EXPECT_EQ(t.correct, 7.0);
  EXPECT_EQ(t.room_found, 2.0);
  EXPECT_EQ(t.room_correct, 2.0);
  const std::string md = suite_markdown(r);
  EXPECT_NE(md.find("## T_PGO against TS-graphs"), std::string::npos) << md;
  EXPECT_NE(md.find("| S-Graphs+ | 0.40 | 0.56 | 0.60 | c | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| TS-graphs | 8 | 7 | 2 | 2 | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find(" T_PGO TS-graphs / S-Graphs+ |"), std::string::npos) << md;
  EXPECT_NE(md.find("| a | done | 0.90 | 1.00 | 0.90 | 0.20 | 0.50 | 0.20 |"), std::string::npos) << md;
}

TEST(SuiteTable, MarkdownHasEveryTable) {
  const std::string md = suite_markdown(three_cases());
  EXPECT_NE(md.find("# Suite hand-made"), std::string::npos);
  EXPECT_NE(md.find("5 cases: 3 counted, 1 failed, 1 not run yet"), std::string::npos) << md;
  EXPECT_NE(md.find("## TS-graphs"), std::string::npos);
  EXPECT_NE(md.find("## S-Graphs+"), std::string::npos);
  for (const SuiteFigure& f : suite_figures()) EXPECT_EQ(count(md, "| " + f.header + " | "), 2u) << f.header;
  EXPECT_NE(md.find("| rooms F1 | higher (p10) | 0.90 | 0.50 | 0.40 | c | 3 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| d_center (m) | lower (p90) | 0.20 | 0.20 | 0.20 | a | 3 |"), std::string::npos) << md;
  // The cases, worst first, and the failed and pending ones by name.
  const std::size_t cases = md.find("## Cases, worst first");
  ASSERT_NE(cases, std::string::npos);
  EXPECT_LT(md.find("| b | failed |", cases), md.find("| c | done |", cases));
  EXPECT_LT(md.find("| c | done |", cases), md.find("| a | done |", cases));
  EXPECT_NE(md.find("- `b`: x.yaml:3"), std::string::npos);
  EXPECT_NE(md.find("- `e`"), std::string::npos);
}

// Two case groups (a suite file's two entries): each gets its own tables, over its cases alone.
TEST(SuiteTable, EachCaseGroupHasItsOwnTables) {
  SuiteResults r = three_cases();
  r.groups = {{"cases[0]: generate", {"a", "b", "c"}}, {"cases[1]: generate, realistic", {"d", "e"}}};
  const SuiteResults first = group_results(r, r.groups[0]);
  ASSERT_EQ(first.cases.size(), 3u);
  EXPECT_TRUE(first.pending.empty());
  EXPECT_EQ(group_results(r, r.groups[1]).pending, std::vector<std::string>{"e"});
  const std::string md = suite_markdown(r);
  const std::size_t groups = md.find("## Case groups");
  ASSERT_NE(groups, std::string::npos) << md;
  const std::size_t g0 = md.find("### cases[0]: generate", groups),
                    g1 = md.find("### cases[1]: generate, realistic", groups);
  ASSERT_NE(g0, std::string::npos);
  ASSERT_NE(g1, std::string::npos);
  EXPECT_NE(md.find("3 cases: 3 with a record, 0 not run yet", g0), std::string::npos) << md;
  // rooms F1 of TS-graphs over a and c alone (b failed): median 0.65, worst 0.40 in c; over d alone 0.90.
  EXPECT_NE(md.find("| rooms F1 | higher (p10) | 0.65 | 0.45 | 0.40 | c | 2 |", g0), std::string::npos) << md;
  EXPECT_NE(md.find("| rooms F1 | higher (p10) | 0.90 | 0.90 | 0.90 | d | 1 |", g1), std::string::npos) << md;
  // One group: no group tables (they would repeat the suite's).
  r.groups.resize(1);
  EXPECT_EQ(suite_markdown(r).find("## Case groups"), std::string::npos);
}

TEST(SuiteFolder, CaseRecordReadsBackWhatWasWritten) {
  CaseRecord c = done_case("office-s3", 0.75, 0.5, 0.25);
  c.methods[0].figures["a_newer.figure"] = 3.0;
  const std::string text = case_record_json(c);
  const CaseRecord back = parse_case_record(text, "case.json");
  EXPECT_EQ(back.id, "office-s3");
  EXPECT_EQ(back.spec, c.spec);
  EXPECT_TRUE(back.done());
  EXPECT_EQ(back.info, c.info);
  ASSERT_EQ(back.methods.size(), 2u);
  EXPECT_EQ(back.methods[1].method.name, "S-Graphs+");
  EXPECT_DOUBLE_EQ(*back.methods[0].figure("rooms_gt.f1"), 0.75);
  EXPECT_DOUBLE_EQ(*back.methods[0].figure("a_newer.figure"), 3.0);
  // Every metrics.json key is written, null where the run has no figure.
  EXPECT_FALSE(back.methods[0].figure("trajectory.ate_rmse"));
  EXPECT_NE(text.find("\"trajectory.ate_rmse\": null"), std::string::npos);
  EXPECT_EQ(case_record_json(back), text);
  const CaseRecord failed = parse_case_record(case_record_json(failed_case("b")), "case.json");
  EXPECT_FALSE(failed.done());
  EXPECT_EQ(failed.message, "x.yaml:3: walls[0]: bad, \"quoted\"");
}

TEST(SuiteFolder, MalformedRecordsNameTheFileAndKey) {
  EXPECT_NE(test::input_error_of([] { parse_case_record("{", "c/case.json"); }).find("c/case.json"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] {
              parse_case_record(R"({"id": "a", "kind": "scene"})", "c/case.json");
            }).find("c/case.json: status"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] {
              parse_case_record(R"({"id": "a", "kind": "scene", "status": "half"})", "c/case.json");
            }).find("expected done or failed"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { read_case_record("/no/such/case.json"); }).find("/no/such/case.json"),
            std::string::npos);
}

TEST(SuiteFolder, IndexReadsBack) {
  const SuiteIndex index{"smoke",
                         "/x/smoke.yaml",
                         {{"ts-graphs", "TS-graphs"}},
                         {"office-s1", "atrium-s1", "office-s1-realistic"},
                         {{"cases[0]: generate", {"office-s1", "atrium-s1"}},
                          {"cases[1]: generate, realistic", {"office-s1-realistic"}}}};
  const std::filesystem::path dir = test::fresh_temp_dir();
  const std::string file = (dir / "suite.json").string();
  std::ofstream(file) << suite_index_json(index);
  const SuiteIndex back = read_suite_index(file);
  EXPECT_EQ(back.name, "smoke");
  EXPECT_EQ(back.suite_file, "/x/smoke.yaml");
  ASSERT_EQ(back.methods.size(), 1u);
  EXPECT_EQ(back.methods[0].name, "TS-graphs");
  EXPECT_EQ(back.case_ids, index.case_ids);
  ASSERT_EQ(back.groups.size(), 2u);
  EXPECT_EQ(back.groups[1].name, "cases[1]: generate, realistic");
  EXPECT_EQ(back.groups[1].case_ids, std::vector<std::string>{"office-s1-realistic"});
  // A folder written before groups existed reads with none.
  std::ofstream(file) << R"({"name": "old", "methods": [], "cases": ["a"]})";
  EXPECT_TRUE(read_suite_index(file).groups.empty());
  std::filesystem::remove_all(dir);
}

TEST(SuiteFolder, MetricsFlattenToGroupDotKey) {
  Metrics m;
  m.rooms_gt.f1 = 0.5;
  m.consistency.f_re = 1.0;
  const std::map<std::string, Figure> f = flatten_metrics_json(metrics_json(m), "metrics.json");
  EXPECT_EQ(f.size(), metrics_keys().size());
  EXPECT_DOUBLE_EQ(*f.at("rooms_gt.f1"), 0.5);
  EXPECT_DOUBLE_EQ(*f.at("consistency.f_re"), 1.0);
  EXPECT_FALSE(f.at("consistency.dcs"));
  EXPECT_EQ(metrics_keys().front(), "consistency.N1st");
  EXPECT_NE(std::find(metrics_keys().begin(), metrics_keys().end(), "rooms_gt.ipa_recall_macro"),
            metrics_keys().end());
  EXPECT_NE(
      test::input_error_of([] { flatten_metrics_json("[1, 2", "r/metrics.json"); }).find("r/metrics.json"),
      std::string::npos);
}
