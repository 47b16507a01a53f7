#pragma once
// One best-first search engine for every graph (lattice, dense grid, and later the
// distributed layer's local part). Algorithms are configurations of it:
//   A*          heap on f = g + h, ties toward larger g
//   weighted A* heap on f = g + w*h, closed states are not reopened (keeps the w bound)
//   Dijkstra    A* with h = 0
//   BFS         FIFO frontier over hop counts, goal tested on generation (fewest hops)
#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <deque>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/graph/lattice_cost.hpp"
#include "hpcplan/search/search_result.hpp"
#include "hpcplan/search/visited_map.hpp"

namespace hpcplan::search {

// What the engine needs from a graph: a cost type (double, or an exact type with value()),
// successor generation with edge costs and move ids,
// parent recovery from a move id (so the visited map stores a small move, not a state), an
// independent edge check for returned paths, and a collision-check counter.
template <class G>
concept SearchGraph = requires(const G& g, const typename G::State& s, typename G::Move m) {
  typename G::Hash;
  typename G::Cost;
  { G::kNoMove } -> std::convertible_to<typename G::Move>;
  { g.predecessor(s, m) } -> std::same_as<typename G::State>;
  { g.checked_edge_length(s, s) } -> std::convertible_to<double>;
  { g.collision_checks() } -> std::convertible_to<std::uint64_t>;
  g.for_each_successor(s, [](const typename G::State&, typename G::Cost, typename G::Move) {});
};

enum class Frontier { best_first, fifo };

struct Options {
  Frontier frontier = Frontier::best_first;
  double weight = 1.0;           // multiplies h in the priority
  bool reopen_closed = true;     // false for weighted A*
  std::uint64_t max_states = 0;  // visited-map size limit; 0 = none
  double time_limit_s = 0.0;     // 0 = none
};

struct ZeroHeuristic {
  template <class State>
  double operator()(const State&) const {
    return 0.0;
  }
};

// Mutable access to a map entry: tsl::robin_map exposes it as value(), the others as second.
template <class Iterator>
auto& mapped(const Iterator& it) {
  if constexpr (requires { it.value(); })
    return it.value();
  else
    return it->second;
}

template <class MapPolicy = DefaultVisitedMap, SearchGraph G, class Heuristic>
Result<typename G::State> best_first_search(const G& graph, const typename G::State& start,
                                            const typename G::State& goal, const Heuristic& h,
                                            const Options& options) {
  using State = typename G::State;
  using Move = typename G::Move;
  using Cost = typename G::Cost;
  struct Node {
    Cost g;
    Move move;  // move that reached this state; kNoMove for the start
    bool closed;
  };
  struct Entry {
    double f;
    double g;
    State state;
  };
  // Heap order: smaller f first; among equal f, larger g first (deeper, closer to the goal).
  auto lower_priority = [](const Entry& a, const Entry& b) {
    return a.f > b.f || (a.f == b.f && a.g < b.g);
  };
  // Differences below this are rounding, not better paths, and must not trigger a reopening
  // (exact cost types never produce them; plain doubles can).
  constexpr double kImprovementEpsilon = 1e-9;

  Result<State> result;
  Counters& counters = result.counters;
  const std::uint64_t checks_before = graph.collision_checks();
  Stopwatch clock;

  typename MapPolicy::template type<State, Node, typename G::Hash> visited;
  std::vector<Entry> heap;
  std::deque<std::pair<State, Cost>> fifo;  // BFS: state and its g, no map look-up to expand
  const bool is_fifo = options.frontier == Frontier::fifo;
  const bool reopen = options.reopen_closed && !is_fifo;
  const double weight = options.weight;
  std::size_t open_size = 0;

  // With an exact heuristic and w = 1, f is formed exactly before rounding, so states on an
  // optimal plateau get bitwise-equal f and the larger-g tie-break can act.
  auto priority = [&](const Cost& g, const State& s) {
    const auto hs = h(s);
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(hs)>, Cost>)
      if (weight == 1.0) return cost_value(g + hs);
    return cost_value(g) + weight * cost_value(hs);
  };
  auto push = [&](const Cost& g, const State& s) {
    if (is_fifo) {
      fifo.emplace_back(s, g);
      open_size = fifo.size();
    } else {
      heap.push_back(Entry{priority(g, s), cost_value(g), s});
      std::push_heap(heap.begin(), heap.end(), lower_priority);
      open_size = heap.size();
    }
    counters.peak_open = std::max<std::uint64_t>(counters.peak_open, open_size);
  };

  auto finish = [&](Status status, const State* reached) {
    counters.peak_states = std::max<std::uint64_t>(counters.peak_states, visited.size());
    counters.collision_checks = graph.collision_checks() - checks_before;
    result.status = status;
    if (reached != nullptr) {
      for (State s = *reached;;) {
        result.path.push_back(s);
        const Move m = visited.find(s)->second.move;
        if (m == G::kNoMove) break;
        s = graph.predecessor(s, m);
      }
      std::reverse(result.path.begin(), result.path.end());
      if (!(result.path.front() == start) || !(result.path.back() == goal))
        throw RunError("internal error: reconstructed path does not join start and goal");
      // Re-validate every move with the graph's independent checker before returning it.
      double length = 0.0;
      for (std::size_t i = 1; i < result.path.size(); ++i) {
        const double len = graph.checked_edge_length(result.path[i - 1], result.path[i]);
        if (len < 0)
          throw RunError("internal error: returned path has an invalid move at step " +
                         std::to_string(i));
        length += len;
      }
      result.cost = cost_value(visited.find(*reached)->second.g);
      if (std::abs(length - result.cost) > 1e-9 * (1.0 + result.cost))
        throw RunError("internal error: path length disagrees with the search's cost");
      result.hops = result.path.size() - 1;
    }
    counters.time_ms = clock.milliseconds();
    return result;
  };

  visited.emplace(start, Node{Cost{}, G::kNoMove, false});
  if (start == goal) return finish(Status::solved, &start);
  push(Cost{}, start);

  while (is_fifo ? !fifo.empty() : !heap.empty()) {
    State x;
    Cost gx;
    if (is_fifo) {
      std::tie(x, gx) = fifo.front();
      fifo.pop_front();
    } else {
      std::pop_heap(heap.begin(), heap.end(), lower_priority);
      const Entry e = heap.back();
      heap.pop_back();
      auto it = visited.find(e.state);
      Node& node = mapped(it);
      if (node.closed || e.g > cost_value(node.g)) continue;  // stale duplicate
      node.closed = true;
      x = e.state;
      gx = node.g;
      if (x == goal) return finish(Status::solved, &goal);
    }
    ++counters.expanded;
    if (options.time_limit_s > 0 && (counters.expanded & 1023) == 0 &&
        clock.seconds() > options.time_limit_s)
      return finish(Status::timeout, nullptr);

    bool goal_generated = false;
    bool over_budget = false;
    graph.for_each_successor(x, [&](const State& t, const Cost& cost, Move m) {
      ++counters.generated;
      if (goal_generated || over_budget) return;
      // BFS stores the real cost too (never compared): it orders by hops through the FIFO.
      const Cost gt = gx + cost;
      auto [it, inserted] = visited.try_emplace(t, Node{gt, m, false});
      if (!inserted) {
        Node& node = mapped(it);
        if (is_fifo || cost_value(gt) + kImprovementEpsilon >= cost_value(node.g)) return;
        if (node.closed) {
          if (!reopen) return;
          ++counters.reopened;
        }
        node = Node{gt, m, false};
      } else if (options.max_states != 0 && visited.size() > options.max_states) {
        over_budget = true;
        return;
      }
      if (is_fifo && t == goal) {
        goal_generated = true;
        return;
      }
      push(gt, t);
    });
    if (goal_generated) return finish(Status::solved, &goal);
    if (over_budget) return finish(Status::budget_exceeded, nullptr);
  }
  return finish(Status::no_path, nullptr);
}

}  // namespace hpcplan::search
