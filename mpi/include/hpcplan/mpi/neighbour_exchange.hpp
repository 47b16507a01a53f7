#pragma once
// The halo exchange of a decomposed lattice: each rank swaps one byte buffer with each of its
// neighbours (the ranks holding blocks next to its own: the rank below and the rank above for
// a chain of slabs, more for blocks cut over several axes), as stencil codes swap their halo
// faces. Non-blocking: the sizes go first (one pair of Isend/Irecv per neighbour), then the
// data; a rank waits only for its own neighbours, never for the whole job. Collective over the
// pairs: a rank that names r as a neighbour is named by r, once.
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
  // Sends to[i] to peers[i]; from[i] receives what peers[i] sent (resized to peers.size()).
  void exchange(std::span<const int> peers, const std::vector<std::vector<std::byte>>& to,
                std::vector<std::vector<std::byte>>& from);
  const Traffic& traffic() const { return traffic_; }

 private:
  const Communicator& comm_;
  Traffic traffic_;
};

}  // namespace hpcplan::mpi
