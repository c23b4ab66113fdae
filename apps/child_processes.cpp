// Child processes with signals forwarded (child_processes.hpp).
#include "child_processes.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace tsgraphs::app {

namespace {

// The handler's view of the children: slots hold a pid or 0. Lock-free atomics are safe to
// read in a signal handler.
std::atomic<pid_t> g_children[ChildProcesses::kMaxChildren];
std::atomic<int> g_signal{0};

extern "C" void forward_signal(int sig) {
  g_signal.store(sig);
  for (auto& slot : g_children) {
    const pid_t pid = slot.load();
    if (pid > 0) ::kill(pid, sig);
  }
}

/// Blocks SIGINT and SIGTERM while alive, so that a signal waits until the table is right.
class BlockSignals {
 public:
  BlockSignals() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigprocmask(SIG_BLOCK, &set, &old_);
  }
  ~BlockSignals() { sigprocmask(SIG_SETMASK, &old_, nullptr); }
  const sigset_t& old() const { return old_; }

 private:
  sigset_t old_;
};

}  // namespace

struct ChildProcesses::Saved {
  struct sigaction int_action {};
  struct sigaction term_action {};
};

ChildProcesses::ChildProcesses() : saved_(new Saved) {
  for (auto& slot : g_children) slot.store(0);
  g_signal.store(0);
  struct sigaction action {};
  action.sa_handler = forward_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: waitpid returns with EINTR and the loop looks again
  sigaction(SIGINT, &action, &saved_->int_action);
  sigaction(SIGTERM, &action, &saved_->term_action);
}

ChildProcesses::~ChildProcesses() {
  for (auto& slot : g_children) {
    const pid_t pid = slot.load();
    if (pid > 0) ::kill(pid, SIGTERM);
  }
  while (running() > 0) {
    if (!wait_any()) break;
  }
  sigaction(SIGINT, &saved_->int_action, nullptr);
  sigaction(SIGTERM, &saved_->term_action, nullptr);
  delete saved_;
}

pid_t ChildProcesses::start(const std::vector<std::string>& argv, const std::string& log) {
  if (argv.empty()) throw std::runtime_error("no program to start");
  // Everything the child needs is made before fork: after it, only async-signal-safe calls.
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  int free_slot = -1;
  for (int i = 0; i < kMaxChildren && free_slot < 0; ++i)
    if (g_children[i].load() == 0) free_slot = i;
  if (free_slot < 0)
    throw std::runtime_error("more than " + std::to_string(kMaxChildren) + " child processes");
  const pid_t parent = ::getpid();

  const BlockSignals block;
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl
    const int null_fd = ::open("/dev/null", O_RDONLY);
    const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    if (log_fd >= 0) {
      ::dup2(log_fd, STDOUT_FILENO);
      ::dup2(log_fd, STDERR_FILENO);
    }
    sigprocmask(SIG_SETMASK, &block.old(), nullptr);
    ::execv(args[0], args.data());
    constexpr const char kFailed[] = "tsgraphs: internal error: cannot start the case process\n";
    (void)!::write(STDERR_FILENO, kFailed, sizeof(kFailed) - 1);
    ::_exit(127);
  }
  g_children[free_slot].store(pid);
  // A signal that came meanwhile is delivered when `block` ends, now that the child is known.
  if (const int sig = g_signal.load(); sig != 0) ::kill(pid, sig);
  return pid;
}

std::optional<ChildProcesses::Exit> ChildProcesses::wait_any() {
  while (running() > 0) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;  // a signal: forwarded already; wait for them to end
      if (errno == ECHILD) {
        for (auto& slot : g_children) slot.store(0);
        return std::nullopt;
      }
      throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
    }
    for (auto& slot : g_children) {
      if (slot.load() == pid) {
        slot.store(0);
        return Exit{pid, status};
      }
    }
  }
  return std::nullopt;
}

int ChildProcesses::running() const {
  int n = 0;
  for (const auto& slot : g_children) n += slot.load() > 0 ? 1 : 0;
  return n;
}

int ChildProcesses::signal_received() { return g_signal.load(); }

std::string describe_wait_status(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    return "killed by signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : "");
  }
  return "ended with wait status " + std::to_string(status);
}

}  // namespace tsgraphs::app
