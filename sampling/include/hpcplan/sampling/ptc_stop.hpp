#pragma once
// OMPL's termination condition is a predicate to evaluate; hpcplan's loops poll a Stop (a stop
// token). This maps one onto the other: a watcher thread evaluates the predicate every
// millisecond and triggers the token, so a search ends within about a millisecond of the
// condition turning true. The watcher ends with this object.
//
// Threads: the predicate is evaluated on the watcher thread (OMPL's conditions are made to be
// evaluated from several threads); one object per run.
#include <chrono>
#include <stop_token>
#include <thread>

#include <ompl/base/PlannerTerminationCondition.h>

namespace hpcplan::sampling {

class PtcStopSource {
 public:
  explicit PtcStopSource(const ompl::base::PlannerTerminationCondition& ptc)
      : watcher_([this, &ptc](std::stop_token run_over) {
          while (!run_over.stop_requested()) {
            if (ptc()) {
              fired_.request_stop();
              return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
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
