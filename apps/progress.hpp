#pragma once
/// Progress for long commands: a bar on a terminal, plain lines otherwise, nothing if quiet.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace tsgraphs::app {

class Progress {
 public:
  Progress(std::string what, bool quiet)
      : what_(std::move(what)), quiet_(quiet), tty_(::isatty(STDERR_FILENO)), start_(Clock::now()) {}

  void update(std::size_t done, std::size_t total) {
    if (quiet_ || total == 0) return;
    const double secs = std::chrono::duration<double>(Clock::now() - start_).count();
    const double rate = secs > 0.0 ? done / secs : 0.0;
    const int percent = static_cast<int>(100.0 * done / total);
    if (tty_) {
      constexpr int kWidth = 30;
      const int filled = kWidth * static_cast<int>(done) / static_cast<int>(total);
      std::fprintf(stderr, "\r%s [%s%s] %3d%% %zu/%zu  %.0f/s  ETA %.0fs ", what_.c_str(),
                   std::string(filled, '#').c_str(), std::string(kWidth - filled, ' ').c_str(), percent, done,
                   total, rate, rate > 0.0 ? (total - done) / rate : 0.0);
      if (done == total) std::fprintf(stderr, "\n");
    } else if (percent / 10 != last_decile_ || done == total) {
      last_decile_ = percent / 10;
      std::fprintf(stderr, "%s: %zu/%zu (%d%%), %.0f/s\n", what_.c_str(), done, total, percent, rate);
    }
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_;
  bool quiet_;
  bool tty_;
  Clock::time_point start_;
  int last_decile_ = -1;
};

}  // namespace tsgraphs::app
