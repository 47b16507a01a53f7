#include "hpcplan/plan/world_planner.hpp"

#include <algorithm>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/bend_points.hpp"
#include "hpcplan/env/box_world.hpp"
#include "hpcplan/env/occupancy_world.hpp"
#include "hpcplan/env/particle_world.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/graph/continuous_grid.hpp"
#include "hpcplan/graph/visibility_graph.hpp"
#include "hpcplan/plan/planner_registry.hpp"
#include "hpcplan/sampling/ompl_planners.hpp"
#include "hpcplan/sampling/world_ompl.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/dense_visited_map.hpp"
#include "hpcplan/search/lazy_theta_star.hpp"
#include "hpcplan/tree/rrt.hpp"
#include "hpcplan/tree/rrt_connect.hpp"
#include "hpcplan/tree/rrt_star.hpp"

namespace hpcplan::plan {

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
  plan.counters = result.counters;
}

template <class W>
void run_visibility(const W& world, const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal,
                    const WorldPlanOptions& o, WorldPlan<W::kDim>& plan) {
  if constexpr (!requires { env::bend_points(world, 1.0, 0.0); }) {
    throw InputError("visgraph needs a world of boxes or spheres (it has no bend points here)");
  } else {
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
    plan.counters = result.counters;
    plan.counters.peak_states = graph.vertex_count();
  }
}

template <class R, class Plan>
void take_tree_result(R r, Plan& plan);

template <class W>
void run_tree(const W& world, const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal,
              const WorldPlanOptions& o, WorldPlan<W::kDim>& plan) {
  tree::TreeOptions to;
  to.seed = o.seed;
  to.stop = Stop::after(o.time_s, o.cancel);
  to.step = o.step;
  to.stop_at_first = o.stop_at_first;
  tree::TreeResult<W::kDim> r;
  if (o.algo == "rrt")
    r = tree::rrt(world, start, goal, to);
  else if (o.algo == "birrt")
    r = tree::rrt_connect(world, start, goal, to);
  else
    r = tree::rrt_star(world, start, goal, to);
  take_tree_result(std::move(r), plan);
}

template <class W>
void run_ompl(const W& world, const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal,
              const WorldPlanOptions& o, WorldPlan<W::kDim>& plan) {
  take_tree_result(sampling::solve_with_ompl(world, start, goal, o.algo.substr(5), o.time_s, o.seed,
                                             o.cancel, o.stop_at_first),
                   plan);
}

template <class R, class Plan>
void take_tree_result(R r, Plan& plan) {
  plan.status = r.status;
  plan.path = std::move(r.path);
  plan.counters = r.counters;
}

// How each planner runs; its registry entry sits beside it.
enum class Runner { grid, visibility, tree, ompl };

struct WorldEntry {
  PlannerSpec spec;
  Runner runner;
};

template <class W>
void run(Runner r, const W& world, const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal,
         const WorldPlanOptions& o, WorldPlan<W::kDim>& plan) {
  switch (r) {
    case Runner::grid:
      return run_grid(world, start, goal, o, plan);
    case Runner::visibility:
      return run_visibility(world, start, goal, o, plan);
    case Runner::tree:
      return run_tree(world, start, goal, o, plan);
    case Runner::ompl:
      return run_ompl(world, start, goal, o, plan);
  }
}

const std::vector<WorldEntry>& world_entries() {
  static const std::vector<WorldEntry> table = [] {
    const std::vector<std::string> worlds{"map3d", "sphere2d"};
    const std::vector<std::string> grid{"resolution", "max_states", "shortcut"};
    const std::vector<std::string> tree{"time", "seed", "step", "shortcut", "stop_at_first"};
    std::vector<WorldEntry> t = {
        {{"astar", "grid search", worlds, grid,
          "A* on the 3^D-1-connected grid over the world (exact edges, octile heuristic)"},
         Runner::grid},
        {{"wastar",
          "grid search",
          worlds,
          {"resolution", "weight", "max_states", "shortcut"},
          "weighted A* on the grid: cost <= w x the grid optimum"},
         Runner::grid},
        {{"dijkstra", "grid search", worlds, grid, "Dijkstra on the grid (the A* oracle)"},
         Runner::grid},
        {{"thetastar", "any-angle", worlds, grid,
          "Lazy Theta* on the grid: parents by line of sight"},
         Runner::grid},
        {{"visgraph",
          "visibility graph",
          worlds,
          {"spacing", "max_states", "shortcut"},
          "A* on the visibility graph of sampled obstacle edges (shortest paths)"},
         Runner::visibility},
        {{"rrt", "tree", worlds, tree, "RRT with goal bias, ends at the first path"}, Runner::tree},
        {{"birrt", "tree", worlds, tree, "RRT-Connect, ends at the first path"}, Runner::tree},
        {{"rrtstar", "tree", worlds, tree, "informed RRT*, refines until --time"}, Runner::tree},
        {{"hybrid",
          "hybrid",
          worlds,
          {"resolution", "samples", "seed", "time", "max_states", "shortcut"},
          "seed 003 hybrid: random open-list picks and sampled successors"},
         Runner::grid},
        {{"hybrid_pick",
          "hybrid",
          worlds,
          {"resolution", "seed", "time", "max_states", "shortcut"},
          "seed 003 hybrid: random open-list picks only"},
         Runner::grid},
        {{"hybrid_sample",
          "hybrid",
          worlds,
          {"resolution", "samples", "seed", "time", "max_states", "shortcut"},
          "seed 003 hybrid: sampled successors in A* order"},
         Runner::grid},
    };
    for (const sampling::OmplPlannerKind& k : sampling::ompl_planners())
      t.push_back({{"ompl:" + k.name, "ompl", worlds, tree, k.help}, Runner::ompl});
    return t;
  }();
  return table;
}

template <class W>
constexpr const char* setting_of() {
  return W::kDim == 3 ? "map3d" : "sphere2d";
}

}  // namespace

template <class W>
WorldPlan<W::kDim> plan_in_world(const W& world, const env::Vec<W::kDim>& start,
                                 const env::Vec<W::kDim>& goal, const WorldPlanOptions& o) {
  constexpr int D = W::kDim;
  tree::check_query(world, start, goal);
  PlannerRegistry::get().require(setting_of<W>(), o.algo);
  const auto entry = std::find_if(world_entries().begin(), world_entries().end(),
                                  [&](const WorldEntry& e) { return e.spec.name == o.algo; });
  if (!(o.time_s > 0) || !std::isfinite(o.time_s)) throw InputError("--time must be positive");
  if (o.step < 0 || !std::isfinite(o.step)) throw InputError("--step must not be negative");
  if (o.samples_per_expansion < 1) throw InputError("--samples must be at least 1");

  WorldPlan<D> plan;
  plan.algo = o.algo;
  const std::uint64_t checks0 = CheckCounter::this_thread();
  Stopwatch clock;
  if (o.spacing < 0 || !std::isfinite(o.spacing))
    throw InputError("--spacing must be a positive number");
  run(entry->runner, world, start, goal, o, plan);
  plan.plan_ms = clock.milliseconds();
  if (plan.status == Status::solved) {
    plan.raw_cost = env::polyline_length<D>(plan.path);
    if (o.shortcut) plan.path = env::tighten_path(world, env::shortcut_path(world, plan.path));
    plan.cost = env::polyline_length<D>(plan.path);
    plan.hops = plan.path.size() - 1;
  }
  plan.counters.time_ms = clock.milliseconds();
  plan.counters.collision_checks = CheckCounter::this_thread() - checks0;
  if (plan.status == Status::solved) {
    if (const std::string why = path_problem(world, plan.path, start, goal); !why.empty())
      throw RunError("internal error: " + o.algo + " returned a bad path: " + why);
  } else {
    plan.path.clear();
  }
  return plan;
}

std::vector<PlannerSpec> world_planner_specs() {
  std::vector<PlannerSpec> specs;
  for (const WorldEntry& e : world_entries()) specs.push_back(e.spec);
  return specs;
}

template WorldPlan<3> plan_in_world(const env::BoxWorld&, const env::Vec<3>&, const env::Vec<3>&,
                                    const WorldPlanOptions&);
template WorldPlan<2> plan_in_world(const env::SphereWorld&, const env::Vec<2>&, const env::Vec<2>&,
                                    const WorldPlanOptions&);
template WorldPlan<3> plan_in_world(const env::OccupancyWorld&, const env::Vec<3>&,
                                    const env::Vec<3>&, const WorldPlanOptions&);
template WorldPlan<3> plan_in_world(const env::ParticleWorld&, const env::Vec<3>&,
                                    const env::Vec<3>&, const WorldPlanOptions&);
template std::string path_problem(const env::OccupancyWorld&, const std::vector<env::Vec<3>>&,
                                  const env::Vec<3>&, const env::Vec<3>&);
template std::string path_problem(const env::ParticleWorld&, const std::vector<env::Vec<3>>&,
                                  const env::Vec<3>&, const env::Vec<3>&);
template std::string path_problem(const env::BoxWorld&, const std::vector<env::Vec<3>>&,
                                  const env::Vec<3>&, const env::Vec<3>&);
template std::string path_problem(const env::SphereWorld&, const std::vector<env::Vec<2>>&,
                                  const env::Vec<2>&, const env::Vec<2>&);

}  // namespace hpcplan::plan
