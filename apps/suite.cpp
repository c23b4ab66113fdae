// `tsgraphs suite` (suite.hpp): the command and its processes; one case is suite_case.cpp,
// the suite file suite_file.cpp, the tables eval/suite_table and report/suite_report.
#include "suite.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <thread>

#include "child_processes.hpp"
#include "methods.hpp"
#include "progress.hpp"
#include "suite_case.hpp"
#include "suite_file.hpp"
#include "tsgraphs/core/error.hpp"
#include "tsgraphs/eval/suite_table.hpp"
#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/report/suite_report.hpp"

namespace tsgraphs::app {

namespace fs = std::filesystem;

static_assert(kMaxSuiteJobs == ChildProcesses::kMaxChildren,
              "--jobs may not start more children than the table holds");

namespace {

namespace files = eval::suite_files;

/// This program's absolute path: the children and the plan's commands run the same binary.
std::string self_exe() { return fs::read_symlink("/proc/self/exe").string(); }

/// A word of a shell command line, quoted when the shell would split or expand it.
std::string shell_word(const std::string& word) {
  constexpr const char* kPlain = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_./=:+,@%";
  if (!word.empty() && word.find_first_not_of(kPlain) == std::string::npos) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::vector<eval::SuiteMethod> suite_methods(const Suite& suite) {
  std::vector<eval::SuiteMethod> out;
  for (const std::string& slug : suite.methods) out.push_back({slug, find_method(slug)->name});
  return out;
}

eval::SuiteIndex index_of(const Suite& suite) {
  eval::SuiteIndex index;
  index.name = suite.name;
  index.suite_file = suite.file;
  index.methods = suite_methods(suite);
  for (const SuiteCase& c : suite.cases) {
    index.case_ids.push_back(c.id);
    if (index.groups.empty() || index.groups.back().name != c.group) index.groups.push_back({c.group, {}});
    index.groups.back().case_ids.push_back(c.id);
  }
  return index;
}

/// The suite folder may be new, empty, or an earlier output of a suite (suite.json).
void check_out_folder(const Suite& suite, const std::string& out) {
  if (out.empty()) throw InputError("suite: give --out DIR");
  if (!fs::exists(out)) return;
  if (!fs::is_directory(out)) throw InputError(out + ": exists and is not a folder");
  if (!fs::is_empty(out) && !fs::exists(fs::path(out) / files::kIndex))
    throw InputError(out + ": folder exists and holds no earlier suite (no " + std::string(files::kIndex) +
                     "); refusing to write into it");
  // A resumed suite writes into its cases' folders: a file in the way is said before any case runs.
  for (const SuiteCase& c : suite.cases) {
    const fs::path dir = case_dir(out, c.id);
    for (const fs::path& p : {dir.parent_path(), dir})
      if (fs::exists(p) && !fs::is_directory(p))
        throw InputError(p.string() + ": exists and is not a folder");
  }
}

void write_index(const Suite& suite, const std::string& out) {
  fs::create_directories(out);
  io::write_file_atomic((fs::path(out) / files::kIndex).string(), eval::suite_index_json(index_of(suite)));
}

/// The arguments of the command that runs case `id` (without the program).
std::vector<std::string> case_args(const Suite& suite, const SuiteOptions& options, const std::string& out,
                                   const std::string& id, int threads, bool quiet) {
  std::vector<std::string> args = {"suite", suite.file, "--out", out, "--case", id};
  if (threads > 0) args.insert(args.end(), {"--threads", std::to_string(threads)});
  if (quiet) args.push_back("-q");
  if (options.keep_sequences) args.push_back("--keep-sequences");
  if (!options.methods.empty()) {
    args.push_back("--methods");
    args.insert(args.end(), suite.methods.begin(), suite.methods.end());
  }
  return args;
}

/// The records under `dir` of the index's cases; a case without a readable case.json is pending.
eval::SuiteResults gather(const std::string& dir, const eval::SuiteIndex& index) {
  eval::SuiteResults results;
  results.name = index.name;
  results.methods = index.methods;
  results.groups = index.groups;
  for (const std::string& id : index.case_ids) {
    const std::string file = case_file(dir, id);
    if (!fs::is_regular_file(file)) {
      results.pending.push_back(id);
      continue;
    }
    try {
      results.cases.push_back(eval::read_case_record(file));
    } catch (const InputError& e) {
      std::fprintf(stderr, "tsgraphs: warning: %s (the case counts as not run)\n", e.what());
      results.pending.push_back(id);
    }
  }
  return results;
}

/// suite.csv, suite.md and report.html in `dir`; returns the markdown.
std::string write_tables(const std::string& dir, const eval::SuiteResults& results) {
  const fs::path d(dir);
  const std::string md = eval::suite_markdown(results);
  io::write_file_atomic((d / files::kCsv).string(), eval::suite_csv(results));
  io::write_file_atomic((d / files::kMarkdown).string(), md);
  report::write_suite_report((d / files::kReport).string(), dir, results);
  return md;
}

int failed_cases(const eval::SuiteResults& results) {
  int n = 0;
  for (const eval::CaseRecord& c : results.cases) n += c.done() ? 0 : 1;
  return n;
}

void print_written(const std::string& dir, const eval::SuiteResults& results, bool quiet) {
  if (quiet) return;
  std::fprintf(stderr, "suite: wrote %s (%zu counted, %d failed, %zu not run yet), suite.md, report.html\n",
               (fs::path(dir) / files::kCsv).c_str(), results.cases.size() - failed_cases(results),
               failed_cases(results), results.pending.size());
}

int collect(const std::string& dir, bool quiet) {
  const std::string index_file = (fs::path(dir) / files::kIndex).string();
  if (!fs::is_regular_file(index_file))
    throw InputError(dir + ": not a suite folder (no " + std::string(files::kIndex) + ")");
  const eval::SuiteResults results = gather(dir, eval::read_suite_index(index_file));
  std::printf("%s", write_tables(dir, results).c_str());
  print_written(dir, results, quiet);
  return 0;
}

int plan(const Suite& suite, const SuiteOptions& options, const std::string& out) {
  check_out_folder(suite, out);
  write_index(suite, out);
  const std::string exe = shell_word(self_exe());
  std::string text;
  for (const SuiteCase& c : suite.cases) {
    text += exe;
    for (const std::string& a : case_args(suite, options, out, c.id, options.threads, false))
      text += " " + shell_word(a);
    text += "\n";
  }
  const std::string file = (fs::path(out) / files::kPlan).string();
  io::write_file_atomic(file, text);
  if (!options.quiet)
    std::fprintf(stderr, "suite: wrote %s: %s, one command a line (docs/suite.md: parallel, Slurm)\n",
                 file.c_str(), eval::cases_text(suite.cases.size()).c_str());
  return 0;
}

/// stdout and stderr appended to a file while alive; the terminal's stderr kept for the end.
class RedirectOutput {
 public:
  explicit RedirectOutput(const std::string& log) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0) throw InputError(log + ": cannot write (folder missing or not writable)");
    std::fflush(stdout);
    std::fflush(stderr);
    out_ = ::dup(STDOUT_FILENO);
    err_ = ::dup(STDERR_FILENO);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    ::close(fd);
  }
  ~RedirectOutput() {
    std::fflush(stdout);
    std::fflush(stderr);
    ::dup2(out_, STDOUT_FILENO);
    ::dup2(err_, STDERR_FILENO);
    ::close(out_);
    ::close(err_);
  }
  RedirectOutput(const RedirectOutput&) = delete;
  RedirectOutput& operator=(const RedirectOutput&) = delete;

 private:
  int out_ = -1, err_ = -1;
};

int run_one_case(const Suite& suite, const SuiteOptions& options, const std::string& out) {
  const SuiteCase& c = find_case(suite, options.case_id);
  check_out_folder(suite, out);
  eval::SuiteResults names;  // what case_line needs to know of the suite
  names.methods = suite_methods(suite);
  if (case_done(suite, c, out)) {
    if (!options.quiet) std::fprintf(stderr, "suite: %s: done earlier, not rerun\n", c.id.c_str());
    return 0;
  }
  // A case run on its own (by hand, or a plan's line) makes a suite folder --collect can read.
  if (!fs::exists(fs::path(out) / files::kIndex)) write_index(suite, out);
  const fs::path dir = case_dir(out, c.id);
  fs::create_directories(dir);
  eval::CaseRecord record;
  {
    const RedirectOutput redirect((dir / files::kLog).string());
    record = run_case(suite, c, {out, options.keep_sequences, options.quiet});
  }
  if (!options.quiet) {
    const std::string log = record.done() ? "" : " (log: " + (dir / files::kLog).string() + ")";
    std::fprintf(stderr, "suite: %s%s\n", eval::case_line(record, names).c_str(), log.c_str());
  }
  return record.done() ? 0 : 1;
}

/// The record of case `c` whose process ended with `status`: the one it wrote, or, when it
/// wrote none that reads (a crash, the OOM killer), a failed one written in its place.
eval::CaseRecord finished_case_record(const Suite& suite, const SuiteCase& c, const std::string& out,
                                      int status) {
  const std::string file = case_file(out, c.id);
  if (fs::is_regular_file(file)) {
    try {
      return eval::read_case_record(file);
    } catch (const InputError&) {
    }
  }
  eval::CaseRecord record;
  record.id = c.id;
  record.kind = c.kind;
  record.spec = case_spec(suite, c);
  record.status = eval::kCaseFailed;
  record.message = "the case's process ended with " + describe_wait_status(status) + " and no record";
  io::write_file_atomic(file, eval::case_record_json(record));
  return record;
}

/// Runs the cases not done yet, `options.jobs` child processes at a time, then writes the tables.
int run_all(const Suite& suite, const SuiteOptions& options, const std::string& out) {
  check_out_folder(suite, out);
  write_index(suite, out);
  std::vector<const SuiteCase*> pending;
  for (const SuiteCase& c : suite.cases)
    if (!case_done(suite, c, out)) pending.push_back(&c);
  const int cores = options.threads > 0 ? options.threads
                                        : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int jobs =
      std::max(1, std::min<int>(options.jobs, static_cast<int>(std::max<std::size_t>(1, pending.size()))));
  const int threads = std::max(1, cores / jobs);
  const bool quiet = options.quiet;
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  if (!quiet) {
    std::fprintf(
        stderr,
        "suite: %s: %s, %zu done earlier, %zu to run, %d at a time (%d thread%s each); logs in %s/%s/ID/%s\n",
        suite.name.c_str(), eval::cases_text(suite.cases.size()).c_str(), suite.cases.size() - pending.size(),
        pending.size(), jobs, threads, threads == 1 ? "" : "s", out.c_str(), files::kCases, files::kLog);
  }
  eval::SuiteResults names;
  names.methods = suite_methods(suite);
  const std::string exe = self_exe();
  Progress progress("suite", quiet);
  ChildProcesses children;
  std::map<pid_t, const SuiteCase*> running;
  std::size_t next = 0, finished = 0;
  if (tty && !pending.empty()) progress.update(0, pending.size());  // the bar from the start
  while (true) {
    while (ChildProcesses::signal_received() == 0 && static_cast<int>(running.size()) < jobs &&
           next < pending.size()) {
      const SuiteCase& c = *pending[next++];
      const fs::path dir = case_dir(out, c.id);
      fs::create_directories(dir);
      fs::remove(dir / files::kCase);  // so that a record after the child is the child's
      std::vector<std::string> argv = {exe};
      for (const std::string& a : case_args(suite, options, out, c.id, threads, true)) argv.push_back(a);
      running[children.start(argv, (dir / files::kLog).string())] = &c;
    }
    if (running.empty()) break;
    const std::optional<ChildProcesses::Exit> exit = children.wait_any();
    if (!exit) break;
    const auto it = running.find(exit->pid);
    if (it == running.end()) continue;
    const SuiteCase& c = *it->second;
    running.erase(it);
    if (ChildProcesses::signal_received() != 0) continue;  // interrupted: not recorded, rerun next time

    const eval::CaseRecord record = finished_case_record(suite, c, out, exit->status);
    const std::string log = (fs::path(case_dir(out, c.id)) / files::kLog).string();
    ++finished;
    if (quiet) continue;
    const std::string line = "suite: [" + std::to_string(finished) + "/" + std::to_string(pending.size()) +
                             "] " + eval::case_line(record, names) +
                             (record.done() ? "" : " (log: " + log + ")");
    if (tty) {
      std::fprintf(stderr, "\r\033[K%s\n", line.c_str());
      progress.update(finished, pending.size());
    } else {
      std::fprintf(stderr, "%s\n", line.c_str());
    }
  }
  if (const int sig = ChildProcesses::signal_received(); sig != 0) {
    std::fprintf(stderr,
                 "\nsuite: interrupted: %zu of %zu cases finished; run the same command again to go on\n",
                 finished, pending.size());
    return 128 + sig;
  }
  const eval::SuiteResults results = gather(out, index_of(suite));
  std::printf("%s", write_tables(out, results).c_str());
  print_written(out, results, quiet);
  return failed_cases(results) > 0 ? 1 : 0;
}

}  // namespace

int suite(const SuiteOptions& options) {
  if (!options.collect.empty()) {
    if (!options.suite.empty() || options.plan || !options.case_id.empty() || !options.out.empty())
      throw InputError("suite: --collect DIR goes alone (it reads DIR/" + std::string(files::kIndex) +
                       "); or give SUITE --out DIR --collect");
    return collect(options.collect, options.quiet);
  }
  if (options.suite.empty()) throw InputError("suite: give a suite file (docs/suite.md), or --collect DIR");
  if (int(options.plan) + int(!options.case_id.empty()) + int(options.collect_flag) > 1)
    throw InputError("suite: --plan, --case and --collect do not go together");
  Suite suite = load_suite(options.suite);
  if (!options.methods.empty()) suite.methods = check_methods(options.methods, "--methods");
  if (options.out.empty()) throw InputError("suite: give --out DIR");
  const std::string out = fs::absolute(options.out).lexically_normal().string();
  const std::string folder = out.size() > 1 && out.back() == '/' ? out.substr(0, out.size() - 1) : out;
  if (options.collect_flag) {
    check_out_folder(suite, folder);
    if (!fs::exists(folder)) throw InputError(folder + ": no such suite folder");
    write_index(suite, folder);
    return collect(folder, options.quiet);
  }
  if (!options.case_id.empty()) return run_one_case(suite, options, folder);
  if (options.plan) return plan(suite, options, folder);
  return run_all(suite, options, folder);
}

}  // namespace tsgraphs::app
