#pragma once
// OMPL's termination condition is a predicate to evaluate; hpcplan's loops poll a Stop (a stop
// token). This maps one onto the other: a watcher thread evaluates the predicate every
// millisecond and triggers the token, so a search ends within about a millisecond of the
// condition turning true. The watcher ends with this object, at once: it waits on its stop
// token, not in a sleep (a plain 1 ms sleep added up to 1 ms to every short solve).
//
// Threads: the predicate is evaluated on the watcher thread (OMPL's conditions are made to be
// evaluated from several threads); one object per run.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stop_token>
#include <thread>

#include <ompl/base/PlannerTerminationCondition.h>

namespace hpcplan::sampling {

class PtcStopSource {
 public:
  explicit PtcStopSource(const ompl::base::PlannerTerminationCondition& ptc)
      : watcher_([this, &ptc](std::stop_token run_over) {
          std::mutex m;
          std::condition_variable_any wake;  // woken by run_over: the run's end joins at once
          std::unique_lock lock(m);
          while (!run_over.stop_requested()) {
            if (ptc()) {
              fired_.request_stop();
              return;
            }
            wake.wait_for(lock, run_over, std::chrono::milliseconds(1), [] { return false; });
          }
        }) {}
  PtcStopSource(const PtcStopSource&) = delete;
  PtcStopSource& operator=(const PtcStopSource&) = delete;

  std::stop_token token() const { return fired_.get_token(); }

 private:
  std::stop_source fired_;  // declared before the watcher, which uses it
  std::jthread watcher_;
};

}  // namespace hpcplan::sampling
