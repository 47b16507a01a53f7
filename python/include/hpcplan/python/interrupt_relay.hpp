#pragma once
// Ctrl-C during a long call made from Python's main thread, with the call kept on that thread.
//
// Python runs its signal handlers on the main thread between bytecodes, never inside a C++
// call; a call that releases the GIL and works for minutes would otherwise see Ctrl-C only at
// its end. While run() runs a job, SIGINT's handler is one that wakes a relay thread (sem_post,
// safe in a handler) and then calls the handler it replaced: Python's, which records the signal
// for the KeyboardInterrupt the caller raises once the job is back. The relay thread, outside
// any signal, calls the job's `on_interrupt` (which stops the job through its stop token).
// Nothing else happens in the handler, and nothing leaves the main thread: no hand-off per call,
// and the thread's OpenMP team is the one it already has.
//
// The relay is installed only over a handler: where SIGINT's action is the default (end the
// process) or ignore, it is left as it is. Only SIGINT is relayed. The handler in place is
// restored when the job ends, however it ends.
//
// Threads: run() is for one thread at a time (Python's main thread); a run() inside a run()
// runs its job without a relay of its own. on_interrupt runs on the relay thread, possibly
// after run() has returned (a signal that arrived at the last moment): it must own what it
// uses. A forked child starts clean, even when forked during a run() on another thread: no run
// under way, SIGINT's handler given back, and a relay thread of its own at its first run().
#include <functional>

namespace hpcplan::python {

class InterruptRelay {
 public:
  // Runs `job` with SIGINT relayed to `on_interrupt`: called at least once for a job that a
  // SIGINT reached (signals close together may be relayed once), and never for a signal that
  // reached an earlier job, however late the relay thread wakes. An exception from the job
  // propagates once the handler is restored.
  static void run(const std::function<void()>& job, std::function<void()> on_interrupt);
};

}  // namespace hpcplan::python
