#pragma once
// The dense engine's slab transport over MPI: the halo exchange with the peer ranks
// (mpi::NeighbourExchange) and the per-level reductions on the communicator. The dense engine
// itself never sees MPI.
//
// Threads: used from the engine's master thread of each rank (MPI_THREAD_FUNNELED).
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/dense/slab_transport.hpp"
#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/mpi/neighbour_exchange.hpp"

namespace hpcplan::distributed {

class MpiSlabTransport final : public dense::SlabTransport {
 public:
  explicit MpiSlabTransport(const mpi::Communicator& comm) : comm_(comm), halo_(comm) {}
  int rank() const override { return comm_.rank(); }
  int ranks() const override { return comm_.size(); }
  int ranks_on_node() const override { return comm_.ranks_on_node(); }
  void exchange(std::span<const int> peers, const std::vector<std::vector<std::byte>>& to,
                std::vector<std::vector<std::byte>>& from) override {
    const Stopwatch clock;
    halo_.exchange(peers, to, from);
    messages_sent = halo_.traffic().messages_sent;
    bytes_sent = halo_.traffic().bytes_sent;
    exchange_ms += clock.milliseconds();
  }
  void sum(std::span<std::uint64_t> v) override {
    timed([&] { comm_.allreduce_sum(v); });
  }
  void max(std::span<std::uint64_t> v) override {
    timed([&] { comm_.allreduce_max(v); });
  }
  void min(std::span<double> v) override {
    timed([&] { comm_.allreduce_min(v); });
  }
  std::vector<std::byte> allgather(std::span<const std::byte> mine) override {
    return comm_.allgather(mine);
  }
  // MPI_Gather of the sizes, then each rank's bytes to rank 0 in messages under 1 GiB.
  std::vector<std::vector<std::byte>> gather_to_root(std::span<const std::byte> mine) override;

 private:
  template <class F>
  void timed(F&& f) {
    const Stopwatch clock;
    f();
    exchange_ms += clock.milliseconds();
  }
  const mpi::Communicator& comm_;
  mpi::NeighbourExchange halo_;
};

}  // namespace hpcplan::distributed
