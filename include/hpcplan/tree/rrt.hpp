#pragma once
// RRT (LaValle 1998) with goal bias: grow one tree from the start by steps of at most eta
// towards uniform samples (the goal itself with probability goal_bias); stop when a new vertex
// sees the goal within one step, and join the goal exactly.
#include "hpcplan/tree/point_index.hpp"
#include "hpcplan/tree/tree_common.hpp"

namespace hpcplan::tree {

template <world::World W>
TreeResult<W::kDim> rrt(const W& world, const world::Vec<W::kDim>& start,
                        const world::Vec<W::kDim>& goal, const TreeOptions& o) {
  constexpr int D = W::kDim;
  check_query(world, start, goal);
  Stopwatch clock;
  const std::uint64_t checks0 = world.collision_checks();
  const double step = o.step > 0 ? o.step : default_step<D>(world.bounds());
  TreeResult<D> r;
  std::vector<world::Vec<D>> points;
  std::vector<std::uint32_t> parent;
  PointIndex<D> index(points);
  auto add = [&](const world::Vec<D>& p, std::uint32_t from) {
    points.push_back(p);
    parent.push_back(from);
    index.added(points.size() - 1);
    return static_cast<std::uint32_t>(points.size() - 1);
  };
  add(start, 0);
  Sampler<D> sampler(world.bounds(), start, goal, o.seed);
  auto done = [&](search::Status status) {
    r.status = status;
    r.tree_size = points.size();
    r.collision_checks = world.collision_checks() - checks0;
    r.time_ms = clock.milliseconds();
    if (status == search::Status::solved) {
      r.path = branch<D>(points, parent, static_cast<std::uint32_t>(points.size() - 1));
      r.length = path_length<D>(r.path);
      r.first_time_ms = r.time_ms;
      r.first_length = r.length;
    }
    return r;
  };
  if (world.segment_free(start, goal)) {
    add(goal, 0);
    return done(search::Status::solved);
  }
  for (;;) {
    if ((r.samples & 255) == 0 && clock.seconds() > o.time_limit_s)
      return done(search::Status::timeout);
    if (o.max_samples && r.samples >= o.max_samples) return done(search::Status::no_path);
    ++r.samples;
    const world::Vec<D> target = sampler.unit() < o.goal_bias ? goal : sampler.uniform();
    const auto near = static_cast<std::uint32_t>(index.nearest(target));
    const world::Vec<D> q = steer<D>(points[near], target, step);
    if (!world.segment_free(points[near], q)) continue;
    const std::uint32_t added = add(q, near);
    if (world::distance<D>(q, goal) <= step && world.segment_free(q, goal)) {
      if (!(q == goal)) add(goal, added);
      return done(search::Status::solved);
    }
  }
}

}  // namespace hpcplan::tree
