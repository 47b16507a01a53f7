#pragma once
// What every planner returns: how it ended, the path, its cost, and what it took. The lattice
// and grid searches, the tree planners, OMPL's planners, the world planners (plan_in_world)
// and the GOG grid planner (GridReport) all answer with a Result of their point type, so
// io formats one shape and the simulator can take any planner's answer.
#include <cstdint>
#include <vector>

#include "hpcplan/core/status.hpp"

namespace hpcplan {

struct Counters {
  std::uint64_t expanded = 0;          // states taken off the frontier and expanded
  std::uint64_t generated = 0;         // legal successors produced by the graph
  std::uint64_t reopened = 0;          // closed states improved and expanded again
  std::uint64_t collision_checks = 0;  // validity evaluations made by this run
  std::uint64_t peak_states = 0;       // most states stored (searches) or tree vertices
  std::uint64_t peak_open = 0;         // largest frontier
  std::uint64_t samples = 0;           // sampling planners: samples drawn
  double time_ms = 0.0;                // the run, excluding problem set-up
  double first_solution_ms = -1.0;     // anytime planners: when the first path appeared
  double first_cost = -1.0;            // ... and its cost
};

template <class Point>
struct Result {
  Status status = Status::no_path;
  std::vector<Point> path;  // start..goal when solved, empty otherwise
  double cost = 0.0;        // length of `path`, re-validated
  std::uint64_t hops = 0;   // segments of `path`
  Counters counters;
};

}  // namespace hpcplan
