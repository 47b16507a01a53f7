#pragma once
// Whether `from` lies in a small pocket of the graph: a breadth-first flood from it that stops
// at `target` or after `budget` states. When the flood runs dry first, no path leaves the pocket
// and a search between `from` and anything outside it can only exhaust the pocket's other side
// (in the fluid's occupancy grid, a goal walled in by particles would otherwise cost A* the
// whole free space: ~220,000 expansions, ~150 ms at 25,000 particles).
//
// Threads: a value-returning function; the graph may be shared.
#include <cstdint>
#include <deque>

#include <absl/container/flat_hash_set.h>

namespace hpcplan::search {

enum class Reach { target, exhausted, budget };

template <class G>
Reach bounded_reach(const G& graph, typename G::State from, typename G::State target,
                    std::size_t budget, std::uint64_t* visited = nullptr) {
  using State = typename G::State;
  absl::flat_hash_set<State, typename G::Hash> seen;
  std::deque<State> queue{from};
  seen.insert(from);
  Reach result = Reach::exhausted;
  while (!queue.empty()) {
    const State s = queue.front();
    queue.pop_front();
    if (s == target) {
      result = Reach::target;
      break;
    }
    bool stop = false;
    graph.for_each_successor(s, [&](const State& t, auto, auto) {
      if (stop || !seen.insert(t).second) return;
      if (seen.size() > budget) stop = true;
      queue.push_back(t);
    });
    if (stop) {
      result = Reach::budget;
      break;
    }
  }
  if (visited) *visited = seen.size();
  return result;
}

}  // namespace hpcplan::search
