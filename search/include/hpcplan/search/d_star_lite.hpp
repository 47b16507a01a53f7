#pragma once
// D* Lite (Koenig and Likhachev 2002) over any graph of the engine whose states are dense
// indices (state_count()) and whose edges are symmetric (the successors of s are also its
// predecessors, at the same cost: true of the occupancy grid). It searches from the goal back
// towards the start and keeps g and rhs between calls, so after the start moves (km grows by
// h(old start, new start)) and some states' edges change, only the states whose distance to the
// goal changed are expanded again. A moved goal invalidates every g: the caller resets.
//
// The open list is a binary heap with lazy deletion: an entry whose key is no longer the
// state's key, or whose state became consistent, is skipped (or re-queued with the new key)
// when it surfaces.
//
// Threads: one object per run, on one thread; the graph it reads may be shared.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "hpcplan/core/status.hpp"
#include "hpcplan/core/stop.hpp"
#include "hpcplan/search/cost_value.hpp"

namespace hpcplan::search {

template <class G, class Heuristic>  // Heuristic: double h(State a, State b), consistent
class DStarLite {
 public:
  using State = typename G::State;
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  explicit DStarLite(Heuristic h) : h_(std::move(h)) {}

  // Forgets everything: a search from `goal` for `start` on `graph`.
  void reset(const G& graph, State start, State goal) {
    const std::size_t n = graph.state_count();
    g_.assign(n, kInf);
    rhs_.assign(n, kInf);
    heap_.clear();
    km_ = 0.0;
    start_ = start;
    goal_ = goal;
    rhs_[goal] = 0.0;
    push(goal);
    initialised_ = true;
  }
  bool initialised() const { return initialised_; }
  State goal() const { return goal_; }

  // The robot moved to `start`: keys already queued stay valid lower bounds through km.
  void move_start(State start) {
    km_ += h_(start_, start);
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
      const Key top = heap_.front().key;
      const Key ks = key(start_);
      if (!(top < ks) && rhs_[start_] == g_[start_]) break;
      if ((++polls & 63) == 0)
        if (const auto why = stop.check()) return *why;
      std::pop_heap(heap_.begin(), heap_.end(), later);
      const Entry e = heap_.back();
      heap_.pop_back();
      const State u = e.state;
      if (g_[u] == rhs_[u]) continue;  // became consistent since it was queued
      const Key now = key(u);
      if (e.key < now) {  // km grew or rhs changed: queue it again with its key
        push(u);
        continue;
      }
      if (now < e.key) continue;  // a newer entry with the smaller key exists
      ++expanded_;
      if (g_[u] > rhs_[u]) {
        g_[u] = rhs_[u];
        graph.for_each_successor(u, [&](State p, auto, auto) { update(graph, p); });
      } else {
        g_[u] = kInf;
        update(graph, u);
        graph.for_each_successor(u, [&](State p, auto, auto) { update(graph, p); });
      }
    }
    return std::isinf(g_[start_]) && std::isinf(rhs_[start_]) ? Status::no_path : Status::solved;
  }

  // The states from the start to the goal, following the least c + g; empty when unreachable.
  std::vector<State> path(const G& graph) const {
    std::vector<State> out;
    if (std::isinf(rhs_[start_]) && std::isinf(g_[start_])) return out;
    State s = start_;
    out.push_back(s);
    const std::size_t limit = g_.size();
    while (s != goal_ && out.size() <= limit) {
      double best = kInf;
      State next = s;
      graph.for_each_successor(s, [&](State t, auto c, auto) {
        const double v = cost_value(c) + g_[t];
        if (v < best) best = v, next = t;
      });
      if (next == s || std::isinf(best)) return {};
      s = next;
      out.push_back(s);
    }
    if (s != goal_) return {};
    return out;
  }

  double distance_to_goal(State s) const { return std::min(g_[s], rhs_[s]); }
  std::uint64_t expanded() const { return expanded_; }
  void reset_counters() { expanded_ = 0; }

 private:
  struct Key {
    double k1 = 0.0, k2 = 0.0;
    friend bool operator<(const Key& a, const Key& b) {
      return a.k1 < b.k1 || (a.k1 == b.k1 && a.k2 < b.k2);
    }
  };
  struct Entry {
    Key key;
    State state;
  };
  static bool later(const Entry& a, const Entry& b) { return b.key < a.key; }

  Key key(State s) const {
    const double m = std::min(g_[s], rhs_[s]);
    return {m + h_(start_, s) + km_, m};
  }
  void push(State s) {
    heap_.push_back({key(s), s});
    std::push_heap(heap_.begin(), heap_.end(), later);
  }
  void update(const G& graph, State u) {
    if (u != goal_) {
      double best = kInf;
      graph.for_each_successor(
          u, [&](State t, auto c, auto) { best = std::min(best, cost_value(c) + g_[t]); });
      rhs_[u] = best;
    }
    if (g_[u] != rhs_[u]) push(u);
  }

  Heuristic h_;
  std::vector<double> g_, rhs_;
  std::vector<Entry> heap_;
  double km_ = 0.0;
  State start_{}, goal_{};
  bool initialised_ = false;
  std::uint64_t expanded_ = 0;
};

}  // namespace hpcplan::search
