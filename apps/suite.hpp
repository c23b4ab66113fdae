#pragma once
/// `tsgraphs suite`: many cases (generated buildings, scenes, sequences) run with the same
/// rules and tabled (docs/suite.md). The suite runs its cases as child processes of this
/// binary, N at once (`--case ID` runs one, in this process); `--plan` writes the command of
/// every case for GNU parallel or a Slurm array; `--collect` builds the tables from whatever
/// has finished.
#include <string>
#include <vector>

namespace tsgraphs::app {

/// Most cases at once: the size of the child-process table (ChildProcesses::kMaxChildren).
inline constexpr int kMaxSuiteJobs = 256;

struct SuiteOptions {
  std::string suite;                 ///< the suite file ("" with --collect alone)
  std::string out;                   ///< the suite folder
  int jobs = 1;                      ///< cases at once
  bool keep_sequences = false;       ///< keep each case's simulated sequence
  std::vector<std::string> methods;  ///< instead of the suite's methods when not empty
  bool plan = false;                 ///< write OUT/plan.txt, run nothing
  bool collect_flag = false;         ///< --collect given: build the tables, run nothing...
  std::string collect;               ///< ...of this suite folder ("": of `out`, with the suite file)
  std::string case_id;               ///< run this case only
  int threads = 0;                   ///< --threads as given: the cores the suite may use (0: all)
  bool quiet = false;
};

/// Runs what the options ask; returns the exit status: 0, 1 when a case failed, 130 when
/// interrupted. Bad input (the suite file, the options) is an InputError, before anything is
/// written.
int suite(const SuiteOptions& options);

}  // namespace tsgraphs::app
