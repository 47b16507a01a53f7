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
#include <thread>
#include <vector>

#include "hpcplan/dense/slab_transport.hpp"

namespace hpcplan::test_support {

class InProcessRanks {
 public:
  explicit InProcessRanks(int ranks)
      : ranks_(ranks), sync_(ranks), out_(ranks), down_(ranks), up_(ranks) {}
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
  std::vector<std::vector<std::byte>> out_;   // per rank: its allgather contribution
  std::vector<std::vector<std::byte>> down_;  // per rank: what it sends to the rank below
  std::vector<std::vector<std::byte>> up_;    // per rank: what it sends to the rank above
  std::vector<int> below_ = std::vector<int>(ranks_, -1), above_ = std::vector<int>(ranks_, -1);
};

class InProcessTransport final : public dense::SlabTransport {
 public:
  InProcessTransport(InProcessRanks& hub, int rank) : hub_(hub), rank_(rank) {}
  int rank() const override { return rank_; }
  int ranks() const override { return hub_.ranks_; }
  int ranks_on_node() const override { return hub_.ranks_; }

  void exchange(int below, std::span<const std::byte> down, int above,
                std::span<const std::byte> up, std::vector<std::byte>& from_below,
                std::vector<std::byte>& from_above) override {
    hub_.down_[rank_].assign(down.begin(), down.end());
    hub_.up_[rank_].assign(up.begin(), up.end());
    hub_.below_[rank_] = below;
    hub_.above_[rank_] = above;
    hub_.sync_.arrive_and_wait();
    // What the rank below sent up to this one, and what the rank above sent down; a rank
    // sends only to the neighbours it names, and they must name it back.
    from_below.clear();
    from_above.clear();
    if (below >= 0 && hub_.above_[below] == rank_) from_below = hub_.up_[below];
    if (above >= 0 && hub_.below_[above] == rank_) from_above = hub_.down_[above];
    messages_sent += (below >= 0) + (above >= 0);
    bytes_sent += down.size() * (below >= 0) + up.size() * (above >= 0);
    hub_.sync_.arrive_and_wait();
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
