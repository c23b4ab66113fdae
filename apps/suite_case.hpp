#pragma once
/// One case of a suite (docs/suite.md), run into OUT/cases/ID/: its scene (generated, or the
/// scene file), the simulated sequence, a run folder per method with metrics.json and the
/// bird's-eye, a log, and last case.json. Resumable: a case whose case.json says done is not
/// rerun, and a method's run folder with a metrics.json is reused.
#include <string>

#include "suite_file.hpp"
#include "tsgraphs/eval/suite_folder.hpp"
#include "tsgraphs/pipeline/pipeline_config.hpp"
#include "tsgraphs/scene/scene.hpp"

namespace tsgraphs::app {

struct CaseOptions {
  std::string out;              ///< the suite folder
  bool keep_sequences = false;  ///< keep OUT/cases/ID/sequence (2-9 GB) after the case
  bool quiet = false;           ///< no progress from the library's steps
};

/// OUT/cases/ID.
std::string case_dir(const std::string& out, const std::string& id);
/// OUT/cases/ID/case.json.
std::string case_file(const std::string& out, const std::string& id);
/// The case's definition in one line: its kind, its parameters, the suite's laps and, for a
/// scene file or an imported map, a fingerprint of the files' contents
/// ("generate style=office seed=3 size=0.3 platform=default laps=2").
std::string case_spec(const Suite& suite, const SuiteCase& c);
/// Whether OUT/cases/ID/case.json says done, for this definition of the case and with a run
/// of every method of the suite.
bool case_done(const Suite& suite, const SuiteCase& c, const std::string& out);

/// Runs the case into OUT/cases/ID and writes its case.json (written whole, last). A case
/// folder left by another definition of the case (spec.txt) is emptied first. A case that
/// throws is recorded as failed with the message, not rethrown; its sequence is removed either
/// way unless keep_sequences (a `sequence` case's folder is never touched). Step lines go to
/// stderr (the case's log when run by `suite`).
eval::CaseRecord run_case(const Suite& suite, const SuiteCase& c, const CaseOptions& options);

}  // namespace tsgraphs::app
