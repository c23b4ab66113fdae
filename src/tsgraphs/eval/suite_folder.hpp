#pragma once
/// The files of a suite folder (docs/suite.md) that `tsgraphs suite` writes and `--collect`
/// reads back: suite.json (the suite's name, methods and case ids, in plan order) and each
/// case's case.json (its status, what it ran on, per method the figures of its metrics.json
/// and the run's wall time). Readers throw InputError naming the file and the key; unknown
/// keys are ignored, so that an older reader takes a newer folder.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tsgraphs/eval/metrics.hpp"

namespace tsgraphs::eval {

/// File and folder names inside a suite folder.
namespace suite_files {
inline constexpr const char* kIndex = "suite.json";
inline constexpr const char* kPlan = "plan.txt";
inline constexpr const char* kCases = "cases";  ///< DIR/cases/ID/ per case
inline constexpr const char* kCase = "case.json";
inline constexpr const char* kSpec = "spec.txt";  ///< the definition the case folder's runs belong to
inline constexpr const char* kLog = "log.txt";
inline constexpr const char* kScene = "scene.yaml";
inline constexpr const char* kSequence = "sequence";
inline constexpr const char* kCsv = "suite.csv";
inline constexpr const char* kMarkdown = "suite.md";
inline constexpr const char* kReport = "report.html";
}  // namespace suite_files

/// case.json "status".
inline constexpr const char* kCaseDone = "done";
inline constexpr const char* kCaseFailed = "failed";

/// A method of the comparison: its run folder's name and the name tables show.
struct SuiteMethod {
  std::string slug;  ///< e.g. "ts-graphs"
  std::string name;  ///< e.g. "TS-graphs"
};

/// One method's run in a case.
struct CaseMethod {
  SuiteMethod method;
  Figure wall_s;  ///< the run's wall time (run_info.json wall_time_s)
  /// metrics.json flattened to "group.key" (e.g. "rooms_gt.f1"); a null figure has no value.
  std::map<std::string, Figure> figures;

  /// The figure at `key`; no value when absent or null.
  Figure figure(const std::string& key) const;
};

/// case.json.
struct CaseRecord {
  std::string id;
  std::string kind;  ///< generate, scene, sequence
  /// The case's definition as it ran (its kind and parameters in one line): a case whose
  /// definition changed since is run again, not reused.
  std::string spec;
  std::string status;   ///< kCaseDone or kCaseFailed
  std::string message;  ///< why it failed; "" when done
  double wall_s = 0.0;  ///< the case's wall time (scene, simulation, runs, evals) in its last attempt
  /// What it ran on, in this order where known (kCaseInfoKeys): e.g. {"style", "office"}.
  std::vector<std::pair<std::string, std::string>> info;
  std::vector<CaseMethod> methods;  ///< in the suite's order; empty when failed

  bool done() const { return status == kCaseDone; }
  /// The run of `slug`, nullptr when the case has none.
  const CaseMethod* method(const std::string& slug) const;
  /// The info value of `key`, "" when absent.
  std::string info_value(const std::string& key) const;
};

/// The info keys of a case, in the order suite.csv gives them columns.
const std::vector<std::string>& case_info_keys();

std::string case_record_json(const CaseRecord& record);
/// `file` names the text in messages.
CaseRecord parse_case_record(const std::string& text, const std::string& file);
/// A missing or malformed file is an InputError naming it.
CaseRecord read_case_record(const std::string& file);

/// The cases one entry of a suite file's `cases:` made (a generate entry: its styles x seeds).
struct CaseGroup {
  std::string name;                   ///< e.g. "cases[1]: generate, realistic"
  std::vector<std::string> case_ids;  ///< in plan order
};

/// suite.json: what --collect needs to know of the suite without its file.
struct SuiteIndex {
  std::string name;
  std::string suite_file;             ///< the suite file's absolute path
  std::vector<SuiteMethod> methods;   ///< in the suite's order
  std::vector<std::string> case_ids;  ///< in plan order
  std::vector<CaseGroup> groups;      ///< the suite file's entries; empty in a folder older than groups
};

std::string suite_index_json(const SuiteIndex& index);
SuiteIndex read_suite_index(const std::string& file);

/// metrics.json text flattened to "group.key" -> figure; nulls and non-numbers have no value.
/// Malformed JSON is an InputError naming `file`.
std::map<std::string, Figure> flatten_metrics_json(const std::string& text, const std::string& file);
/// Every "group.key" of metrics.json, in the order eval writes them.
const std::vector<std::string>& metrics_keys();

}  // namespace tsgraphs::eval
