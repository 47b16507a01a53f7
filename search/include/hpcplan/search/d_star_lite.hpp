#pragma once
// D* Lite (Koenig and Likhachev 2002) over any graph of the engine whose states are dense
// indices (state_count()) and whose edges are symmetric (the successors of s are also its
// predecessors, at the same cost: true of the occupancy grid). It searches from the goal back
// towards the start and keeps g and rhs between calls, so after the start moves (km grows by
// h(old start, new start)) and some states' edges change, only the states whose distance to the
// goal changed are expanded again. A moved goal invalidates every g: the caller resets.
//
// Distances are kept in the graph's own cost type. With the lattices' exact costs (LatticeCost:
// counts of 1, √2, √3) keys that tie exactly compare equal, which the algorithm relies on: its
// stopping rule compares the best queued key with the start's, and on a grid's optimal plateaus
// those tie in k1 and are decided by k2. With doubles, rounding broke such ties the wrong way
// and left states inconsistent below the start's key (found by the repair test against Dijkstra).
// The heuristic returns the same cost type and must be consistent.
//
// The open list is a binary heap with lazy deletion: an entry whose key is no longer the
// state's key, or whose state became consistent, is skipped (or re-queued with the new key)
// when it surfaces.
//
// Threads: one object per run, on one thread; the graph it reads may be shared.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "hpcplan/core/status.hpp"
#include "hpcplan/core/stop.hpp"
#include "hpcplan/search/cost_value.hpp"

namespace hpcplan::search {

template <class G, class Heuristic>  // Heuristic: G::Cost h(State a, State b), consistent
class DStarLite {
 public:
  using State = typename G::State;
  using Cost = typename G::Cost;

  explicit DStarLite(Heuristic h) : h_(std::move(h)) {}

  // Forgets everything: a search from `goal` for `start` on `graph`.
  void reset(const G& graph, State start, State goal) {
    const std::size_t n = graph.state_count();
    g_.assign(n, Dist{});
    rhs_.assign(n, Dist{});
    heap_.clear();
    km_ = Cost{};
    start_ = start;
    goal_ = goal;
    rhs_[goal] = Dist{Cost{}, false};
    push(goal);
  }
  State goal() const { return goal_; }

  // The robot moved to `start`: keys already queued stay valid lower bounds through km.
  void move_start(State start) {
    km_ = km_ + h_(start_, start);
    start_ = start;
  }

  // The edges of these states changed (with symmetric edges: any state next to a changed one).
  void edges_changed(const G& graph, std::span<const State> states) {
    for (State s : states) update(graph, s);
  }

  // Brings g up to date for the current start. solved: the start reaches the goal; no_path: it
  // does not; or what `stop` said.
  Status compute(const G& graph, const Stop& stop) {
    std::uint64_t polls = 0;
    while (!heap_.empty()) {
      if (!(heap_.front().key < key(start_)) && rhs_[start_] == g_[start_]) break;
      if ((++polls & 63) == 0)
        if (const auto why = stop.check()) return *why;
      std::pop_heap(heap_.begin(), heap_.end(), later);
      const Entry e = heap_.back();
      heap_.pop_back();
      const State u = e.state;
      if (g_[u] == rhs_[u]) continue;  // became consistent since it was queued
      const Key now = key(u);
      if (e.key < now) {  // km grew: queue it again with its key
        push(u);
        continue;
      }
      if (now < e.key) continue;  // a newer entry with the smaller key exists
      ++expanded_;
      if (rhs_[u] < g_[u]) {
        g_[u] = rhs_[u];
        graph.for_each_successor(u, [&](State p, auto, auto) { update(graph, p); });
      } else {
        g_[u] = Dist{};
        update(graph, u);
        graph.for_each_successor(u, [&](State p, auto, auto) { update(graph, p); });
      }
    }
    return reachable(start_) ? Status::solved : Status::no_path;
  }

  // The states from the start to the goal, following the least c + g; empty when unreachable.
  std::vector<State> path(const G& graph) const {
    std::vector<State> out;
    if (!reachable(start_)) return out;
    State s = start_;
    out.push_back(s);
    const std::size_t limit = g_.size();
    while (s != goal_ && out.size() <= limit) {
      Dist best;
      State next = s;
      graph.for_each_successor(s, [&](State t, const Cost& c, auto) {
        const Dist v = g_[t] + c;
        if (v < best) best = v, next = t;
      });
      if (next == s || best.inf) return {};
      s = next;
      out.push_back(s);
    }
    if (s != goal_) return {};
    return out;
  }

  // min(g, rhs) of s as a number (infinity when unreachable).
  double distance_to_goal(State s) const {
    const Dist d = std::min(g_[s], rhs_[s]);
    return d.inf ? std::numeric_limits<double>::infinity() : cost_value(d.c);
  }
  std::uint64_t expanded() const { return expanded_; }
  void reset_counters() { expanded_ = 0; }

 private:
  // A distance: a cost, or infinity.
  struct Dist {
    Cost c{};
    bool inf = true;
    friend Dist operator+(const Dist& a, const Cost& b) { return a.inf ? a : Dist{a.c + b, false}; }
    friend bool operator==(const Dist& a, const Dist& b) {
      return a.inf == b.inf && (a.inf || a.c == b.c);
    }
    friend bool operator<(const Dist& a, const Dist& b) {
      if (a.inf || b.inf) return !a.inf && b.inf;
      return !(a.c == b.c) && cost_value(a.c) < cost_value(b.c);
    }
  };
  struct Key {
    Dist k1, k2;
    friend bool operator<(const Key& a, const Key& b) {
      return a.k1 < b.k1 || (a.k1 == b.k1 && a.k2 < b.k2);
    }
  };
  struct Entry {
    Key key;
    State state;
  };
  static bool later(const Entry& a, const Entry& b) { return b.key < a.key; }

  bool reachable(State s) const { return !g_[s].inf || !rhs_[s].inf; }
  Key key(State s) const {
    const Dist m = std::min(g_[s], rhs_[s]);
    return {m + (h_(start_, s) + km_), m};
  }
  void push(State s) {
    heap_.push_back({key(s), s});
    std::push_heap(heap_.begin(), heap_.end(), later);
  }
  void update(const G& graph, State u) {
    if (u != goal_) {
      Dist best;
      graph.for_each_successor(u, [&](State t, const Cost& c, auto) {
        const Dist v = g_[t] + c;
        if (v < best) best = v;
      });
      rhs_[u] = best;
    }
    if (!(g_[u] == rhs_[u])) push(u);
  }

  Heuristic h_;
  std::vector<Dist> g_, rhs_;
  std::vector<Entry> heap_;
  Cost km_{};
  State start_{}, goal_{};
  std::uint64_t expanded_ = 0;
};

}  // namespace hpcplan::search
