#pragma once
#include <cstdint>
#include <string_view>
#include <vector>

namespace hpcplan::search {

enum class Status { solved, no_path, budget_exceeded, timeout };

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
  }
  return "unknown";
}

struct Counters {
  std::uint64_t expanded = 0;          // states taken off the frontier and expanded
  std::uint64_t generated = 0;         // legal successors produced by the graph
  std::uint64_t reopened = 0;          // closed states improved and expanded again
  std::uint64_t collision_checks = 0;  // validity evaluations made by the graph
  std::uint64_t peak_states = 0;       // most states stored in the visited map
  std::uint64_t peak_open = 0;         // largest frontier
  double time_ms = 0.0;                // search time, excluding field set-up
};

template <class State>
struct Result {
  Status status = Status::no_path;
  std::vector<State> path;  // start..goal when solved
  double cost = 0.0;        // sum of re-validated move lengths along `path`
  std::uint64_t hops = 0;
  Counters counters;
};

}  // namespace hpcplan::search
