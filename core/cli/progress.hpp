// A progress line on stderr for long jobs: "[#####.....] 12/50 units, 3.2 s, ETA 10 s".
// Redrawn in place on a terminal, one line per 10 % otherwise (logs stay readable).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace plumage::cli {

class Progress {
 public:
  Progress(std::string what, std::size_t total, bool quiet)
      : what_(std::move(what)), total_(total), quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0),
        start_(std::chrono::steady_clock::now()) {}

  // eta_s: the caller's own estimate of the remaining time, for jobs whose units differ in cost
  // (negative: extrapolate from the mean time per unit so far).
  void advance(std::size_t done, double eta_s = -1.0) {
    if (quiet_ || total_ == 0) return;
    const int tenth = static_cast<int>(10 * done / total_);
    if (!tty_ && tenth == last_tenth_ && done != total_) return;
    last_tenth_ = tenth;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = eta_s >= 0.0 ? eta_s
                       : done      ? elapsed * static_cast<double>(total_ - done) / static_cast<double>(done)
                                   : 0.0;
    const int width = 30;
    const int filled = static_cast<int>(width * done / total_);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "%s[%s] %zu/%zu %s, %.1f s, ETA %.1f s%s", tty_ ? "\r" : "", bar.c_str(),
                 done, total_, what_.c_str(), elapsed, eta, tty_ && done != total_ ? "" : "\n");
    std::fflush(stderr);
  }

 private:
  std::string what_;
  std::size_t total_;
  bool quiet_, tty_;
  int last_tenth_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace plumage::cli
