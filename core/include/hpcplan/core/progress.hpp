#pragma once
// Progress and time left for long sweeps, on stderr: one line rewritten in place, only when
// stderr is a terminal (so logs and CI output stay clean) unless HPCPLAN_PROGRESS=1 asks for
// it anyway (then one line per step, for files). The estimate assumes the remaining steps
// take as long as the finished ones on average.
#include <unistd.h>

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "hpcplan/core/stopwatch.hpp"

namespace hpcplan {

// Progress is shown on a terminal, or anywhere when HPCPLAN_PROGRESS=1 asks for it.
inline bool progress_wanted(bool tty) {
  const char* forced = std::getenv("HPCPLAN_PROGRESS");
  return tty || (forced != nullptr && std::string(forced) == "1");
}

class Progress {
 public:
  Progress(std::string what, std::size_t total)
      : what_(std::move(what)),
        total_(total),
        tty_(::isatty(STDERR_FILENO) == 1),
        enabled_(progress_wanted(tty_)) {}
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
  bool enabled_;
  Stopwatch clock_;
};

// A long single run (one search): after `quiet_s` seconds, at most once a second, one line with
// the states stored against the budget, the rate and the elapsed time. Shown under the same
// rule as Progress (a terminal, or HPCPLAN_PROGRESS=1); silent runs cost one clock read per
// call, and calls come every 65,536 expansions.
class RunProgress {
 public:
  RunProgress(std::string what, std::uint64_t budget, double quiet_s = 2.0)
      : what_(std::move(what)),
        budget_(budget),
        quiet_s_(quiet_s),
        tty_(::isatty(STDERR_FILENO) == 1),
        enabled_(progress_wanted(tty_)) {}
  ~RunProgress() {
    if (shown_ && tty_) std::fputc('\n', stderr);
  }
  RunProgress(const RunProgress&) = delete;
  RunProgress& operator=(const RunProgress&) = delete;

  void update(std::uint64_t expanded, std::uint64_t stored) {
    if (!enabled_) return;
    const double t = clock_.seconds();
    if (t < quiet_s_ || t < last_ + 1.0) return;
    last_ = t;
    shown_ = true;
    std::fprintf(stderr,
                 "%s%s: %.0f s, %.3gM states stored of %.3gM budget (%.1f%%), %.3gM expanded "
                 "(%.3gM/s)%s",
                 tty_ ? "\r" : "", what_.c_str(), t, stored / 1e6, budget_ / 1e6,
                 budget_ ? 100.0 * stored / budget_ : 0.0, expanded / 1e6, expanded / 1e6 / t,
                 tty_ ? "\033[K" : "\n");
    std::fflush(stderr);
  }

 private:
  std::string what_;
  std::uint64_t budget_;
  double quiet_s_;
  bool tty_;
  bool enabled_;
  bool shown_ = false;
  double last_ = 0.0;
  Stopwatch clock_;
};

// One progress line, rewritten in place on a terminal (a line per call otherwise), under the
// same rule as Progress. The caller decides when to show it.
class ProgressLine {
 public:
  ProgressLine() : tty_(::isatty(STDERR_FILENO) == 1), enabled_(progress_wanted(tty_)) {}
  ~ProgressLine() {
    if (shown_ && tty_) std::fputc('\n', stderr);
  }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  bool enabled() const { return enabled_; }

  [[gnu::format(printf, 2, 3)]] void show(const char* format, ...) {
    if (!enabled_) return;
    shown_ = true;
    if (tty_) std::fputc('\r', stderr);
    va_list args;
    va_start(args, format);
    std::vfprintf(stderr, format, args);
    va_end(args);
    std::fputs(tty_ ? "\033[K" : "\n", stderr);
    std::fflush(stderr);
  }

 private:
  bool tty_;
  bool enabled_;
  bool shown_ = false;
};

}  // namespace hpcplan
