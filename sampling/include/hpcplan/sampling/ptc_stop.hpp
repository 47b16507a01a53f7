#pragma once
// OMPL's termination condition is a predicate to evaluate; hpcplan's loops poll a Stop. This
// makes the one a condition of the other, evaluated by the loop itself every 64th poll. (It used
// to be a watcher thread that triggered a stop token; starting and joining that thread cost a
// 2D query more than its search.)
//
// Threads: the predicate is evaluated on the thread running the loop, the one OMPL called
// solve() on; the condition must outlive the run.
#include <ompl/base/PlannerTerminationCondition.h>

#include "hpcplan/core/stop.hpp"

namespace hpcplan::sampling {

inline Stop stop_on(const ompl::base::PlannerTerminationCondition& ptc) {
  return Stop().also_when([&ptc] { return ptc(); });
}

}  // namespace hpcplan::sampling
