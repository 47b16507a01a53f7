#pragma once
// RRT (LaValle 1998) with goal bias: grow one tree from the start by steps of at most eta
// towards uniform samples (the goal itself with probability goal_bias); stop when a new vertex
// sees the goal within one step, and join the goal exactly.
#include "hpcplan/tree/tree_common.hpp"

namespace hpcplan::tree {

template <env::World W>
TreeResult<W::kDim> rrt(const W& world, const env::Vec<W::kDim>& start,
                        const env::Vec<W::kDim>& goal, const TreeOptions& o) {
  constexpr int D = W::kDim;
  TreeRun<D> run(world, start, goal, o);
  TreeResult<D> r;
  Tree<D> tree;
  tree.add_root(start);
  Sampler<D> sampler(world.bounds(), start, goal, o.seed);
  auto done = [&](Status status) {
    r.status = status;
    r.counters.peak_states = tree.points.size();
    r.counters.collision_checks = run.checks();
    r.counters.time_ms = run.clock.milliseconds();
    if (status == Status::solved) {
      r.path = tree.branch(static_cast<std::uint32_t>(tree.points.size() - 1));
      r.cost = env::polyline_length<D>(r.path);
      r.hops = r.path.size() - 1;
      r.counters.first_solution_ms = r.counters.time_ms;
      r.counters.first_cost = r.cost;
    }
    return r;
  };
  if (world.segment_free(start, goal)) {
    tree.add(goal, 0);
    return done(Status::solved);
  }
  for (;;) {
    if (const auto why = run.stop.poll()) return done(*why);
    if (o.max_samples && r.counters.samples >= o.max_samples) return done(Status::no_path);
    ++r.counters.samples;
    const env::Vec<D> target = sampler.unit() < o.goal_bias ? goal : sampler.uniform();
    const auto near = static_cast<std::uint32_t>(tree.index.nearest(target));
    const env::Vec<D> q = steer<D>(tree.points[near], target, run.step);
    if (!world.segment_free(tree.points[near], q)) continue;
    const std::uint32_t added = tree.add(q, near);
    if (env::distance<D>(q, goal) <= run.step && world.segment_free(q, goal)) {
      if (!(q == goal)) tree.add(goal, added);
      return done(Status::solved);
    }
  }
}

}  // namespace hpcplan::tree
