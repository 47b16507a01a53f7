// The monotone open list against a binary heap, its refusal of a falling priority, and the
// search's move to a binary heap when a heuristic that claims consistency is not.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <queue>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/gog.hpp"
#include "hpcplan/graph/lattice_graph.hpp"
#include "hpcplan/graph/lattice_heuristic.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/radix_open_list.hpp"
#include "hpcplan/search/stamped_dense_map.hpp"
#include "lattice_oracle.hpp"

namespace {

using namespace hpcplan;

struct Item {
  double f;
  double g;
  int id;
};

// A Dijkstra-like workload: every push is at least the last popped priority, with many equal
// priorities (integer and half-integer steps) and some arbitrary ones.
TEST(RadixOpenList, PopsInTheOrderOfABinaryHeap) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SplitMix64 rng(seed);
    search::RadixOpenList<Item> radix;
    std::priority_queue<double, std::vector<double>, std::greater<>> heap;
    double last = 0.0;
    int pushed = 0, popped = 0;
    auto push = [&] {
      const double step = rng.next_below(4) == 0 ? 1e3 * rng.next_unit()
                                                 : 0.5 * static_cast<double>(rng.next_below(6));
      const Item it{last + step, rng.next_unit(), pushed++};
      ASSERT_TRUE(radix.push(it));
      heap.push(it.f);
    };
    for (int i = 0; i < 5; ++i) push();
    for (int round = 0; round < 2000; ++round) {
      if (rng.next_below(3) != 0) {
        push();
        continue;
      }
      Item it;
      ASSERT_EQ(radix.pop(it), !heap.empty());
      if (heap.empty()) continue;
      EXPECT_EQ(it.f, heap.top()) << "seed " << seed << " pop " << popped;
      heap.pop();
      last = it.f;
      ++popped;
      double least;
      if (radix.least(least)) {
        EXPECT_EQ(least, heap.top());
      }
      EXPECT_EQ(radix.size(), heap.size());
    }
    Item it;
    while (radix.pop(it)) {
      EXPECT_EQ(it.f, heap.top());
      heap.pop();
    }
    EXPECT_TRUE(heap.empty());
  }
}

// Equal priorities leave deepest first (largest g), as the binary heap's tie-break does.
TEST(RadixOpenList, EqualPrioritiesLeaveDeepestFirst) {
  search::RadixOpenList<Item> radix;
  for (int i = 0; i < 6; ++i)
    ASSERT_TRUE(radix.push(Item{7.0, static_cast<double>((i * 5) % 6), i}));
  ASSERT_TRUE(radix.push(Item{3.0, 0.0, 99}));
  Item it;
  ASSERT_TRUE(radix.pop(it));
  EXPECT_EQ(it.id, 99);
  for (double g = 5; g >= 0; --g) {
    ASSERT_TRUE(radix.pop(it));
    EXPECT_EQ(it.f, 7.0);
    EXPECT_EQ(it.g, g);
  }
  EXPECT_FALSE(radix.pop(it));
}

// A list lent again by the pool starts over: the last popped priority of its previous search
// must not make it refuse the next search's first pushes.
TEST(RadixOpenList, AClearedListStartsOver) {
  search::RadixOpenList<Item> radix;
  ASSERT_TRUE(radix.push(Item{50.0, 0.0, 0}));
  Item it;
  ASSERT_TRUE(radix.pop(it));
  radix.clear();
  EXPECT_TRUE(radix.push(Item{3.0, 0.0, 1}));
  ASSERT_TRUE(radix.pop(it));
  EXPECT_EQ(it.id, 1);
}

TEST(RadixOpenList, RefusesAFallingOrNegativePriority) {
  search::RadixOpenList<Item> radix;
  EXPECT_FALSE(radix.push(Item{-1.0, 0.0, 0}));
  ASSERT_TRUE(radix.push(Item{5.0, 0.0, 1}));
  ASSERT_TRUE(radix.push(Item{9.0, 0.0, 2}));
  Item it;
  ASSERT_TRUE(radix.pop(it));
  EXPECT_FALSE(radix.push(Item{4.0, 0.0, 3}));
  EXPECT_TRUE(radix.push(Item{5.0, 0.0, 4}));
  EXPECT_EQ(radix.size(), 2u);
  std::vector<int> popped;
  while (radix.pop(it)) popped.push_back(it.id);
  EXPECT_EQ(popped, (std::vector<int>{4, 2}));  // the refused ones were not stored
}

// States without edges, so a test can drive the store by hand.
struct PointGraph {
  using State = std::uint64_t;
  using Cost = double;
  using Move = std::uint8_t;
  using Hash = std::hash<std::uint64_t>;
  static constexpr Move kNoMove = 0xFF;
  State predecessor(const State& s, Move) const { return s; }
  double checked_edge_length(const State&, const State&) const { return 1.0; }
  std::uint64_t collision_checks() const { return 0; }
  template <class Emit>
  void for_each_successor(const State&, Emit&&) const {}
};

// Entries offered below the radix list's last popped priority (a state from another rank, a
// reopened one) wait in the store's binary heap and must leave before every radix entry, in
// priority order.
TEST(RadixOpenList, StorePopsLateEntriesBeforeTheRadixList) {
  const search::ZeroHeuristic h;
  search::SearchStore<search::DefaultVisitedMap, PointGraph, search::ZeroHeuristic> store(
      h, search::Options{}, /*monotone=*/true);
  store.offer(1, 5.0, 0);
  std::uint64_t x;
  double g, f;
  ASSERT_TRUE(store.pop(x, g, f));
  EXPECT_EQ(x, 1u);  // the radix list's last key is now 5
  store.offer(2, 7.0, 0);
  store.offer(3, 3.0, 0);  // late
  store.offer(4, 4.0, 0);  // late
  EXPECT_EQ(store.open_size(), 3u);
  EXPECT_EQ(store.best_priority(), 3.0);
  std::vector<std::uint64_t> order;
  while (store.pop(x, g, f)) order.push_back(x);
  EXPECT_EQ(order, (std::vector<std::uint64_t>{3, 4, 2}));
  EXPECT_TRUE(store.open_empty());
}

// Admissible but not consistent, while claiming to be: the exact free distance at states with
// an even first coordinate, nothing elsewhere, so f falls by up to the whole distance along a
// move. The store must keep each falling priority in its binary heap, pop those first, reopen
// states, and still return the optimum.
template <int W>
class ClaimsConsistency {
 public:
  static constexpr bool kConsistent = true;
  ClaimsConsistency(const KeyLayout& layout, std::span<const int> goal)
      : exact_(layout, goal), layout_(layout) {}
  LatticeCost operator()(const PackedKey<W>& s) const {
    int c[kMaxDims];
    layout_.unpack(s, c);
    return c[0] % 2 == 0 ? exact_(s) : LatticeCost{};
  }

 private:
  SeedRuleHeuristic<W> exact_;
  const KeyLayout& layout_;
};

TEST(RadixOpenList, SearchKeepsFallingPrioritiesInAHeapWhenTheHeuristicIsNotConsistent) {
  int solved = 0;
  std::uint64_t reopened = 0;
  for (std::uint64_t seed = 1; seed <= 24; ++seed) {
    GogParams params;
    params.seed = seed;
    params.density = 0.25;
    const GogField field(2, 60, params);
    const LatticeGraph<1> graph(field, Connectivity::seed_pairs);
    const std::vector<int> start{0, 0}, goal{59, 59};
    if (!field.is_free(start) || !field.is_free(goal)) continue;
    const oracle::Lattice oracle(field, false);
    const oracle::Answer best = oracle.dijkstra(start, goal);
    const ClaimsConsistency<1> h(graph.layout(), goal);
    search::Options options;
    options.dense_keys = graph.layout().dense_index_bound();
    const auto r = search::best_first_search<search::StampedDensePolicy>(
        graph, graph.pack(start), graph.pack(goal), h, options);
    ASSERT_EQ(r.status == search::Status::solved, best.reachable) << "seed " << seed;
    if (!best.reachable) continue;
    ++solved;
    reopened += r.counters.reopened;
    EXPECT_NEAR(r.cost, best.cost, 1e-9 * (1 + best.cost)) << "seed " << seed;
  }
  EXPECT_GE(solved, 12);
  EXPECT_GT(reopened, 0u) << "the heuristic never broke consistency: the test tests nothing";
}

}  // namespace
