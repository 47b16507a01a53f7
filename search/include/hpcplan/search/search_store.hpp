#pragma once
// The state store every best-first search shares: the visited map (g, parent move, closed
// flag per state) and the open list (a binary heap on f; a radix heap when the caller says the
// priorities rarely fall, see kMonotonePriorities, with the binary heap taking the few entries
// that arrive below its last key; a FIFO for BFS). The serial engine
// (best_first.hpp) and the distributed engines (mpi/) both drive this one store, so the rules
// for inserting, improving, reopening and popping states are written once.
//
// Threads: a store belongs to one run (one rank's search) on one thread.
#include <algorithm>
#include <concepts>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/huge_page_allocator.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/core/stop.hpp"
#include "hpcplan/search/cost_value.hpp"
#include "hpcplan/search/radix_open_list.hpp"
#include "hpcplan/search/visited_map.hpp"

namespace hpcplan::search {

// What the engine needs from a graph: a cost type (double, or an exact type with value()),
// successor generation with edge costs and move ids, parent recovery from a move id (so the
// visited map stores a small move, not a state), an independent edge check for returned
// paths, and a collision-check counter.
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

// best_first: a heap on f; fifo: BFS; random: any open state, uniformly (the seed 003 hybrid's
// "random choice from the open list"; complete, but neither optimal nor bounded).
enum class Frontier { best_first, fifo, random };

struct Options {
  Frontier frontier = Frontier::best_first;
  double weight = 1.0;           // multiplies h in the priority
  bool reopen_closed = true;     // false for serial weighted A*
  std::uint64_t max_states = 0;  // visited-map size limit; 0 = none
  Stop stop;                     // deadline and/or cancellation; default: never
  // Called every 2^16 expansions with (expanded, stored states): the caller decides whether and
  // how to show it (the engine does no I/O). Empty: nothing is called.
  std::function<void(std::uint64_t, std::uint64_t)> progress;
  std::uint64_t seed = 1;        // Frontier::random only
  std::uint64_t dense_keys = 0;  // map policies with a dense range: keys below this bound
};

struct ZeroHeuristic {
  static constexpr bool kConsistent = true;
  template <class State>
  double operator()(const State&) const {
    return 0.0;
  }
};

// Whether a best-first search at weight 1 pops priorities that never fall: Dijkstra (g only
// grows along a path, in any arithmetic), or A* whose heuristic declares itself consistent and
// returns the graph's exact cost type, so f = g + h is formed exactly and cannot dip by a
// rounding. Such a search may use the monotone open list.
template <class Heuristic, class G>
inline constexpr bool kMonotonePriorities =
    std::is_same_v<Heuristic, ZeroHeuristic> ||
    (
        requires { requires Heuristic::kConsistent; } &&
        requires(const Heuristic& h, const typename G::State& s, const typename G::Cost& c) {
          { h(s) } -> std::same_as<typename G::Cost>;
          c.value();
        });

// Mutable access to a map entry: tsl::robin_map exposes it as value(), the others as second.
template <class Iterator>
auto& mapped(const Iterator& it) {
  if constexpr (requires { it.value(); })
    return it.value();
  else
    return it->second;
}

template <class MapPolicy, SearchGraph G, class Heuristic>
class SearchStore {
 public:
  using State = typename G::State;
  using Move = typename G::Move;
  using Cost = typename G::Cost;
  struct Node {
    Cost g;
    Move move;  // move that reached this state; kNoMove for the start
    bool closed;
  };
  enum class Offered { pushed, ignored, over_budget };

  // monotone: the priorities pushed are expected to stay at or above the last one popped (see
  // kMonotonePriorities), so the open list is a radix heap. One that falls below after all
  // goes to the binary heap, which is popped first while it holds anything: every entry there
  // is below every radix entry, so the order stays exact.
  SearchStore(const Heuristic& h, const Options& options, bool monotone = false)
      : h_(h),
        fifo_(options.frontier == Frontier::fifo),
        // A random frontier closes states in no useful order; reopening one would leave its
        // descendants' costs stale, so closed states stay as they are.
        reopen_(options.reopen_closed && options.frontier == Frontier::best_first),
        weight_(options.weight),
        random_(options.frontier == Frontier::random),
        max_states_(options.max_states),
        monotone_(monotone && options.frontier == Frontier::best_first && options.weight == 1.0),
        rng_(options.seed) {
    // Small searches (2D, replanning, benchmark loops) would otherwise spend a third of
    // their time growing the map and heap through a dozen rehashes and re-faulted pages.
    if constexpr (requires { visited_.set_dense_keys(options.dense_keys); })
      visited_.set_dense_keys(options.dense_keys);
    visited_.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(max_states_, kInitial)));
    if (monotone_)
      radix_.borrow();
    else if (!fifo_)
      heap_.reserve(kInitial / 4);
  }

  // A state reached with cost g through move m. New states are stored and opened; known ones
  // only when g is strictly better (never for BFS, whose FIFO orders by hops) and, if already
  // expanded, only when reopening is allowed. A new state beyond the budget is stored but not
  // opened, and reported so the caller can stop.
  [[gnu::always_inline]] Offered offer(const State& t, const Cost& g, Move m) {
    auto [it, inserted] = visited_.try_emplace(t, Node{g, m, false});
    if (!inserted) {
      Node& node = mapped(it);
      if (fifo_ || cost_value(g) + kImprovementEpsilon >= cost_value(node.g))
        return Offered::ignored;
      if (node.closed) {
        if (!reopen_) return Offered::ignored;
        ++reopened_;
      }
      node = Node{g, m, false};
    } else if (max_states_ != 0 && visited_.size() > max_states_) {
      return Offered::over_budget;
    }
    push(g, t);
    return Offered::pushed;
  }

  // Whether offer(t, g, ...) would store or improve t: lets a graph skip testing edges that
  // cannot matter.
  bool could_improve(const State& t, const Cost& g) const {
    auto it = visited_.find(t);
    if (it == visited_.end()) return true;
    const Node& node = it->second;
    if (fifo_ || cost_value(g) + kImprovementEpsilon >= cost_value(node.g)) return false;
    return !node.closed || reopen_;
  }

  // Takes the next state to expand off the open list and marks it closed; skips stale heap
  // duplicates. `f` receives its priority (its g for BFS). False when the open list is empty.
  bool pop(State& x, Cost& g, double& f) {
    if (fifo_) {
      if (fifo_queue_.empty()) return false;
      std::tie(x, g) = fifo_queue_.front();
      fifo_queue_.pop_front();
      f = cost_value(g);
      return true;
    }
    Entry e;
    while (take(e)) {
      Node& node = mapped(visited_.find(e.state));
      if (node.closed || e.g > cost_value(node.g)) continue;  // stale duplicate
      node.closed = true;
      x = e.state;
      g = node.g;
      f = e.f;
      return true;
    }
    return false;
  }

  const Node* find(const State& s) const {
    auto it = visited_.find(s);
    return it == visited_.end() ? nullptr : &it->second;
  }
  // Gives a stored state a new cost and parent move without reopening it (Lazy Theta*'s
  // repair of a parent that turned out not to be visible).
  void reparent(const State& s, const Cost& g, Move m) {
    Node& node = mapped(visited_.find(s));
    node.g = g;
    node.move = m;
  }
  // Lowest priority on the open list (may belong to a stale entry), +inf when empty.
  double best_priority() const {
    if (fifo_) return fifo_queue_.empty() ? kInfinity : cost_value(fifo_queue_.front().second);
    if (!heap_.empty()) return heap_.front().f;  // below every radix entry, if any
    double f;
    return monotone_ && radix_->least(f) ? f : kInfinity;
  }
  bool open_empty() const { return open_size() == 0; }
  std::size_t open_size() const {
    if (fifo_) return fifo_queue_.size();
    return heap_.size() + (monotone_ ? radix_->size() : 0);
  }
  void clear_open() {
    heap_.clear();
    if (radix_) radix_->clear();
    fifo_queue_.clear();
  }
  std::size_t stored() const { return visited_.size(); }
  std::uint64_t reopened() const { return reopened_; }
  std::uint64_t peak_open() const { return peak_open_; }

  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

 private:
  struct Entry {
    double f;
    double g;
    State state;
  };
  // Heap order: smaller f first; among equal f, larger g first (deeper, closer to the goal).
  // (A function object, not a function pointer, so the heap operations inline it.)
  struct LowerPriority {
    bool operator()(const Entry& a, const Entry& b) const {
      return a.f > b.f || (a.f == b.f && a.g < b.g);
    }
  };
  static constexpr LowerPriority lower_priority{};
  // Differences below this are rounding, not better paths, and must not trigger a reopening
  // (exact cost types never produce them; plain doubles can).
  static constexpr double kImprovementEpsilon = 1e-9;

  // With an exact heuristic and w = 1, f is formed exactly before rounding, so states on an
  // optimal plateau get bitwise-equal f and the larger-g tie-break can act.
  [[gnu::always_inline]] double priority(const Cost& g, const State& s) const {
    const auto hs = h_(s);
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(hs)>, Cost>)
      if (weight_ == 1.0) return cost_value(g + hs);
    return cost_value(g) + weight_ * cost_value(hs);
  }

  [[gnu::always_inline]] void push(const Cost& g, const State& s) {
    std::size_t size;
    if (fifo_) {
      fifo_queue_.emplace_back(s, g);
      size = fifo_queue_.size();
    } else {
      const Entry e{priority(g, s), cost_value(g), s};
      if (!monotone_ || !radix_->push(e)) {
        // Below the radix list's last key (a late arrival from another rank, a reopened
        // state, a heuristic that is not consistent after all): the binary heap holds it.
        heap_.push_back(e);
        if (!random_) std::push_heap(heap_.begin(), heap_.end(), lower_priority);
      }
      size = open_size();
    }
    peak_open_ = std::max<std::uint64_t>(peak_open_, size);
  }

  // The next open entry, stale or not, in priority order (random order for Frontier::random).
  // With the radix list in use, the heap holds only entries below its last key, so it goes
  // first.
  bool take(Entry& e) {
    if (heap_.empty()) return monotone_ && radix_->pop(e);
    if (random_)
      std::swap(heap_[rng_.next_below(heap_.size())], heap_.back());
    else
      std::pop_heap(heap_.begin(), heap_.end(), lower_priority);
    e = heap_.back();
    heap_.pop_back();
    return true;
  }

  static constexpr std::uint64_t kInitial = 1 << 14;  // states reserved up front

  const Heuristic& h_;
  bool fifo_;
  bool reopen_;
  double weight_;
  bool random_;
  std::uint64_t max_states_;
  bool monotone_;
  SplitMix64 rng_;
  typename MapPolicy::template type<State, Node, typename G::Hash> visited_;
  std::vector<Entry, HugePageAllocator<Entry>> heap_;
  LentOpenList<Entry> radix_;                      // borrowed only when monotone
  std::deque<std::pair<State, Cost>> fifo_queue_;  // BFS: each state with its g
  std::uint64_t reopened_ = 0;
  std::uint64_t peak_open_ = 0;
};

// Follows parent moves from `s` back to the start through a store holding the whole chain.
template <class Store, class G>
std::vector<typename G::State> trace_back(const Store& store, const G& graph, typename G::State s) {
  std::vector<typename G::State> path;
  for (;;) {
    path.push_back(s);
    const auto m = store.find(s)->move;
    if (m == G::kNoMove) break;
    s = graph.predecessor(s, m);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

// Re-validates every move of `path` with the graph's independent checker and returns its
// length; a returned path with an illegal move is an internal error, never an answer.
template <class G>
double validated_length(const G& graph, const std::vector<typename G::State>& path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const double len = graph.checked_edge_length(path[i - 1], path[i]);
    if (len < 0)
      throw RunError("internal error: returned path has an invalid move at step " +
                     std::to_string(i));
    length += len;
  }
  return length;
}

}  // namespace hpcplan::search
