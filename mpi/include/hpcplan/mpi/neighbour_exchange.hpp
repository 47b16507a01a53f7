#pragma once
// The halo exchange of a chain of slabs: each rank swaps one byte buffer with the rank below
// and one with the rank above (either may be absent), as stencil codes swap their halo layers.
// Non-blocking: the sizes go first (one pair of Isend/Irecv per neighbour), then the data; a
// rank waits only for its own two neighbours, never for the whole job. Collective over the
// pairs: a rank that names r as its neighbour below is named by r as its neighbour above.
//
// Threads: one thread of each rank calls it (MPI_THREAD_FUNNELED).
#include <cstddef>
#include <span>
#include <vector>

#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/mpi/traffic.hpp"

namespace hpcplan::mpi {

class NeighbourExchange {
 public:
  explicit NeighbourExchange(const Communicator& comm) : comm_(comm) {}
  // below / above: neighbour ranks, or -1 for none.
  void exchange(int below, std::span<const std::byte> to_below, int above,
                std::span<const std::byte> to_above, std::vector<std::byte>& from_below,
                std::vector<std::byte>& from_above);
  const Traffic& traffic() const { return traffic_; }

 private:
  const Communicator& comm_;
  Traffic traffic_;
};

}  // namespace hpcplan::mpi
