#pragma once
/// Child processes for `suite --jobs N`: started with fork and exec, their stdout and stderr
/// appended to a log file, reaped with waitpid. While an instance lives, SIGINT and SIGTERM
/// are forwarded to the children (and remembered), and a child dies with its parent
/// (PR_SET_PDEATHSIG), so that Ctrl-C or a kill leaves no orphan running.
#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace tsgraphs::app {

class ChildProcesses {
 public:
  /// Most children at once: the signal handler's table is fixed (it may not allocate).
  static constexpr int kMaxChildren = 256;

  ChildProcesses();
  /// Terminates the children still running, reaps them and restores the signal handlers.
  ~ChildProcesses();
  ChildProcesses(const ChildProcesses&) = delete;
  ChildProcesses& operator=(const ChildProcesses&) = delete;

  /// Starts argv[0] (a path) with `argv`, stdin from /dev/null, stdout and stderr appended to
  /// `log`. Throws std::runtime_error when it cannot fork or the table is full.
  pid_t start(const std::vector<std::string>& argv, const std::string& log);

  struct Exit {
    pid_t pid = 0;
    int status = 0;  ///< the wait status (WIFEXITED, WEXITSTATUS, WIFSIGNALED, WTERMSIG)
  };
  /// Waits for a child to end; none when no child is running.
  std::optional<Exit> wait_any();

  int running() const;
  /// The SIGINT or SIGTERM that arrived, 0 for none.
  static int signal_received();

 private:
  struct Saved;
  Saved* saved_;
};

/// "exit status 3", "killed by signal 9 (Killed)".
std::string describe_wait_status(int status);

}  // namespace tsgraphs::app
