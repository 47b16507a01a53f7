// The occupancy planners of the fluid: A* (octile or the seed's Euclidean heuristic) and D*
// Lite, after a pocket check that settles walled-in ends with a small flood.
#include "fluid_planners.hpp"

#include "hpcplan/env/occupancy_diff.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/bounded_reach.hpp"
#include "hpcplan/search/dense_visited_map.hpp"

namespace hpcplan::plan::fluid {

namespace {

// States a pocket check may flood before giving up on finding the pocket closed (~0.3 ms).
constexpr std::size_t kPocketBudget = 4096;

std::vector<std::uint32_t> dstar_lite(const env::OccupancyWorld& world, const OccupancyGraph& graph,
                                      std::uint32_t s, std::uint32_t g, DStarState& inc,
                                      std::stop_token cancel, FluidPlan& out) {
  const bool restart = !inc.world || inc.dstar.goal() != g;
  if (restart) {
    if (inc.world)
      *inc.world = world;  // copy into the same storage
    else
      inc.world.emplace(world);
    inc.dstar.reset(graph, s, g);
    out.incremental = Incremental::restart;
  } else {
    const env::OccupancyDiff diff = env::occupancy_diff(*inc.world, world);
    out.changed_cells = diff.changed;
    *inc.world = world;
    inc.dstar.move_start(s);
    inc.dstar.edges_changed(graph, diff.touched);
    out.incremental = Incremental::repair;
  }
  inc.dstar.reset_counters();
  out.status = inc.dstar.compute(graph, Stop(cancel));
  out.counters.expanded = inc.dstar.expanded();
  std::vector<std::uint32_t> cells;
  if (out.status == Status::solved) {
    cells = inc.dstar.path(graph);
    out.search_cost = inc.dstar.distance_to_goal(s);
    if (cells.empty()) out.status = Status::no_path;
  }
  if (out.status == Status::cancelled) inc.world.reset();  // half-repaired: start over
  return cells;
}

}  // namespace

std::vector<std::uint32_t> search_occupancy(Runner runner, const env::OccupancyWorld& world,
                                            std::uint32_t s, std::uint32_t g, DStarState* dstar,
                                            std::stop_token cancel, FluidPlan& out) {
  const OccupancyGraph graph(world);
  // A pocket around either end (the moving fluid often walls one in) settles the replan with a
  // small flood instead of an exhaustive search.
  std::uint64_t flooded = 0;
  if (search::bounded_reach(graph, g, s, kPocketBudget, &flooded) == search::Reach::exhausted ||
      search::bounded_reach(graph, s, g, kPocketBudget, &flooded) == search::Reach::exhausted) {
    out.status = Status::no_path;
    out.counters.expanded = flooded;
    return {};
  }
  if (runner == Runner::dstar_lite) return dstar_lite(world, graph, s, g, *dstar, cancel, out);

  search::Options so;
  so.stop = Stop(cancel);
  so.dense_keys = graph.state_count();
  search::Result<std::uint32_t> r;
  if (runner == Runner::astar_euclid)
    r = search::best_first_search<search::DenseThenHashPolicy>(graph, s, g,
                                                               OccupancyEuclidean{world, g}, so);
  else
    r = search::best_first_search<search::DenseThenHashPolicy>(graph, s, g,
                                                               OccupancyOctile{world, g}, so);
  out.status = r.status;
  out.counters.expanded = r.counters.expanded;
  out.search_cost = r.cost;
  return std::move(r.path);
}

}  // namespace hpcplan::plan::fluid
