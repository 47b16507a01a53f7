#pragma once
// A visibility graph over a continuous world's bend points (world/bend_points.hpp) for the
// search engine: the exact start and goal plus every bend point, each joined to every other it
// sees along a segment that is tangent at both ends. A* with the straight-line heuristic on it
// finds the shortest path through the sampled bends; its length is within the sampling error
// of the true shortest path's, and tightening (world/path_shortcut.hpp) slides the bends on.
//
// Every state may neighbour every other, so the graph is implicit: an expansion walks all
// points, skips non-tangent segments, asks the engine whether the edge could improve the
// neighbour's cost, and only then runs the exact segment test. That keeps the collision tests
// to the few edges that matter, not the n^2 of an explicit graph.
//
// Threads: a graph belongs to one run; the world it reads may be shared.
#include <cstdint>
#include <utility>
#include <vector>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/bend_points.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan {

template <env::World W>
class VisibilityGraph {
 public:
  static constexpr int D = W::kDim;
  using Point = env::Vec<D>;
  using State = std::uint64_t;
  using Move = std::uint64_t;  // the parent state
  using Cost = double;
  struct Hash {
    std::size_t operator()(State s) const noexcept { return splitmix64_mix(s); }
  };
  static constexpr Move kNoMove = ~std::uint64_t{0};
  static constexpr State kStart = 0;
  static constexpr State kGoal = 1;

  VisibilityGraph(const W& world, const Point& start, const Point& goal,
                  std::vector<env::BendPoint<D>> bends)
      : world_(world), start_(start), goal_(goal), bends_(std::move(bends)) {}

  std::uint64_t vertex_count() const { return bends_.size() + 2; }
  // This thread's checks: the world may be shared with other planning threads.
  std::uint64_t collision_checks() const { return CheckCounter::this_thread(); }
  const Point& goal_point() const { return goal_; }
  Point point(State s) const {
    return s == kStart ? start_ : s == kGoal ? goal_ : bends_[s - 2].point;
  }
  State predecessor(State, Move m) const { return m; }

  double checked_edge_length(State a, State b) const {
    const Point pa = point(a), pb = point(b);
    return world_.segment_free(pa, pb) ? env::distance<D>(pa, pb) : -1.0;
  }

  // Every successor, tested: for callers that cannot say which edges matter.
  template <class Emit>
  void for_each_successor(State s, Emit&& emit) const {
    for_each_successor(s, emit, [](State, double) { return true; });
  }

  // `worth(t, cost)` says whether reaching t at this cost could change the search; edges it
  // refuses are never collision-tested.
  template <class Emit, class Worth>
  void for_each_successor(State s, Emit&& emit, Worth&& worth) const {
    const Point p = point(s);
    const env::BendPoint<D>* at = s >= 2 ? &bends_[s - 2] : nullptr;
    const std::uint64_t n = vertex_count();
    for (State t = 1; t < n; ++t) {
      if (t == s) continue;
      const Point q = point(t);
      Point d;
      for (int k = 0; k < D; ++k) d[k] = q[k] - p[k];
      if (at && !at->tangent(d)) continue;
      if (t >= 2 && !bends_[t - 2].tangent(d)) continue;
      const double cost = env::distance<D>(p, q);
      if (!worth(t, cost)) continue;
      if (world_.segment_free(p, q)) emit(t, cost, s);
    }
  }

 private:
  const W& world_;
  Point start_, goal_;
  std::vector<env::BendPoint<D>> bends_;
};

}  // namespace hpcplan
