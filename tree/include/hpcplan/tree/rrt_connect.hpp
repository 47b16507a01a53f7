#pragma once
// RRT-Connect (Kuffner and LaValle 2000): a tree from the start and one from the goal take
// turns; one extends a step towards a sample, the other then steps greedily towards the new
// vertex until it reaches it (the trees join) or is blocked.
#include <array>

#include "hpcplan/tree/tree_common.hpp"

namespace hpcplan::tree {

template <env::World W>
TreeResult<W::kDim> rrt_connect(const W& world, const env::Vec<W::kDim>& start,
                                const env::Vec<W::kDim>& goal, const TreeOptions& o) {
  constexpr int D = W::kDim;
  TreeRun<D> run(world, start, goal, o);
  Tree<D> from_start, from_goal;
  from_start.add_root(start);
  from_goal.add_root(goal);
  Sampler<D> sampler(world.bounds(), start, goal, o.seed);
  TreeResult<D> r;
  auto done = [&](Status status, std::uint32_t a = 0, std::uint32_t b = 0) {
    r.status = status;
    r.counters.peak_states = from_start.points.size() + from_goal.points.size();
    r.counters.collision_checks = run.checks();
    if (status == Status::solved) {
      r.path = from_start.branch(a);
      auto back = from_goal.branch(b);
      // The joining vertex may be the same point in both trees.
      std::size_t skip = r.path.back() == back.back() ? 1 : 0;
      for (auto it = back.rbegin() + static_cast<std::ptrdiff_t>(skip); it != back.rend(); ++it)
        r.path.push_back(*it);
      r.cost = env::polyline_length<D>(r.path);
      r.hops = r.path.size() - 1;
    }
    r.counters.time_ms = run.clock.milliseconds();
    if (status == Status::solved)
      r.counters.first_solution_ms = r.counters.time_ms, r.counters.first_cost = r.cost;
    return r;
  };
  if (world.segment_free(start, goal)) return done(Status::solved, 0, 0);

  Tree<D>* a = &from_start;
  Tree<D>* b = &from_goal;
  for (;;) {
    if (const auto why = run.stop.poll()) return done(*why);
    if (o.max_samples && r.counters.samples >= o.max_samples) return done(Status::no_path);
    ++r.counters.samples;
    const env::Vec<D> target = sampler.uniform();
    const auto near = static_cast<std::uint32_t>(a->index.nearest(target));
    const env::Vec<D> q = steer<D>(a->points[near], target, run.step);
    if (world.segment_free(a->points[near], q)) {
      const std::uint32_t qa = a->add(q, near);
      // Connect: the other tree walks towards q.
      auto nb = static_cast<std::uint32_t>(b->index.nearest(q));
      for (;;) {
        const env::Vec<D> next = steer<D>(b->points[nb], q, run.step);
        if (!world.segment_free(b->points[nb], next)) break;
        if (next == q) {
          // Joined: the start tree's vertex and the goal tree's vertex meet at the same point.
          if (a == &from_start) return done(Status::solved, qa, nb);
          const std::uint32_t in_goal_tree = qa;
          return done(Status::solved, nb, in_goal_tree);
        }
        nb = b->add(next, nb);
      }
    }
    std::swap(a, b);
  }
}

}  // namespace hpcplan::tree
