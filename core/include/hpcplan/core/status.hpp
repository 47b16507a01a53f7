#pragma once
// How a planning run ended. Every planner in hpcplan (lattice searches, continuous-world
// searches, tree planners, OMPL planners, the distributed search) answers with one of these;
// each is an answer (exit 0 on the command line), not a failure.
#include <string_view>

namespace hpcplan {

enum class Status {
  solved,   // a path was found and re-validated
  no_path,  // proved: the reachable set was exhausted (or, for sampling planners: none found)
  budget_exceeded,  // the state budget ran out first
  timeout,          // the deadline passed first
  cancelled,        // another thread asked the run to stop
  interrupted,      // a signal (SLURM's warning, SIGTERM, Ctrl-C) ended it at a safe boundary
                    // after its checkpoint was written; --restart continues it
};

constexpr std::string_view to_string(Status s) {
  switch (s) {
    case Status::solved:
      return "solved";
    case Status::no_path:
      return "no_path";
    case Status::budget_exceeded:
      return "budget_exceeded";
    case Status::timeout:
      return "timeout";
    case Status::cancelled:
      return "cancelled";
    case Status::interrupted:
      return "interrupted";
  }
  return "unknown";
}

}  // namespace hpcplan
