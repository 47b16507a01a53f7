#include "hpcplan/core/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace hpcplan::interrupt {

namespace {

// Lock-free, so that the handler may store to it (a plain sig_atomic_t would not be visible to
// other threads in order).
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void record(int signal) {
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);  // the first signal is the one reported
}

}  // namespace

void install() {
  static const bool installed = [] {
    struct sigaction action {};
    action.sa_handler = record;
    sigemptyset(&action.sa_mask);
    // SA_RESTART: system calls in flight (a file being written) carry on. SA_RESETHAND for
    // SIGTERM and Ctrl-C: the next one has its default action (the escape from a run that will
    // not stop). Not for SIGUSR1, which a job may well receive twice for one warning (from
    // SLURM directly and forwarded by mpirun or the batch shell): a second one is only a
    // repeat of the request.
    action.sa_flags = SA_RESTART;
    sigaction(SIGUSR1, &action, nullptr);
    action.sa_flags = SA_RESTART | SA_RESETHAND;
    for (const int s : {SIGTERM, SIGINT}) sigaction(s, &action, nullptr);
    return true;
  }();
  (void)installed;
}

int requested() {
  return g_signal.load(std::memory_order_relaxed);
}

const char* name(int signal) {
  switch (signal) {
    case SIGUSR1:
      return "SIGUSR1";
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    default:
      return "a signal";
  }
}

}  // namespace hpcplan::interrupt
