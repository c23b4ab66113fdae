#pragma once
/// The page of a suite (docs/suite.md): self-contained like the run and demo pages (inline CSS
/// and SVG, no script, no URL). Its counts and per method the table of the suite's figures
/// (eval/suite_table.hpp), then a bird's-eye per case, each method side by side, the worst case
/// first, captioned with the case id and its figures, so that one sees at once where a method
/// fails.
#include <functional>
#include <string>

#include "tsgraphs/eval/suite_table.hpp"

namespace tsgraphs::report {

/// The SVG text of the bird's-eye of `slug`'s run in case `c`, "" when there is none.
using BirdseyeSource = std::function<std::string(const eval::CaseRecord& c, const std::string& slug)>;

std::string suite_report_html(const eval::SuiteResults& results, const BirdseyeSource& birdseye);

/// The bird's-eye a run folder keeps (RUN/birdseye.svg, drawn with the sequence's ground truth
/// by run and eval, so it outlives the sequence), "" when the file is missing.
std::string read_birdseye(const std::string& run_dir);

/// Writes `path` (whole or not at all) from the cases under `suite_dir`: each run's
/// bird's-eye from suite_dir/cases/ID/<slug>/birdseye.svg.
void write_suite_report(const std::string& path, const std::string& suite_dir,
                        const eval::SuiteResults& results);

}  // namespace tsgraphs::report
