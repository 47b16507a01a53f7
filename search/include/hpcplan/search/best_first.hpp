#pragma once
// The serial best-first search engine for every graph (lattice, dense grid). Algorithms are
// configurations of it:
//   A*          heap on f = g + h, ties toward larger g (a radix heap when h is consistent and
//               exact, or h = 0: the priorities popped never fall)
//   weighted A* heap on f = g + w*h, closed states are not reopened (keeps the w bound)
//   Dijkstra    A* with h = 0
//   BFS         FIFO frontier over hop counts, goal tested on generation (fewest hops)
//   jump point search   A* on graph/jump_point_graph.hpp, whose successors depend on the move
//               that reached a state (ExpandsAfterArrival)
// The store (visited map + open list) is shared with the distributed engines in mpi/.
#include <cmath>
#include <cstdint>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/search/search_result.hpp"
#include "hpcplan/search/search_store.hpp"

namespace hpcplan::search {

// Fills in the counters and, for a solved search, the path traced back through the store,
// re-validated edge by edge and checked against the search's own cost. Shared by every serial
// search over a SearchStore (best_first_search, lazy_theta_star).
template <class Store, class G>
Result<typename G::State>& complete_result(Result<typename G::State>& result, const Store& store,
                                           const G& graph, const typename G::State& start,
                                           const typename G::State& goal, Status status,
                                           bool solved, std::uint64_t checks_before,
                                           const Stopwatch& clock) {
  Counters& counters = result.counters;
  counters.peak_states = store.stored();
  counters.peak_open = store.peak_open();
  counters.reopened = store.reopened();
  counters.collision_checks = graph.collision_checks() - checks_before;
  result.status = status;
  if (solved) {
    result.path = trace_back(store, graph, goal);
    if (!(result.path.front() == start))
      throw RunError("internal error: reconstructed path does not join start and goal");
    const double length = validated_length(graph, result.path);
    result.cost = cost_value(store.find(goal)->g);
    if (std::abs(length - result.cost) > 1e-9 * (1.0 + result.cost))
      throw RunError("internal error: path length disagrees with the search's cost");
    result.hops = result.path.size() - 1;
  }
  counters.time_ms = clock.milliseconds();
  return result;
}

// Graphs with costly edge tests (the visibility graph) take a second callback and test an
// edge only when the store says offering it could change something.
template <class G>
concept FiltersSuccessors = requires(const G& g, const typename G::State& s) {
  g.for_each_successor(
      s, [](const typename G::State&, typename G::Cost, typename G::Move) {},
      [](const typename G::State&, typename G::Cost) { return true; });
};

// Graphs whose successors depend on how a state was reached (jump point search prunes by the
// arriving direction) are handed the move the store keeps for it.
template <class G>
concept ExpandsAfterArrival = requires(const G& g, const typename G::State& s, typename G::Move m) {
  g.for_each_successor_after(s, m,
                             [](const typename G::State&, typename G::Cost, typename G::Move) {});
};

template <class MapPolicy = DefaultVisitedMap, SearchGraph G, class Heuristic>
Result<typename G::State> best_first_search(const G& graph, const typename G::State& start,
                                            const typename G::State& goal, const Heuristic& h,
                                            const Options& options) {
  using State = typename G::State;
  using Cost = typename G::Cost;
  using Store = SearchStore<MapPolicy, G, Heuristic>;

  Result<State> result;
  Counters& counters = result.counters;
  const std::uint64_t checks_before = graph.collision_checks();
  Stopwatch clock;
  Store store(h, options, kMonotonePriorities<Heuristic, G>);
  const bool is_fifo = options.frontier == Frontier::fifo;
  Stop stop = options.stop;

  auto finish = [&](Status status, bool solved) {
    return complete_result(result, store, graph, start, goal, status, solved, checks_before, clock);
  };

  store.offer(start, Cost{}, G::kNoMove);
  if (start == goal) return finish(Status::solved, true);

  State x;
  Cost gx;
  double fx;
  while (store.pop(x, gx, fx)) {
    if (!is_fifo && x == goal) return finish(Status::solved, true);
    ++counters.expanded;
    if (const auto why = stop.poll()) return finish(*why, false);
    if ((counters.expanded & 0xffff) == 0 && options.progress)
      options.progress(counters.expanded, store.stored());

    bool goal_generated = false;
    bool over_budget = false;
    // (Forced inline: GCC kept it a call; inlined, a 2D query is about 8% faster.)
    auto emit = [&](const State& t, const Cost& cost, typename G::Move m)
        __attribute__((always_inline)) {
      ++counters.generated;
      if (goal_generated || over_budget) return;
      // BFS stores the real cost too (never compared): it orders by hops through the FIFO.
      const auto offered = store.offer(t, gx + cost, m);
      if (offered == Store::Offered::over_budget)
        over_budget = true;
      else if (is_fifo && offered == Store::Offered::pushed && t == goal)
        goal_generated = true;
    };
    if constexpr (ExpandsAfterArrival<G>)
      graph.for_each_successor_after(x, store.find(x)->move, emit);
    else if constexpr (FiltersSuccessors<G>)
      graph.for_each_successor(x, emit, [&](const State& t, const Cost& cost) {
        return store.could_improve(t, gx + cost);
      });
    else
      graph.for_each_successor(x, emit);
    if (goal_generated) return finish(Status::solved, true);
    if (over_budget) return finish(Status::budget_exceeded, false);
  }
  return finish(Status::no_path, false);
}

}  // namespace hpcplan::search
