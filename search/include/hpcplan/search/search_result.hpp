#pragma once
#include <cstdint>
#include <vector>

#include "hpcplan/core/result.hpp"
#include "hpcplan/core/status.hpp"

namespace hpcplan::search {

using hpcplan::Status;
using hpcplan::to_string;

using hpcplan::Counters;

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
using Result = hpcplan::Result<State>;

}  // namespace hpcplan::search
