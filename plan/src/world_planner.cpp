#include "hpcplan/plan/world_planner.hpp"

#include <algorithm>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/bend_points.hpp"
#include "hpcplan/env/box_world.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/graph/continuous_grid.hpp"
#include "hpcplan/graph/visibility_graph.hpp"
#include "hpcplan/sampling/world_ompl.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/dense_visited_map.hpp"
#include "hpcplan/search/lazy_theta_star.hpp"
#include "hpcplan/tree/rrt.hpp"
#include "hpcplan/tree/rrt_connect.hpp"
#include "hpcplan/tree/rrt_star.hpp"

namespace hpcplan::plan {

const std::vector<std::string>& world_algorithms() {
  static const std::vector<std::string> names = {
      "astar",   "wastar", "dijkstra",    "thetastar",     "rrt",     "birrt",
      "rrtstar", "hybrid", "hybrid_pick", "hybrid_sample", "visgraph"};
  return names;
}

const std::vector<std::string>& world_ompl_planners() {
  return sampling::world_ompl_planner_names();
}

template <class W>
std::string path_problem(const W& world, const std::vector<env::Vec<W::kDim>>& path,
                         const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal) {
  if (path.empty()) return "the path is empty";
  if (!(path.front() == start)) return "the path does not begin exactly at the start";
  if (!(path.back() == goal)) return "the path does not end exactly at the goal";
  for (std::size_t i = 1; i < path.size(); ++i)
    if (!world.segment_free(path[i - 1], path[i]))
      return "segment " + std::to_string(i) + " of the path is in collision";
  if (path.size() == 1 && !world.point_free(path[0]))
    return "the path's only point is in collision";
  return "";
}

namespace {

constexpr std::uint64_t kDenseVertexLimit = std::uint64_t{1} << 26;
constexpr double kDefaultSpacing = 1.0 / 40;  // visgraph: bend spacing per world extent

template <class W>
void run_grid(const W& world, const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal,
              const WorldPlanOptions& o, WorldPlan<W::kDim>& plan) {
  using Grid = ContinuousGrid<W>;
  typename Grid::Config config;
  config.resolution = o.resolution;
  config.seed = o.seed;
  const bool hybrid = o.algo.starts_with("hybrid");
  if (hybrid && o.algo != "hybrid_pick") config.samples_per_expansion = o.samples_per_expansion;
  const Grid grid(world, start, goal, config);
  search::Options so;
  so.max_states = o.max_states;
  so.stop = Stop::after(hybrid ? o.time_s : 0.0, o.cancel);
  so.seed = o.seed;
  if (o.algo == "wastar") {
    if (!(o.weight >= 1.0)) throw InputError("--weight must be at least 1");
    so.weight = o.weight;
    so.reopen_closed = false;
  }
  if (o.algo == "hybrid" || o.algo == "hybrid_pick") so.frontier = search::Frontier::random;
  // Sampled successors differ at every expansion, so a reopened state would not regenerate
  // (and update) the children it had: closed states stay closed in the hybrids.
  if (hybrid) so.reopen_closed = false;
  // Lattice vertices get the dense visited array when it fits in a modest address range
  // (pages are only faulted in where the search goes).
  if (grid.vertex_count() <= kDenseVertexLimit) so.dense_keys = grid.vertex_count();
  using Map = search::DenseThenHashPolicy;
  search::Result<typename Grid::State> result;
  if (o.algo == "dijkstra") {
    result = search::best_first_search<Map>(grid, Grid::kStart, Grid::kGoal,
                                            search::ZeroHeuristic{}, so);
  } else {
    // Any-angle paths and the hybrids' sampled edges are not lattice moves: they need the
    // straight-line heuristic (consistent for every edge), not the lattice one.
    if (o.algo == "thetastar")
      result = search::lazy_theta_star<Map>(grid, Grid::kStart, Grid::kGoal,
                                            EuclideanToGoal<Grid>{&grid}, so);
    else if (hybrid)
      result = search::best_first_search<Map>(grid, Grid::kStart, Grid::kGoal,
                                              EuclideanToGoal<Grid>{&grid}, so);
    else
      result = search::best_first_search<Map>(grid, Grid::kStart, Grid::kGoal,
                                              LatticeToGoal<Grid>{&grid}, so);
  }
  plan.status = result.status;
  for (auto s : result.path) plan.path.push_back(grid.point(s));
  plan.expanded = result.counters.expanded;
  plan.tree_size = result.counters.peak_states;
}

template <class W>
void run_visibility(const W& world, const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal,
                    const WorldPlanOptions& o, WorldPlan<W::kDim>& plan) {
  using Graph = VisibilityGraph<W>;
  const double extent = world.bounds().largest_side();
  const double spacing = o.spacing > 0 ? o.spacing : extent * kDefaultSpacing;
  // Bends sit a millionth of the world off the obstacles: far outside the contact margin, far
  // below any length that matters.
  const Graph graph(world, start, goal, env::bend_points(world, spacing, 1e-6 * extent));
  search::Options so;
  so.max_states = o.max_states;
  so.dense_keys = graph.vertex_count();
  so.stop = Stop(o.cancel);
  const auto result = search::best_first_search<search::DenseThenHashPolicy>(
      graph, Graph::kStart, Graph::kGoal, EuclideanToGoal<Graph>{&graph}, so);
  plan.status = result.status;
  for (auto s : result.path) plan.path.push_back(graph.point(s));
  plan.expanded = result.counters.expanded;
  plan.tree_size = graph.vertex_count();
}

template <class W>
void run_tree(const W& world, const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal,
              const WorldPlanOptions& o, WorldPlan<W::kDim>& plan) {
  tree::TreeOptions to;
  to.seed = o.seed;
  to.stop = Stop::after(o.time_s, o.cancel);
  to.step = o.step;
  tree::TreeResult<W::kDim> r;
  if (o.algo == "rrt")
    r = tree::rrt(world, start, goal, to);
  else if (o.algo == "birrt")
    r = tree::rrt_connect(world, start, goal, to);
  else if (o.algo == "rrtstar")
    r = tree::rrt_star(world, start, goal, to);
  else
    r = sampling::solve_with_ompl(world, start, goal, o.algo.substr(5), o.time_s, o.seed, o.cancel);
  plan.status = r.status;
  plan.path = std::move(r.path);
  plan.tree_size = r.tree_size;
  plan.first_time_ms = r.first_time_ms;
}

}  // namespace

template <class W>
WorldPlan<W::kDim> plan_in_world(const W& world, const env::Vec<W::kDim>& start,
                                 const env::Vec<W::kDim>& goal, const WorldPlanOptions& o) {
  constexpr int D = W::kDim;
  tree::check_query(world, start, goal);
  const auto& names = world_algorithms();
  const bool grid = o.algo == "astar" || o.algo == "wastar" || o.algo == "dijkstra" ||
                    o.algo == "thetastar" || o.algo.starts_with("hybrid");
  const bool known = std::find(names.begin(), names.end(), o.algo) != names.end();
  if (o.algo.starts_with("ompl:")) {
    const auto& ompl = world_ompl_planners();
    if (std::find(ompl.begin(), ompl.end(), o.algo.substr(5)) == ompl.end()) {
      std::string list;
      for (const auto& n : ompl) list += (list.empty() ? "" : ", ") + n;
      throw InputError("unknown OMPL planner '" + o.algo.substr(5) + "' (known: " + list + ")");
    }
  } else if (!known) {
    throw InputError("unknown algorithm '" + o.algo +
                     "' (astar, wastar, dijkstra, thetastar, visgraph, rrt, birrt, rrtstar, "
                     "hybrid, hybrid_pick, hybrid_sample, ompl:<name>)");
  }
  if (!(o.time_s > 0) || !std::isfinite(o.time_s)) throw InputError("--time must be positive");
  if (o.step < 0 || !std::isfinite(o.step)) throw InputError("--step must not be negative");
  if (o.samples_per_expansion < 1) throw InputError("--samples must be at least 1");

  WorldPlan<D> plan;
  plan.algo = o.algo;
  const std::uint64_t checks0 = CheckCounter::this_thread();
  Stopwatch clock;
  if (o.spacing < 0 || !std::isfinite(o.spacing))
    throw InputError("--spacing must be a positive number");
  if (grid)
    run_grid(world, start, goal, o, plan);
  else if (o.algo == "visgraph")
    run_visibility(world, start, goal, o, plan);
  else
    run_tree(world, start, goal, o, plan);
  plan.plan_ms = clock.milliseconds();
  if (plan.status == Status::solved) {
    plan.raw_length = env::polyline_length<D>(plan.path);
    if (o.shortcut) plan.path = env::tighten_path(world, env::shortcut_path(world, plan.path));
    plan.length = env::polyline_length<D>(plan.path);
  }
  plan.time_ms = clock.milliseconds();
  plan.collision_checks = CheckCounter::this_thread() - checks0;
  if (plan.status == Status::solved) {
    if (const std::string why = path_problem(world, plan.path, start, goal); !why.empty())
      throw RunError("internal error: " + o.algo + " returned a bad path: " + why);
  } else {
    plan.path.clear();
  }
  return plan;
}

template WorldPlan<3> plan_in_world(const env::BoxWorld&, const env::Vec<3>&, const env::Vec<3>&,
                                    const WorldPlanOptions&);
template WorldPlan<2> plan_in_world(const env::SphereWorld&, const env::Vec<2>&, const env::Vec<2>&,
                                    const WorldPlanOptions&);
template std::string path_problem(const env::BoxWorld&, const std::vector<env::Vec<3>>&,
                                  const env::Vec<3>&, const env::Vec<3>&);
template std::string path_problem(const env::SphereWorld&, const std::vector<env::Vec<2>>&,
                                  const env::Vec<2>&, const env::Vec<2>&);

}  // namespace hpcplan::plan
