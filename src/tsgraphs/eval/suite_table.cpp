#include "tsgraphs/eval/suite_table.hpp"

#include "tsgraphs/eval/table_text.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace tsgraphs::eval {
namespace {

/// A CSV number: enough digits to read back what metrics.json holds.
std::string csv_number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.10g", v);
  return buf;
}

/// A markdown cell: pipes escaped, line breaks flattened.
std::string md_cell(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n' || c == '\r')
      out += ' ';
    else
      out += c;
  }
  return out;
}

const SuiteFigure& figure_by_key(const std::string& key) {
  for (const SuiteFigure& f : suite_figures())
    if (f.key == key) return f;
  throw std::logic_error("no suite figure " + key);
}

/// Is `a` worse than `b`?
bool worse(double a, double b, Better better) { return better == Better::kHigher ? a < b : a > b; }

}  // namespace

const std::vector<SuiteFigure>& suite_figures() {
  static const std::vector<SuiteFigure> figures = {
      {"consistency.f_re", "f_re", Better::kHigher, 2, ""},
      {"consistency.dcs", "DCS", Better::kHigher, 2, ""},
      {"consistency.d_center", "d_center (m)", Better::kLower, 2, ""},
      {"rooms_gt.precision", "rooms P", Better::kHigher, 2, ""},
      {"rooms_gt.recall", "rooms R", Better::kHigher, 2, ""},
      {"rooms_gt.f1", "rooms F1", Better::kHigher, 2, "rooms_gt.recall"},
      {"rooms_gt.mean_iou", "mean IoU", Better::kHigher, 2, ""},
      {"rooms_gt.under_segmented", "under-segmented", Better::kLower, 1, "", true},
      {"rooms_gt.over_segmented", "over-segmented", Better::kLower, 1, "", true},
      {"rooms_gt.unsupported", "unsupported rooms", Better::kLower, 1, "", true},
      {"rooms_gt.ipa_precision_micro", "IPA P micro", Better::kHigher, 2, ""},
      {"rooms_gt.ipa_recall_micro", "IPA R micro", Better::kHigher, 2, ""},
      {"rooms_gt.ipa_precision_macro", "IPA P macro", Better::kHigher, 2, ""},
      {"rooms_gt.ipa_recall_macro", "IPA R macro", Better::kHigher, 2, ""},
      {"trajectory.ate_rmse", "ATE_rmse (m)", Better::kLower, 3, ""},
      {"pgo.t_pgo_s", "T_PGO (s)", Better::kLower, 3, ""},
      {"speed.rtf", "RTF", Better::kHigher, 1, ""},
  };
  return figures;
}

Figure suite_value(const CaseMethod& run, const SuiteFigure& figure) {
  if (const Figure f = run.figure(figure.key)) return f;
  if (!figure.zero_when_null_with.empty() && run.figure(figure.zero_when_null_with)) return 0.0;
  return std::nullopt;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) throw std::invalid_argument("percentile of no values");
  std::sort(values.begin(), values.end());
  const double rank = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (rank - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

int worst_decile_percentile(Better better) { return better == Better::kHigher ? 10 : 90; }

double worst_decile(const std::vector<double>& values, Better better) {
  return percentile(values, worst_decile_percentile(better));
}

FigureStats figure_stats(const std::vector<std::pair<std::string, double>>& values, Better better) {
  FigureStats s;
  std::vector<double> v;
  for (const auto& [id, x] : values) {
    if (!std::isfinite(x)) continue;
    v.push_back(x);
    if (!s.worst || worse(x, *s.worst, better)) {
      s.worst = x;
      s.worst_case = id;
    }
  }
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  s.median = percentile(v, 50.0);
  s.worst_decile = worst_decile(v, better);
  return s;
}

std::vector<MethodSummary> summarise(const SuiteResults& results) {
  std::vector<MethodSummary> out;
  for (const SuiteMethod& m : results.methods) {
    MethodSummary summary;
    summary.method = m;
    std::vector<std::vector<std::pair<std::string, double>>> values(suite_figures().size());
    for (const CaseRecord& c : results.cases) {
      if (!c.done()) {
        ++summary.failed;
        continue;
      }
      const CaseMethod* run = c.method(m.slug);
      if (run == nullptr) continue;
      ++summary.counted;
      for (std::size_t k = 0; k < suite_figures().size(); ++k)
        if (const Figure f = suite_value(*run, suite_figures()[k])) values[k].emplace_back(c.id, *f);
    }
    for (std::size_t k = 0; k < suite_figures().size(); ++k)
      summary.stats.push_back(figure_stats(values[k], suite_figures()[k].better));
    out.push_back(std::move(summary));
  }
  return out;
}

std::string key_method(const SuiteResults& results) {
  for (const SuiteMethod& m : results.methods)
    if (m.slug == "ts-graphs") return m.slug;
  return results.methods.empty() ? "" : results.methods.front().slug;
}

std::vector<std::pair<std::string, double>> pgo_ratios(const SuiteResults& results,
                                                       const std::string& other) {
  const std::string key = key_method(results);
  std::vector<std::pair<std::string, double>> out;
  for (const CaseRecord& c : results.cases) {
    const CaseMethod* a = c.done() ? c.method(key) : nullptr;
    const CaseMethod* b = c.done() ? c.method(other) : nullptr;
    if (a == nullptr || b == nullptr) continue;
    const Figure ta = a->figure("pgo.t_pgo_s"), tb = b->figure("pgo.t_pgo_s");
    if (ta && tb && *tb > 0.0) out.emplace_back(c.id, *ta / *tb);
  }
  return out;
}

LoopTotals loop_totals(const SuiteResults& results, const std::string& method) {
  LoopTotals t;
  for (const CaseRecord& c : results.cases) {
    const CaseMethod* run = c.done() ? c.method(method) : nullptr;
    const Figure found = run ? run->figure("loops.n_loops") : std::nullopt;
    if (!found) continue;
    ++t.cases;
    t.found += *found;
    t.correct += run->figure("loops.n_loops_correct").value_or(0.0);
    t.room_found += run->figure("loops.n_loops_room").value_or(0.0);
    t.room_correct += run->figure("loops.n_loops_room_correct").value_or(0.0);
  }
  return t;
}

std::vector<const CaseRecord*> worst_first(const SuiteResults& results) {
  const std::string key = key_method(results);
  const SuiteFigure& f1 = figure_by_key("rooms_gt.f1");
  const SuiteFigure& f_re = figure_by_key("consistency.f_re");
  // Failed cases, and figures a case lacks, sort before every number.
  constexpr double kFirst = -std::numeric_limits<double>::infinity();
  const auto sort_key = [&](const CaseRecord& c) {
    const CaseMethod* run = c.done() ? c.method(key) : nullptr;
    if (run == nullptr) return std::make_tuple(0, kFirst, kFirst);
    return std::make_tuple(1, suite_value(*run, f1).value_or(kFirst),
                           suite_value(*run, f_re).value_or(kFirst));
  };
  std::vector<const CaseRecord*> out;
  for (const CaseRecord& c : results.cases) out.push_back(&c);
  std::stable_sort(out.begin(), out.end(),
                   [&](const CaseRecord* a, const CaseRecord* b) { return sort_key(*a) < sort_key(*b); });
  return out;
}

std::string figure_text(const Figure& f, int decimals) { return f ? fixed_text(*f, decimals) : "-"; }

std::string case_figure_text(const CaseMethod& run, const SuiteFigure& figure) {
  return figure_text(suite_value(run, figure), figure.whole ? 0 : figure.decimals);
}

std::string case_figure_text(const CaseMethod& run, const std::string& key) {
  return case_figure_text(run, figure_by_key(key));
}

std::string cases_text(std::size_t n) { return std::to_string(n) + (n == 1 ? " case" : " cases"); }

std::string better_text(Better better) { return better == Better::kHigher ? "higher (p10)" : "lower (p90)"; }

std::string case_line(const CaseRecord& c, const SuiteResults& results) {
  if (!c.done()) return c.id + ": failed: " + c.message;
  const std::string key = key_method(results);
  std::string line = c.id + ":";
  const auto add = [&](const CaseMethod& run, const char* figure_key, const char* label, const char* unit) {
    return std::string(label) + " " + case_figure_text(run, figure_key) + unit;
  };
  if (const CaseMethod* run = c.method(key)) {
    line += " " + run->method.name + " " + add(*run, "rooms_gt.f1", "F1", "") + ", " +
            add(*run, "consistency.f_re", "f_re", "") + ", " + add(*run, "consistency.dcs", "DCS", "") +
            ", " + add(*run, "consistency.d_center", "d_center", " m") + ";";
  }
  for (const CaseMethod& run : c.methods) {
    if (run.method.slug == key) continue;
    line += " " + run.method.name + " " + add(run, "rooms_gt.f1", "F1", "") + ";";
  }
  return line + " " + fixed_text(c.wall_s, 0) + " s";
}

std::string suite_csv(const SuiteResults& results) {
  std::string out = "case,status,message,kind";
  for (const std::string& k : case_info_keys()) out += "," + k;
  out += ",method,wall_s";
  for (const std::string& k : metrics_keys()) out += "," + k;
  out += "\n";
  for (const CaseRecord& c : results.cases) {
    std::string lead =
        csv_field(c.id) + "," + csv_field(c.status) + "," + csv_field(c.message) + "," + csv_field(c.kind);
    for (const std::string& k : case_info_keys()) lead += "," + csv_field(c.info_value(k));
    for (const SuiteMethod& m : results.methods) {
      const CaseMethod* run = c.done() ? c.method(m.slug) : nullptr;
      if (c.done() && run == nullptr) continue;  // a case run without this method
      out += lead + "," + csv_field(m.name) + ",";
      if (run != nullptr && run->wall_s) out += csv_number(*run->wall_s);
      for (const std::string& k : metrics_keys()) {
        out += ",";
        if (run == nullptr) continue;
        if (const Figure f = run->figure(k)) out += csv_number(*f);
      }
      out += "\n";
    }
  }
  return out;
}

SuiteResults group_results(const SuiteResults& results, const CaseGroup& group) {
  SuiteResults out;
  out.name = results.name;
  out.methods = results.methods;
  for (const CaseRecord& c : results.cases) {
    if (std::find(group.case_ids.begin(), group.case_ids.end(), c.id) != group.case_ids.end())
      out.cases.push_back(c);
  }
  for (const std::string& id : results.pending) {
    if (std::find(group.case_ids.begin(), group.case_ids.end(), id) != group.case_ids.end())
      out.pending.push_back(id);
  }
  return out;
}

namespace {

/// Per method, a table of every suite figure under a heading of level `heading` ("##").
std::string figure_tables(const std::vector<MethodSummary>& summaries, const std::string& heading) {
  std::string md;
  for (const MethodSummary& s : summaries) {
    md += "\n" + heading + " " + md_cell(s.method.name) + "\n\n" + cases_text(s.counted) + " counted, " +
          std::to_string(s.failed) + " failed.\n\n";
    md += "| figure | better (worst decile) | median | worst decile | worst | worst case | cases |\n";
    md += "|---|---|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < suite_figures().size(); ++k) {
      const SuiteFigure& f = suite_figures()[k];
      const FigureStats& st = s.stats[k];
      md += "| " + f.header + " | " + better_text(f.better) + " | " + figure_text(st.median, f.decimals) +
            " | " + figure_text(st.worst_decile, f.decimals) + " | " + figure_text(st.worst, f.decimals) +
            " | " + (st.worst_case.empty() ? "-" : md_cell(st.worst_case)) + " | " + std::to_string(st.n) +
            " |\n";
    }
  }
  return md;
}

/// The title, the counts of cases and their wall time, the methods, and how the tables read.
std::string suite_overview(const SuiteResults& results) {
  int done = 0, failed = 0;
  double wall = 0.0;
  for (const CaseRecord& c : results.cases) {
    (c.done() ? done : failed) += 1;
    wall += c.wall_s;
  }
  const std::size_t total = results.cases.size() + results.pending.size();
  std::string md = "# Suite " + md_cell(results.name) + "\n\n";
  md += cases_text(total) + ": " + std::to_string(done) + " counted, " + std::to_string(failed) +
        " failed, " + std::to_string(results.pending.size()) + " not run yet; " + fixed_text(wall, 0) +
        " s of case wall time. Methods: ";
  for (std::size_t i = 0; i < results.methods.size(); ++i) md += (i ? ", " : "") + results.methods[i].name;
  md += ".\n\n";
  md +=
      "Per method and figure, over the counted cases that have the figure (`cases`): the median, the worst "
      "decile (the 10th percentile where higher is better, the 90th where lower is better; linear between "
      "ranks), the worst value and the first case with it. DCS, d_center and mean IoU exist only where "
      "rooms were paired or matched; rooms F1 is 0 where a run has no final room.\n";
  return md;
}

/// The figure tables again over each group of cases, when the suite file has more than one.
std::string group_tables(const SuiteResults& results) {
  if (results.groups.size() <= 1) return "";
  std::string md =
      "\n## Case groups\n\nThe same tables over the cases of each entry of the suite file's `cases:` "
      "alone.\n";
  for (const CaseGroup& g : results.groups) {
    const SuiteResults sub = group_results(results, g);
    md += "\n### " + md_cell(g.name) + "\n\n" + cases_text(g.case_ids.size()) + ": " +
          std::to_string(sub.cases.size()) + " with a record, " + std::to_string(sub.pending.size()) +
          " not run yet.\n";
    md += figure_tables(summarise(sub), "####");
  }
  return md;
}

/// The name of the method with this slug (the slug itself when there is none).
std::string method_name(const SuiteResults& results, const std::string& slug) {
  std::string name = slug;
  for (const SuiteMethod& m : results.methods)
    if (m.slug == slug) name = m.name;
  return name;
}

/// Per other method, the key method's T_PGO over its on the same case.
std::string pgo_table(const SuiteResults& results, const std::string& key, const std::string& key_name) {
  std::string md = "\n## T_PGO against " + md_cell(key_name) + "\n\n";
  md += "Per case, " + md_cell(key_name) +
        "'s T_PGO over the other method's on the same sequence (below 1: cheaper); "
        "the worst decile is the 90th percentile.\n\n";
  md += "| method | median | worst decile | worst | worst case | cases |\n|---|---|---|---|---|---|\n";
  for (const SuiteMethod& m : results.methods) {
    if (m.slug == key) continue;
    const FigureStats st = figure_stats(pgo_ratios(results, m.slug), Better::kLower);
    md += "| " + md_cell(m.name) + " | " + figure_text(st.median, 2) + " | " +
          figure_text(st.worst_decile, 2) + " | " + figure_text(st.worst, 2) + " | " +
          (st.worst_case.empty() ? "-" : md_cell(st.worst_case)) + " | " + std::to_string(st.n) + " |\n";
  }
  return md;
}

/// Per method, the loop closures found and correct, in all and as the room rule proposed them.
std::string loop_table(const SuiteResults& results) {
  std::string md = "\n## Loop closures\n\n";
  md +=
      "Summed over the counted cases: found and correct (eval's tolerance of the truth), in all and as the "
      "room "
      "rule proposed them (the rest: the distance rule).\n\n";
  md +=
      "| method | found | correct | room rule: found | room rule: correct | cases "
      "|\n|---|---|---|---|---|---|\n";
  for (const SuiteMethod& m : results.methods) {
    const LoopTotals t = loop_totals(results, m.slug);
    md += "| " + md_cell(m.name) + " | " + fixed_text(t.found, 0) + " | " + fixed_text(t.correct, 0) + " | " +
          fixed_text(t.room_found, 0) + " | " + fixed_text(t.room_correct, 0) + " | " +
          std::to_string(t.cases) + " |\n";
  }
  return md;
}

/// The columns of the cases table: per method its figures (rooms F1; the key method also its
/// consistency), with the header and rule cells they add, T_PGO ratio included.
std::vector<std::pair<const SuiteMethod*, std::vector<const SuiteFigure*>>> case_columns(
    const SuiteResults& results, const std::string& key, const std::string& key_name, std::string* header,
    std::string* rule) {
  std::vector<std::pair<const SuiteMethod*, std::vector<const SuiteFigure*>>> columns;
  for (const SuiteMethod& m : results.methods) {
    std::vector<const SuiteFigure*> figures = {&figure_by_key("rooms_gt.f1")};
    if (m.slug == key) {
      for (const char* k : {"consistency.f_re", "consistency.dcs", "consistency.d_center"})
        figures.push_back(&figure_by_key(k));
    }
    for (const SuiteFigure* f : figures) {
      *header += " " + md_cell(m.name) + " " + f->header + " |";
      *rule += "---|";
    }
    if (m.slug != key && !key.empty()) {
      *header += " T_PGO " + md_cell(key_name) + " / " + md_cell(m.name) + " |";
      *rule += "---|";
    }
    columns.emplace_back(&m, std::move(figures));
  }
  return columns;
}

/// Every case, worst first: its status, each method's figures and T_PGO ratio, its wall time.
std::string cases_table(const SuiteResults& results, const std::string& key, const std::string& key_name) {
  std::string md = "\n## Cases, worst first\n\n";
  md += "By the " + (key.empty() ? std::string("first method") : key) + " run's rooms F1, then its f_re.\n\n";
  std::string header = "| case | status |", rule = "|---|---|";
  const auto columns = case_columns(results, key, key_name, &header, &rule);
  md += header + " wall (s) |\n" + rule + "---|\n";
  std::vector<std::map<std::string, double>> ratios;
  for (const auto& [m, figures] : columns) {
    const auto r = pgo_ratios(results, m->slug);
    ratios.emplace_back(r.begin(), r.end());
  }
  for (const CaseRecord* c : worst_first(results)) {
    md += "| " + md_cell(c->id) + " | " + c->status + " |";
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const auto& [m, figures] = columns[i];
      const CaseMethod* run = c->done() ? c->method(m->slug) : nullptr;
      for (const SuiteFigure* f : figures)
        md += " " + (run ? case_figure_text(*run, *f) : std::string("-")) + " |";
      if (m->slug != key && !key.empty()) {
        const auto r = ratios[i].find(c->id);
        md += " " + (r == ratios[i].end() ? std::string("-") : fixed_text(r->second, 2)) + " |";
      }
    }
    md += " " + fixed_text(c->wall_s, 0) + " |\n";
  }
  return md;
}

/// The failed cases with their messages, and the cases not run yet.
std::string unfinished_cases(const SuiteResults& results) {
  std::string md;
  if (std::any_of(results.cases.begin(), results.cases.end(),
                  [](const CaseRecord& c) { return !c.done(); })) {
    md += "\n## Failed cases\n\n";
    for (const CaseRecord& c : results.cases)
      if (!c.done()) md += "- `" + c.id + "`: " + md_cell(c.message) + "\n";
  }
  if (!results.pending.empty()) {
    md += "\n## Not run yet\n\n";
    for (const std::string& id : results.pending) md += "- `" + id + "`\n";
  }
  return md;
}

}  // namespace

std::string suite_markdown(const SuiteResults& results) {
  const std::vector<MethodSummary> summaries = summarise(results);
  std::string md = suite_overview(results);
  md += figure_tables(summaries, "##");
  md += group_tables(results);
  const std::string key = key_method(results);
  const std::string key_name = method_name(results, key);
  if (results.methods.size() > 1) md += pgo_table(results, key, key_name);
  md += loop_table(results);
  md += cases_table(results, key, key_name);
  md += unfinished_cases(results);
  return md;
}

}  // namespace tsgraphs::eval
