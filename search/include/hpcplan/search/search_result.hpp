#pragma once
#include <cstdint>
#include <vector>

#include "hpcplan/core/status.hpp"

namespace hpcplan::search {

using hpcplan::Status;
using hpcplan::to_string;

struct Counters {
  std::uint64_t expanded = 0;          // states taken off the frontier and expanded
  std::uint64_t generated = 0;         // legal successors produced by the graph
  std::uint64_t reopened = 0;          // closed states improved and expanded again
  std::uint64_t collision_checks = 0;  // validity evaluations made by the graph
  std::uint64_t peak_states = 0;       // most states stored in the visited map
  std::uint64_t peak_open = 0;         // largest frontier
  double time_ms = 0.0;                // search time, excluding field set-up
};

// One rank's share of a distributed search (plain data so ranks can gather it as bytes).
struct RankCounters {
  std::uint64_t expanded = 0;
  std::uint64_t generated = 0;
  std::uint64_t collision_checks = 0;
  std::uint64_t states_stored = 0;  // states this rank owns and stored
  std::uint64_t peak_open = 0;
  std::uint64_t reopened = 0;
  std::uint64_t messages_sent = 0;  // MPI messages (batches of records), control included
  std::uint64_t messages_received = 0;
  std::uint64_t bytes_sent = 0;
  std::uint64_t bytes_received = 0;
  std::uint64_t records_sent = 0;  // states handed to their owners on other ranks
  std::uint64_t records_received = 0;
  std::uint64_t records_filtered = 0;  // duplicates not sent (already sent at no higher cost)
  std::uint64_t sync_rounds = 0;       // termination waves (async) or exchanges (synchronous)
  double wait_ms = 0.0;  // idle (async) or inside exchanges and reductions (synchronous)
  double search_ms = 0.0;
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
