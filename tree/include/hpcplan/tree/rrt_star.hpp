#pragma once
// RRT* (Karaman and Frazzoli 2011): RRT whose new vertex takes the cheapest visible parent
// among its neighbours within r(n) = min(gamma (log n / n)^(1/d), eta), and then offers itself
// as parent to those neighbours (rewiring). The goal is a vertex once a step reaches it, so
// rewiring keeps shortening the returned path; after the first path, samples may come from
// the informed ellipsoid only (Informed RRT*), which is where improvements can be. Seed 000's
// variant fixes the rewiring radius and the goal's capture radius (TreeOptions).
#include <cmath>

#include "hpcplan/tree/tree_common.hpp"

namespace hpcplan::tree {

template <env::World W>
TreeResult<W::kDim> rrt_star(const W& world, const env::Vec<W::kDim>& start,
                             const env::Vec<W::kDim>& goal, const TreeOptions& o) {
  constexpr int D = W::kDim;
  TreeRun<D> run(world, start, goal, o);
  const double gamma = o.gamma_factor * 2.0 * std::pow(1.0 + 1.0 / D, 1.0 / D) *
                       std::pow(world.free_volume() / Sampler<D>::unit_ball_volume(), 1.0 / D);

  Tree<D> tree;
  auto& points = tree.points;
  auto& parent = tree.parent;
  auto& index = tree.index;
  std::vector<double> cost;                          // per vertex: path length from the start
  std::vector<std::vector<std::uint32_t>> children;  // to pass cost savings down a subtree
  auto add = [&](const env::Vec<D>& p, std::uint32_t from, double c) {
    const std::uint32_t i = tree.add(p, from);
    cost.push_back(c);
    children.emplace_back();
    if (i != from) children[from].push_back(i);
    return i;
  };
  // Moves vertex v under new parent p and lowers the cost of its whole subtree by the saving.
  auto reparent = [&](std::uint32_t v, std::uint32_t p, double c) {
    auto& siblings = children[parent[v]];
    siblings.erase(std::find(siblings.begin(), siblings.end(), v));
    parent[v] = p;
    children[p].push_back(v);
    const double saving = cost[v] - c;
    std::vector<std::uint32_t> stack{v};
    while (!stack.empty()) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      cost[u] -= saving;
      for (std::uint32_t w : children[u]) stack.push_back(w);
    }
  };

  const double goal_radius = o.goal_radius > 0.0 ? o.goal_radius : run.step;
  TreeResult<D> r;
  add(start, 0, 0.0);
  std::uint32_t goal_vertex = UINT32_MAX;
  if (world.segment_free(start, goal)) goal_vertex = add(goal, 0, env::distance<D>(start, goal));
  Sampler<D> sampler(world.bounds(), start, goal, o.seed);
  typename PointIndex<D>::Matches near;
  auto solved = [&] { return goal_vertex != UINT32_MAX; };

  Status status = Status::timeout;
  const bool straight = solved();  // the straight segment is optimal: nothing to refine
  while (!straight && !(solved() && o.stop_at_first)) {
    if (const auto why = run.stop.poll()) {
      status = *why;
      break;
    }
    if (o.max_samples && r.counters.samples >= o.max_samples) {
      status = Status::no_path;
      break;
    }
    ++r.counters.samples;
    const double best = solved() ? cost[goal_vertex] : std::numeric_limits<double>::infinity();
    env::Vec<D> target;
    if (!solved() && sampler.unit() < o.goal_bias)
      target = goal;
    else
      target = o.informed ? sampler.informed(best) : sampler.uniform();
    const auto nearest = static_cast<std::uint32_t>(index.nearest(target));
    const env::Vec<D> q = steer<D>(points[nearest], target, run.step);
    if (q == goal && solved()) continue;
    if (!world.segment_free(points[nearest], q)) continue;

    const double n = static_cast<double>(points.size());
    const double radius =
        o.rewire_radius > 0.0
            ? o.rewire_radius
            : std::min(gamma * std::pow(std::log(n + 1) / (n + 1), 1.0 / D), run.step);
    index.within(q, radius, near);
    // Cheapest parent among the neighbours that see q (the nearest vertex always does).
    std::uint32_t best_parent = nearest;
    double best_cost = cost[nearest] + env::distance<D>(points[nearest], q);
    for (const auto& [i, d2] : near) {
      const auto v = static_cast<std::uint32_t>(i);
      const double c = cost[v] + std::sqrt(d2);
      if (v != nearest && c < best_cost && world.segment_free(points[v], q))
        best_parent = v, best_cost = c;
    }
    const std::uint32_t qv = add(q, best_parent, best_cost);
    for (const auto& [i, d2] : near) {
      const auto v = static_cast<std::uint32_t>(i);
      const double c = best_cost + std::sqrt(d2);
      if (v != best_parent && c < cost[v] - 1e-12 && world.segment_free(q, points[v]))
        reparent(v, qv, c);
    }
    if (q == goal) {
      goal_vertex = qv;
    } else if (!solved() && env::distance<D>(q, goal) <= goal_radius &&
               world.segment_free(q, goal)) {
      goal_vertex = add(goal, qv, best_cost + env::distance<D>(q, goal));
    }
    if (solved() && r.counters.first_solution_ms < 0) {
      r.counters.first_solution_ms = run.clock.milliseconds();
      r.counters.first_cost = cost[goal_vertex];
    }
  }
  if (solved()) {
    status = Status::solved;
    r.path = tree.branch(goal_vertex);
    r.cost = env::polyline_length<D>(r.path);
    r.hops = r.path.size() - 1;
    if (r.counters.first_solution_ms < 0)
      r.counters.first_solution_ms = run.clock.milliseconds(), r.counters.first_cost = r.cost;
  }
  r.status = status;
  r.counters.peak_states = points.size();
  r.counters.collision_checks = run.checks();
  r.counters.time_ms = run.clock.milliseconds();
  return r;
}

}  // namespace hpcplan::tree
