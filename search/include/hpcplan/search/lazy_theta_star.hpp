#pragma once
// Lazy Theta* (Nash, Koenig and Tovey, 2010): any-angle search on the same store as A*. A
// successor t of x is offered with x's parent as its own parent (g(parent) + |parent t|),
// assuming the straight segment is free; the assumption is checked only when t is expanded,
// and if it fails t takes its best already-expanded neighbour as parent instead. Paths bend
// only at obstacles rather than at lattice directions.
//
// The graph's moves are parent states (predecessor(s, m) == m) and it answers
// line_of_sight(a, b) and distance(a, b); its successor relation must be symmetric, since the
// repair looks for expanded neighbours among the successors.
#include <cmath>
#include <concepts>
#include <limits>

#include "hpcplan/search/best_first.hpp"

namespace hpcplan::search {

template <class G>
concept AnyAngleGraph = SearchGraph<G> && std::same_as<typename G::Move, typename G::State> &&
    requires(const G& g, const typename G::State& s) {
  { g.line_of_sight(s, s) } -> std::same_as<bool>;
  { g.distance(s, s) } -> std::convertible_to<double>;
};

template <class MapPolicy = DefaultVisitedMap, AnyAngleGraph G, class Heuristic>
Result<typename G::State> lazy_theta_star(const G& graph, const typename G::State& start,
                                          const typename G::State& goal, const Heuristic& h,
                                          const Options& options) {
  using State = typename G::State;
  using Store = SearchStore<MapPolicy, G, Heuristic>;
  static_assert(std::is_same_v<typename G::Cost, double>, "any-angle costs are real lengths");

  Result<State> result;
  Counters& counters = result.counters;
  const std::uint64_t checks_before = graph.collision_checks();
  Stopwatch clock;
  Options o = options;
  o.frontier = Frontier::best_first;
  o.reopen_closed = false;
  Store store(h, o);
  Stop stop = options.stop;
  auto finish = [&](Status status, bool solved) {
    return complete_result(result, store, graph, start, goal, status, solved, checks_before, clock);
  };

  store.offer(start, 0.0, G::kNoMove);
  State x;
  double gx, fx;
  while (store.pop(x, gx, fx)) {
    State parent = store.find(x)->move;
    if (parent != G::kNoMove && !graph.line_of_sight(parent, x)) {
      // The optimistic parent is hidden: fall back to the best expanded neighbour (one exists,
      // the state x was generated from).
      double best = std::numeric_limits<double>::infinity();
      State best_parent = G::kNoMove;
      graph.for_each_successor(x, [&](const State& n, double cost, State) {
        const auto* node = store.find(n);
        if (node && node->closed && !(n == x) && node->g + cost < best)
          best = node->g + cost, best_parent = n;
      });
      if (best_parent == G::kNoMove)
        throw RunError("internal error: Lazy Theta* found no expanded neighbour to repair");
      store.reparent(x, best, best_parent);
      gx = best;
      parent = best_parent;
    }
    if (x == goal) return finish(Status::solved, true);
    ++counters.expanded;
    if (const auto why = stop.poll()) return finish(*why, false);

    const bool has_parent = parent != G::kNoMove;
    const double g_parent = has_parent ? store.find(parent)->g : 0.0;
    bool over_budget = false;
    graph.for_each_successor(x, [&](const State& t, double cost, State) {
      ++counters.generated;
      if (over_budget) return;
      const auto* node = store.find(t);
      if (node && node->closed) return;
      const auto offered = has_parent ? store.offer(t, g_parent + graph.distance(parent, t), parent)
                                      : store.offer(t, gx + cost, x);
      over_budget = offered == Store::Offered::over_budget;
    });
    if (over_budget) return finish(Status::budget_exceeded, false);
  }
  return finish(Status::no_path, false);
}

}  // namespace hpcplan::search
