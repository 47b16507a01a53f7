#pragma once
// Ranks of the dense engine as threads of one process: P std::threads each run dense::search
// with their own InProcessTransport over one shared InProcessRanks hub, so the engine's rank
// protocol (halo exchanges with the neighbouring slabs, reductions, gathers) runs under
// ThreadSanitizer and in the unit suite without mpirun. Every collective is a deposit into the
// caller's slot, a barrier, a read of the other slots, and a second barrier (so no slot is
// written again before every rank has read it): the same ordering MPI's collectives give.
//
// Threads: one InProcessTransport per rank thread; the hub is shared by all of them.
#include <algorithm>
#include <barrier>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "hpcplan/dense/slab_transport.hpp"

namespace hpcplan::test_support {

class InProcessRanks {
 public:
  explicit InProcessRanks(int ranks)
      : ranks_(ranks), sync_(ranks), out_(ranks), sent_(ranks), named_(ranks) {}
  int ranks() const { return ranks_; }

  // Runs body(rank) on `ranks` threads at once and joins them. An exception on any rank thread
  // would leave the others waiting at a barrier, so bodies must catch their own.
  void run(const std::function<void(int)>& body) {
    std::vector<std::thread> threads;
    for (int r = 0; r < ranks_; ++r) threads.emplace_back(body, r);
    for (auto& t : threads) t.join();
  }

 private:
  friend class InProcessTransport;
  int ranks_;
  std::barrier<> sync_;
  std::vector<std::vector<std::byte>> out_;  // per rank: its allgather contribution
  // Per rank: what it sends each rank (by rank), and the peers it named in the exchange.
  std::vector<std::vector<std::vector<std::byte>>> sent_;
  std::vector<std::vector<int>> named_;
};

class InProcessTransport final : public dense::SlabTransport {
 public:
  InProcessTransport(InProcessRanks& hub, int rank) : hub_(hub), rank_(rank) {}
  int rank() const override { return rank_; }
  int ranks() const override { return hub_.ranks_; }
  int ranks_on_node() const override { return hub_.ranks_; }

  // Each peer's buffer; a rank receives only from the peers it names, and each of them must
  // name it back (a one-sided pair is the engine's bug, and fails the test).
  void exchange(std::span<const int> peers, const std::vector<std::vector<std::byte>>& to,
                std::vector<std::vector<std::byte>>& from) override {
    auto& mine = hub_.sent_[rank_];
    mine.assign(hub_.ranks_, {});
    for (std::size_t i = 0; i < peers.size(); ++i) {
      mine[peers[i]] = to[i];
      if (!to[i].empty()) {
        ++messages_sent;
        bytes_sent += to[i].size();
      }
    }
    hub_.named_[rank_].assign(peers.begin(), peers.end());
    hub_.sync_.arrive_and_wait();
    from.assign(peers.size(), {});
    int one_sided = -1;
    for (std::size_t i = 0; i < peers.size(); ++i) {
      const auto& theirs = hub_.named_[peers[i]];
      if (std::find(theirs.begin(), theirs.end(), rank_) == theirs.end()) one_sided = peers[i];
      from[i] = hub_.sent_[peers[i]][rank_];
    }
    hub_.sync_.arrive_and_wait();
    // Thrown after the barrier, so that the other ranks are not left waiting at it.
    if (one_sided >= 0)
      throw std::logic_error("in-process exchange: rank " + std::to_string(rank_) + " names " +
                             std::to_string(one_sided) + ", which does not name it");
  }
  void sum(std::span<std::uint64_t> v) override {
    reduce(v, [](std::uint64_t a, std::uint64_t b) { return a + b; });
  }
  void max(std::span<std::uint64_t> v) override {
    reduce(v, [](std::uint64_t a, std::uint64_t b) { return std::max(a, b); });
  }
  void min(std::span<double> v) override {
    reduce(v, [](double a, double b) { return std::min(a, b); });
  }
  std::vector<std::byte> allgather(std::span<const std::byte> mine) override {
    hub_.out_[rank_].assign(mine.begin(), mine.end());
    hub_.sync_.arrive_and_wait();
    std::vector<std::byte> all;
    for (const auto& part : hub_.out_) all.insert(all.end(), part.begin(), part.end());
    hub_.sync_.arrive_and_wait();
    return all;
  }

 private:
  template <class T, class Op>
  void reduce(std::span<T> v, Op op) {
    const std::vector<std::byte> all = allgather(std::as_bytes(v));
    for (int r = 0; r < hub_.ranks_; ++r)
      for (std::size_t i = 0; i < v.size(); ++i) {
        T x;
        std::memcpy(&x, all.data() + (r * v.size() + i) * sizeof(T), sizeof(T));
        v[i] = r == 0 ? x : op(v[i], x);
      }
  }

  InProcessRanks& hub_;
  int rank_;
};

}  // namespace hpcplan::test_support
