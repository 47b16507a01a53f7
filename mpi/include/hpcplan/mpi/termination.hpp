#pragma once
// Distributed termination detection by Mattern's four-counter method, run as a sequence of
// non-blocking all-reduce "waves". A rank joins a wave only while passive (nothing to do
// locally, all its messages handed to MPI) and contributes its counts of messages sent and
// received-and-processed so far. Each wave completes only after every rank has joined it,
// so every contribution to wave k precedes every contribution to wave k+1: between them
// lies a cut time t. If the total received in wave k equals the total sent in wave k+1,
// then (counts being monotone) sent(t) <= S(k+1) = R(k) <= received(t) <= sent(t): nothing
// was in flight at t and no rank received anything between its wave-k snapshot (taken while
// passive) and t, so every rank was still passive at t. A passive rank becomes active only
// by receiving, so the computation had ended at t, and all ranks see the same sums and stop
// after the same wave.
#include <mpi.h>

#include <array>
#include <cstdint>

#include "hpcplan/mpi/communicator.hpp"

namespace hpcplan::mpi {

class TerminationDetector {
 public:
  explicit TerminationDetector(const Communicator& comm) : comm_(comm.handle()) {}
  ~TerminationDetector();
  TerminationDetector(const TerminationDetector&) = delete;
  TerminationDetector& operator=(const TerminationDetector&) = delete;

  // Progresses the current wave; when `passive` and no wave is pending, joins the next one
  // with these counts. Returns true once termination is proven (the same wave on all ranks).
  bool poll(bool passive, std::uint64_t sent, std::uint64_t received);

  std::uint64_t waves() const { return waves_; }

 private:
  MPI_Comm comm_;
  MPI_Request request_ = MPI_REQUEST_NULL;
  bool pending_ = false;
  bool have_previous_ = false;
  std::uint64_t previous_received_ = 0;
  std::array<std::uint64_t, 2> in_{};   // sent, received
  std::array<std::uint64_t, 2> out_{};  // their sums over all ranks
  std::uint64_t waves_ = 0;
};

}  // namespace hpcplan::mpi
