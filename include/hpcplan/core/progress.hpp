#pragma once
// Progress and time left for long sweeps, on stderr: one line rewritten in place, only when
// stderr is a terminal (so logs and CI output stay clean) unless HPCPLAN_PROGRESS=1 asks for
// it anyway (then one line per step, for files). The estimate assumes the remaining steps
// take as long as the finished ones on average.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "hpcplan/core/stopwatch.hpp"

namespace hpcplan {

class Progress {
 public:
  Progress(std::string what, std::size_t total)
      : what_(std::move(what)), total_(total), tty_(::isatty(STDERR_FILENO) == 1) {
    const char* forced = std::getenv("HPCPLAN_PROGRESS");
    enabled_ = tty_ || (forced != nullptr && std::string(forced) == "1");
  }
  ~Progress() {
    if (enabled_ && tty_ && done_ > 0) std::fputc('\n', stderr);
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Marks one more step done; `label` says which.
  void step(const std::string& label) {
    ++done_;
    if (!enabled_) return;
    const double elapsed = clock_.seconds();
    const double left = done_ < total_ ? elapsed / done_ * (total_ - done_) : 0.0;
    std::fprintf(stderr, "%s%s: %zu/%zu %s, %.0f s elapsed, ~%.0f s left%s", tty_ ? "\r" : "",
                 what_.c_str(), done_, total_, label.c_str(), elapsed, left,
                 tty_ ? "\033[K" : "\n");
    std::fflush(stderr);
  }

 private:
  std::string what_;
  std::size_t total_;
  std::size_t done_ = 0;
  bool tty_;
  bool enabled_ = false;
  Stopwatch clock_;
};

}  // namespace hpcplan
