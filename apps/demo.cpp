// `tsgraphs demo` (demo.hpp).
#include "demo.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <thread>

#include "commands.hpp"
#include "methods.hpp"
#include "tsgraphs/eval/method_table.hpp"
#include "tsgraphs/eval/table_text.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/report/report_html.hpp"
#include "tsgraphs/report/run_view.hpp"

namespace tsgraphs::app {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// "2026-11-22 08:10 UTC".
std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M UTC", &tm);
  return text;
}

/// "2 cores, <model name>" from /proc/cpuinfo where there is one.
std::string machine() {
  std::string model;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; model.empty() && std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
      model = line.substr(line.find(':') + 2);
  }
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return std::to_string(cores) + (cores == 1 ? " core" : " cores") + (model.empty() ? "" : ", " + model);
}

std::string figure(const std::optional<double>& v) { return v ? eval::fixed_text(*v, 2) : "-"; }

/// Says what the demo does now, with the seconds since it started, unless quiet.
using Step = std::function<void(const std::string&)>;

/// Every seed of `scene` simulated and run by every method; a row per method in `results`.
void run_scene(const scene::Scene& scene, const DemoOptions& options, const fs::path& out, const Step& step,
               std::vector<eval::MethodResult>& results) {
  const std::size_t first_row = results.size();
  for (const Method& m : kMethods) results.push_back({scene.name, m.name, {}});
  for (int seed = 1; seed <= options.seeds; ++seed) {
    const std::string tag = scene.name + "_seed" + std::to_string(seed);
    const std::string seq = (out / tag).string();
    step("simulate " + tag);
    simulate(scene, seq, static_cast<std::uint64_t>(seed), 0, true);
    for (std::size_t k = 0; k < std::size(kMethods); ++k) {
      const Method& m = kMethods[k];
      pipeline::PipelineConfig config;
      config.rooms.layer.free_space_method = m.free_space;
      config.rooms.layer.room_trigger = m.room_trigger;
      const std::string run_dir = (out / (tag + "_" + m.slug)).string();
      step("run " + tag + ", " + m.name);
      run(seq, run_dir, config, true);
      results[first_row + k].seeds.push_back(evaluate(run_dir, seq, true, false));
    }
  }
}

/// Two platforms on `scene`, seed 1: the same path with the sensor at options.platform_height (a
/// person carrying it rather than a robot), TS-graphs on both, their rooms paired; one line.
std::string compare_platforms(const scene::Scene& scene, const DemoOptions& options, const fs::path& out,
                              const Step& step) {
  scene::Scene raised = scene;
  raised.sensor.mount_height = options.platform_height;
  const std::string height = eval::fixed_text(options.platform_height, 2);
  const std::string tag = scene.name + "_seed1_sensor" + height;
  const std::string seq = (out / tag).string();
  step("simulate " + tag);
  simulate(raised, seq, 1, 0, true);
  const pipeline::PipelineConfig config;  // the platform is measured from the scans
  const std::string low_run = (out / (scene.name + "_seed1_" + kMethods[0].slug)).string();
  const std::string high_run = (out / (tag + "_" + kMethods[0].slug)).string();
  step("run " + tag + ", TS-graphs");
  run(seq, high_run, config, true);
  const eval::Metrics high = evaluate(high_run, seq, true, false);
  const eval::Consistency c = compare(low_run, high_run, true, false);
  return "Platforms (" + scene.name + ", seed 1, TS-graphs): the sensor at " +
         eval::fixed_text(scene.sensor.mount_height, 2) + " m against " + height +
         " m: " + std::to_string(c.N1st) + " / " + std::to_string(c.N2nd) + " rooms, " +
         std::to_string(c.N_re) + " paired, f_re " + eval::fixed_text(c.f_re, 2) + ", DCS " + figure(c.dcs) +
         ", d_center " + figure(c.d_center) + " m; at " + height + " m: rooms F1 " +
         figure(high.rooms_gt.f1) + ", ATE_rmse " +
         (high.trajectory.ate_rmse ? eval::fixed_text(*high.trajectory.ate_rmse, 3) : std::string("-")) +
         " m.\n";
}

/// table.md's text (printed too) and table.csv, in `out`.
std::string write_tables(const std::vector<eval::MethodResult>& results, const std::string& summary,
                         const std::string& platforms, const fs::path& out) {
  std::string md = summary + "\n\n";
  md += "Table 1 (the paper's layout; ATE is ATE_loop, the distance between the first and last pose):\n\n";
  md += eval::markdown_table(results, eval::table1_columns());
  md += "\nAgainst the simulator's ground truth, and speed:\n\n";
  md += eval::markdown_table(results, eval::truth_columns());
  if (!platforms.empty()) md += "\n" + platforms;
  std::vector<eval::TableColumn> all = eval::table1_columns();
  for (eval::TableColumn& c : eval::truth_columns()) all.push_back(std::move(c));
  io::write_file_atomic((out / "table.md").string(), md);
  io::write_file_atomic((out / "table.csv").string(), eval::csv_table(results, all));
  return md;
}

/// report.html: the tables, then each scene's seed-1 runs side by side.
void write_report(const std::vector<eval::MethodResult>& results, const std::string& summary,
                  const std::string& platforms, const fs::path& out) {
  std::vector<report::DemoSection> sections;
  for (std::size_t row = 0; row < results.size(); row += std::size(kMethods)) {
    const std::string& scene = results[row].scene;
    report::DemoSection section{scene + ", seed 1", {}};
    for (const Method& m : kMethods) {
      report::RunView run = report::read_run_view((out / (scene + "_seed1_" + m.slug)).string(),
                                                  (out / (scene + "_seed1")).string());
      run.label = m.name;
      section.runs.push_back(std::move(run));
    }
    sections.push_back(std::move(section));
  }
  const std::string intro = "<p>" + report::html_escape(summary) + "</p>\n" +
                            (platforms.empty() ? "" : "<p>" + report::html_escape(platforms) + "</p>\n");
  const std::string tables =
      "<h2>Table 1</h2>\n<p>The paper's layout; ATE is ATE_loop, the distance between the "
      "first and last pose.</p>\n" +
      report::method_table_html(results, eval::table1_columns()) +
      "<h2>Against the simulator's ground truth, and speed</h2>\n" +
      report::method_table_html(results, eval::truth_columns());
  io::write_file_atomic((out / "report.html").string(),
                        report::demo_report_html("tsgraphs demo: TS-graphs, S-Graphs+ and the ablations",
                                                 intro, tables, sections));
}

}  // namespace

void demo(const DemoOptions& options) {
  const auto start = Clock::now();
  const fs::path out = options.out;
  fs::create_directories(out);
  const Step step = [&](const std::string& what) {
    if (!options.quiet) std::fprintf(stderr, "demo: %6.1f s  %s\n", seconds_since(start), what.c_str());
  };
  std::vector<eval::MethodResult> results;
  std::string platforms;
  for (std::size_t si = 0; si < options.scenes.size(); ++si) {
    const scene::Scene scene = load_and_warn(options.scenes[si]);
    draw_scene(scene, (out / (scene.name + ".svg")).string(), true);
    run_scene(scene, options, out, step, results);
    if (si == 0 && options.platform_height > 0.0) platforms = compare_platforms(scene, options, out, step);
  }
  const std::string summary = "Measured " + utc_now() + " on " + machine() + "; " +
                              std::to_string(options.seeds) + (options.seeds == 1 ? " seed" : " seeds") +
                              (options.seeds > 1 ? " (mean ± standard deviation)" : "") + "; the demo took " +
                              eval::fixed_text(seconds_since(start), 0) + " s.";
  const std::string md = write_tables(results, summary, platforms, out);
  step("report");
  write_report(results, summary, platforms, out);
  std::printf("%s", md.c_str());
  step("wrote " + (out / "table.md").string() + ", table.csv, report.html");
}

}  // namespace tsgraphs::app
