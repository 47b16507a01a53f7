#pragma once
// What the dense engine needs from the ranks around it, and nothing more: each rank holds
// blocks of the lattice, so a level (or a bucket of cost classes) ends with one exchange with
// the ranks holding the blocks next to its own (its peers: two for slabs along the last axis,
// more for blocks cut over several axes) and one small reduction over all. The engine never
// calls MPI; the MPI implementation lives in the distributed layer (as Graph500's reference
// BFS keeps its communication apart from the algorithm), and LocalTransport is the one-rank
// case, which is the serial engine.
//
// Threads: called from one thread of each rank (the engine's master thread), collectively:
// every rank makes the same calls in the same order.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace hpcplan::dense {

class SlabTransport {
 public:
  virtual ~SlabTransport() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // Ranks sharing this rank's node (they share its memory budget).
  virtual int ranks_on_node() const { return 1; }
  // Sends to[i] to rank peers[i] and returns in from[i] what that rank sent this one (resized
  // to peers.size()). Peers are distinct ranks other than this one, and the relation is
  // symmetric: a rank that names r is named by r in the same exchange.
  virtual void exchange(std::span<const int> peers, const std::vector<std::vector<std::byte>>& to,
                        std::vector<std::vector<std::byte>>& from) = 0;
  // Element-wise over all ranks, in place.
  virtual void sum(std::span<std::uint64_t> values) = 0;
  virtual void max(std::span<std::uint64_t> values) = 0;
  virtual void min(std::span<double> values) = 0;
  // Gathers `bytes` bytes from every rank on every rank (rank order).
  virtual std::vector<std::byte> allgather(std::span<const std::byte> mine) = 0;
  // Every rank's bytes on rank 0, one vector per rank in rank order (empty on the other
  // ranks): the per-rank parts of a result only rank 0 writes (a distance field). Any size.
  // This default goes through allgather (every rank receives everything, under 2 GiB in all);
  // a transport overrides it with a real gather.
  virtual std::vector<std::vector<std::byte>> gather_to_root(std::span<const std::byte> mine) {
    const std::uint64_t n = mine.size();
    const std::vector<std::byte> sizes =
        allgather(std::as_bytes(std::span<const std::uint64_t>(&n, 1)));
    const std::vector<std::byte> all = allgather(mine);
    std::vector<std::vector<std::byte>> out;
    if (rank() != 0) return out;
    std::size_t at = 0;
    for (std::size_t r = 0; r * sizeof n < sizes.size(); ++r) {
      std::uint64_t k = 0;
      std::memcpy(&k, sizes.data() + r * sizeof n, sizeof k);
      out.emplace_back(all.begin() + static_cast<std::ptrdiff_t>(at),
                       all.begin() + static_cast<std::ptrdiff_t>(at + k));
      at += k;
    }
    return out;
  }

  // What the exchanges cost this rank.
  std::uint64_t messages_sent = 0;
  std::uint64_t bytes_sent = 0;
  double exchange_ms = 0.0;  // inside exchange() and the reductions
};

// One rank: nothing to exchange, reductions are the identity.
class LocalTransport final : public SlabTransport {
 public:
  int rank() const override { return 0; }
  int ranks() const override { return 1; }
  void exchange(std::span<const int> peers, const std::vector<std::vector<std::byte>>&,
                std::vector<std::vector<std::byte>>& from) override {
    from.assign(peers.size(), {});
  }
  void sum(std::span<std::uint64_t>) override {}
  void max(std::span<std::uint64_t>) override {}
  void min(std::span<double>) override {}
  std::vector<std::byte> allgather(std::span<const std::byte> mine) override {
    return {mine.begin(), mine.end()};
  }
  std::vector<std::vector<std::byte>> gather_to_root(std::span<const std::byte> mine) override {
    return {std::vector<std::byte>(mine.begin(), mine.end())};
  }
};

}  // namespace hpcplan::dense
