// The suite page (report/suite_report.hpp) on hand-made cases: the tables, then each case's
// bird's-eyes side by side, worst first, captioned with its figures; self-contained.
#include <gtest/gtest.h>

#include <string>

#include "tsgraphs/report/suite_report.hpp"

using namespace tsgraphs;

namespace {

eval::CaseRecord done_case(const std::string& id, double f1) {
  eval::CaseRecord c;
  c.id = id;
  c.kind = "generate";
  c.status = eval::kCaseDone;
  c.info = {{"style", "office"},
            {"seed", "3"},
            {"platform", "handheld"},
            {"preset", "vlp-16"},
            {"mount_height", "1.50"}};
  for (const auto& [slug, name] :
       {std::pair{"ts-graphs", "TS-graphs"}, std::pair{"s-graphs-plus", "S-Graphs+"}}) {
    eval::CaseMethod m;
    m.method = {slug, name};
    m.figures = {{"rooms_gt.f1", f1},
                 {"rooms_gt.recall", 1.0},
                 {"consistency.f_re", 0.5},
                 {"rooms_gt.unsupported", 2.0}};
    c.methods.push_back(m);
  }
  return c;
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + what.size())) ++n;
  return n;
}

}  // namespace

TEST(SuiteReport, CasesWorstFirstWithEveryRunSideBySide) {
  eval::SuiteResults r;
  r.name = "a <b> & c";
  r.methods = {{"ts-graphs", "TS-graphs"}, {"s-graphs-plus", "S-Graphs+"}};
  eval::CaseRecord failed;
  failed.id = "broken";
  failed.kind = "scene";
  failed.status = eval::kCaseFailed;
  failed.message = "x.yaml:2: <bad>";
  r.cases = {done_case("good", 0.9), failed, done_case("bad", 0.2)};
  const std::string html =
      report::suite_report_html(r, [](const eval::CaseRecord& c, const std::string& slug) {
        if (c.id == "good" && slug == "s-graphs-plus")
          return std::string();  // a run folder without a picture
        return "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"tsg-birdseye\"><g "
               "data-run=\"" +
               c.id + "/" + slug + "\"/></svg>";
      });
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(count(html, "<script"), 0u);
  EXPECT_EQ(count(html, "<?xml"), 0u) << "inline SVG without its declaration";
  EXPECT_NE(html.find("<title>tsgraphs suite: a &lt;b&gt; &amp; c</title>"), std::string::npos);
  EXPECT_EQ(count(html, "<table class=\"suite\">"), 2u);
  EXPECT_NE(html.find("3 cases: 2 counted, 1 failed, 0 not run yet"), std::string::npos);
  // Failed first, then by TS-graphs' rooms F1.
  const std::size_t broken = html.find("<h3>broken</h3>"), bad = html.find("<h3>bad</h3>"),
                    good = html.find("<h3>good</h3>");
  ASSERT_NE(broken, std::string::npos);
  EXPECT_LT(broken, bad);
  EXPECT_LT(bad, good);
  EXPECT_NE(html.find("failed: x.yaml:2: &lt;bad&gt;"), std::string::npos);
  EXPECT_EQ(count(html, "class=\"tsg-birdseye\""), 3u);
  EXPECT_NE(html.find("data-run=\"bad/s-graphs-plus\""), std::string::npos);
  EXPECT_NE(html.find("no bird's-eye in the run folder"), std::string::npos);
  EXPECT_NE(html.find("<figcaption>bad, TS-graphs: rooms F1 0.20, f_re 0.50, DCS -, d_center - m, "
                      "unsupported 2, ATE - m"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("office, seed 3, platform handheld, vlp-16 at 1.50 m"), std::string::npos);
}
