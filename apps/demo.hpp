#pragma once
/// `tsgraphs demo`: the paper's comparison on built-in scenes, with nothing to download.
/// Simulates each scene for each seed, runs TS-graphs, S-Graphs+ and the two ablations on it,
/// evaluates every run against the simulator's ground truth, compares two platforms (the
/// sensor at its own height and higher, one seed), and writes the tables and the report.
#include <string>
#include <vector>

namespace tsgraphs::app {

struct DemoOptions {
  std::string out = "tsgraphs-demo";  ///< output folder
  int seeds = 1;                      ///< seeds 1..N per scene (one run each ~20 s on 2 cores)
  std::vector<std::string> scenes = {"atrium", "office"};  ///< built-in names or scene files
  double platform_height = 1.7;  ///< the second platform's sensor height for the comparison (m); 0: none
  bool quiet = false;
};

/// Runs the demo; prints the tables on stdout and writes OUT/table.md, table.csv, report.html
/// (the tables and, per scene, the seed-1 runs of every method drawn side by side).
void demo(const DemoOptions& options);

}  // namespace tsgraphs::app
