#include "hpcplan/python/interrupt_relay.hpp"

#include <errno.h>
#include <pthread.h>
#include <semaphore.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <new>
#include <thread>

namespace hpcplan::python {

namespace {

// The relay's state, process-wide (a signal handler has no other way to reach it). Never
// destroyed: the relay thread may be blocked in sem_wait while static objects are torn down.
struct Relay {
  sem_t wake;
  sem_t started;  // posted once by a new relay thread, from its own loop
  std::mutex m;
  std::function<void()> current;  // the job's on_interrupt, while a job runs
  std::uint64_t current_run = 0;  // that job's run number (under m)
  // Run numbers: each run() takes the next; `running` is the one under way (0: none), and
  // `signalled` the one the latest SIGINT arrived during (0: none since the relay last looked).
  // The relay calls on_interrupt only when the signalled run is the current one: a relay thread
  // that woke late otherwise stopped the next call for a Ctrl-C that reached the one before.
  std::uint64_t runs = 0;
  std::atomic<std::uint64_t> running{0};
  std::atomic<std::uint64_t> signalled{0};
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free);  // read in the handler
  pid_t owner = 0;                // the process whose relay thread exists
  std::atomic<bool> busy{false};  // a run() is under way
  bool installed = false;         // the relay's handler is SIGINT's (during a run)
  struct sigaction replaced {};   // SIGINT's action before the relay (read by the handler)
};

// In a child forked while a run() was under way on another thread (os.fork() from a second
// Python thread): that run does not go on in the child, and its relay thread is not there. The
// child starts clean: SIGINT's handler given back, the run forgotten (busy would otherwise keep
// every later run from relaying), the mutex rebuilt (a thread that is not in the child may
// have held it), and no relay thread, so the child's first run() starts one.
extern "C" void relay_after_fork_in_child();

Relay& relay() {
  static Relay* r = [] {
    auto* made = new Relay;
    pthread_atfork(nullptr, nullptr, relay_after_fork_in_child);
    return made;
  }();
  return *r;
}

extern "C" void relay_after_fork_in_child() {
  Relay& r = relay();
  if (r.installed) sigaction(SIGINT, &r.replaced, nullptr);
  r.installed = false;
  new (&r.m) std::mutex;
  r.current = nullptr;
  r.current_run = 0;
  r.running = 0;
  r.signalled = 0;
  r.busy = false;
  r.owner = 0;
}

void relay_loop(Relay* r) {
  sem_post(&r->started);
  for (;;) {
    while (sem_wait(&r->wake) != 0 && errno == EINTR) {
    }
    const std::uint64_t run = r->signalled.exchange(0);
    std::function<void()> interrupt;
    {
      std::lock_guard lock(r->m);
      if (run != 0 && run == r->current_run) interrupt = r->current;
    }
    if (interrupt) interrupt();
  }
}

// A relay thread for this process: started at the first run(), and again in a forked child
// (threads do not survive fork()), with every asynchronous signal blocked so that none is ever
// delivered to it. Returns once the thread runs its loop: under ThreadSanitizer, a SIGINT that
// reached the process while a new thread was still starting was lost before any handler ran
// (25 of 200 tries of a 20-line program with no hpcplan code; none once the thread had
// started), and the first job's Ctrl-C was exactly such a signal.
void ensure_relay_thread(Relay& r) {
  if (r.owner == getpid()) return;
  sem_init(&r.wake, 0, 0);
  sem_init(&r.started, 0, 0);
  sigset_t all, previous;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &previous);
  try {
    std::thread(relay_loop, &r).detach();
  } catch (...) {  // no thread (a process at its limit): the caller's signals as they were
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
    throw;
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  while (sem_wait(&r.started) != 0 && errno == EINTR) {
  }
  r.owner = getpid();
}

extern "C" void relay_sigint(int signal, siginfo_t* info, void* context) {
  const int saved = errno;
  Relay& r = relay();
  if (const std::uint64_t run = r.running.load(); run != 0) r.signalled.store(run);
  sem_post(&r.wake);
  const struct sigaction& next = r.replaced;
  if (next.sa_flags & SA_SIGINFO)
    next.sa_sigaction(signal, info, context);
  else if (next.sa_handler != SIG_DFL && next.sa_handler != SIG_IGN)
    next.sa_handler(signal);
  errno = saved;
}

}  // namespace

void InterruptRelay::run(const std::function<void()>& job, std::function<void()> on_interrupt) {
  Relay& r = relay();
  if (r.busy.exchange(true)) {  // a run() inside a run(): the outer one relays
    job();
    return;
  }
  struct Done {
    Relay& r;
    ~Done() {
      if (r.installed) {
        sigaction(SIGINT, &r.replaced, nullptr);
        r.installed = false;
      }
      r.running = 0;
      {
        std::lock_guard lock(r.m);
        r.current = nullptr;
        r.current_run = 0;
      }
      r.busy = false;
    }
  } done{r};
  struct sigaction now {};
  sigaction(SIGINT, nullptr, &now);
  const bool handler =
      (now.sa_flags & SA_SIGINFO) || (now.sa_handler != SIG_DFL && now.sa_handler != SIG_IGN);
  if (handler) {
    ensure_relay_thread(r);
    const std::uint64_t run = ++r.runs;  // run() is for one thread at a time (busy)
    {
      std::lock_guard lock(r.m);
      r.current = std::move(on_interrupt);
      r.current_run = run;
    }
    r.running = run;
    r.replaced = now;
    struct sigaction ours {};
    ours.sa_sigaction = relay_sigint;
    ours.sa_flags = SA_SIGINFO | SA_RESTART;  // the job's system calls go on, not EINTR
    sigemptyset(&ours.sa_mask);
    sigaction(SIGINT, &ours, nullptr);
    r.installed = true;
  }
  job();
}

}  // namespace hpcplan::python
