#pragma once
// Runs a job on a thread of its own while the calling thread polls. The Python module's long
// calls made from Python's main thread use it: the main thread is the only one on which
// Python runs its signal handlers (Ctrl-C's KeyboardInterrupt), so it must stay free to do so
// while the engine works; the poll runs them and, when one raises, stops the job through its
// stop token.
//
// The worker keeps its thread between jobs, so the OpenMP team that thread starts is made
// once, not at every call. It blocks the asynchronous signals (SIGINT, SIGTERM, SIGUSR1,
// SIGUSR2, SIGHUP, SIGQUIT, SIGALRM), so that they are delivered to the caller's threads, never
// in the middle of the engine.
//
// Threads: run() may be called from any thread; jobs are served one at a time (a second
// caller waits until the first's job has ended). A process forked while the worker exists
// has no worker thread: the first run() in the child starts a new one.
#include <sys/types.h>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace hpcplan::python {

class PolledWorker {
 public:
  PolledWorker() = default;
  PolledWorker(const PolledWorker&) = delete;
  PolledWorker& operator=(const PolledWorker&) = delete;
  ~PolledWorker();  // waits for the job under way, then ends the thread

  // Runs `job` on the worker thread and, until it ends, calls `poll` on this thread once every
  // `interval`. Returns when the job has ended; an exception the job threw is rethrown here
  // (an exception from `poll` is thrown once the job has ended).
  void run(const std::function<void()>& job, const std::function<void()>& poll,
           std::chrono::milliseconds interval);

 private:
  void start();
  void loop();

  std::mutex callers_;  // one job at a time
  std::mutex m_;
  std::condition_variable wake_, done_;
  const std::function<void()>* job_ = nullptr;
  bool finished_ = false, quit_ = false;
  std::exception_ptr error_;
  std::unique_ptr<std::thread> thread_;
  pid_t owner_ = 0;  // the process that started thread_
};

}  // namespace hpcplan::python
