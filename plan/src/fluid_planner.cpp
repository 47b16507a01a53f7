#include "hpcplan/plan/fluid_planner.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/graph/occupancy_graph.hpp"
#include "hpcplan/plan/world_planner.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/bounded_reach.hpp"
#include "hpcplan/search/d_star_lite.hpp"
#include "hpcplan/search/dense_visited_map.hpp"
#include "hpcplan/tree/rrt_star.hpp"

namespace hpcplan::plan {

namespace {

using Vec3 = env::Vec<3>;
using Cell = env::OccupancyWorld::Cell;

// States a pocket check may flood before giving up on finding the pocket closed (~0.3 ms).
constexpr std::size_t kPocketBudget = 4096;

bool grid_algo(std::string_view a) {
  return a == "astar" || a == "astar_euclid" || a == "dstar_lite";
}

// The free cell nearest to p (by centre distance; ties: lowest index) within `reach` cells
// (Chebyshev) of p's cell, p's own cell first when it is free.
std::optional<Cell> escape_cell(const env::OccupancyWorld& w, const Vec3& p, int reach) {
  const Cell c = w.cell_of(p);
  if (!w.occupied(c)) return c;
  std::optional<Cell> best;
  double best_d2 = 0.0;
  for (int dz = -reach; dz <= reach; ++dz)
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        const Cell q{c[0] + dx, c[1] + dy, c[2] + dz};
        if (!w.inside(q) || w.occupied(q)) continue;
        const Vec3 m = w.centre(q);
        const double d2 = (m[0] - p[0]) * (m[0] - p[0]) + (m[1] - p[1]) * (m[1] - p[1]) +
                          (m[2] - p[2]) * (m[2] - p[2]);
        if (!best || d2 < best_d2 || (d2 == best_d2 && w.index(q) < w.index(*best)))
          best = q, best_d2 = d2;
      }
  w.count_checks(static_cast<std::uint64_t>((2 * reach + 1) * (2 * reach + 1) * (2 * reach + 1)));
  return best;
}

// The first free point on rays from p in the 26 lattice directions, stepping 0.05 out to
// `reach`; p itself when free.
template <class W>
std::optional<Vec3> escape_point(const W& w, const Vec3& p, double reach) {
  if (w.point_free(p)) return p;
  constexpr double kStep = 0.05;
  for (double r = kStep; r <= reach + 1e-12; r += kStep)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!dx && !dy && !dz) continue;
          const double n = std::sqrt(static_cast<double>(dx * dx + dy * dy + dz * dz));
          const Vec3 q{p[0] + r * dx / n, p[1] + r * dy / n, p[2] + r * dz / n};
          if (w.point_free(q)) return q;
        }
  return std::nullopt;
}

FailReason reason_of(Status s) {
  switch (s) {
    case Status::solved:
      return FailReason::none;
    case Status::no_path:
      return FailReason::disconnected;
    case Status::cancelled:
      return FailReason::cancelled;
    case Status::budget_exceeded:
    case Status::timeout:
      return FailReason::budget;
  }
  return FailReason::disconnected;
}

// Robot .. goal: the escape legs around the planner's path (only when they were taken).
std::vector<Vec3> with_ends(const Vec3& robot, const Vec3& goal, std::vector<Vec3> inner) {
  std::vector<Vec3> path;
  path.reserve(inner.size() + 2);
  if (inner.empty() || !(inner.front() == robot)) path.push_back(robot);
  path.insert(path.end(), inner.begin(), inner.end());
  if (!(path.back() == goal)) path.push_back(goal);
  return path;
}

// A map3d planner of the registry through plan_in_world, from a to b in `world`.
template <class W>
void run_registry_planner(const W& world, const Vec3& a, const Vec3& b, const FluidPlanOptions& o,
                          std::uint64_t seed, double resolution, std::stop_token cancel,
                          FluidPlan& out, std::vector<Vec3>& inner) {
  WorldPlanOptions wo;
  wo.algo = o.algo;
  wo.seed = seed;
  wo.time_s = o.time_s;
  wo.resolution = resolution;
  wo.cancel = std::move(cancel);
  const auto r = plan_in_world(world, a, b, wo);
  out.status = r.status;
  out.expanded = r.counters.expanded + r.counters.samples;
  inner = r.path;
}

// After the search: the reason, and for a solved plan the smoother (in the planner's world),
// the exact re-check of the part that is checked, and the exempt legs around it.
template <class W>
void finish_plan(const W& world, const Vec3& robot, const Vec3& goal, const std::string& algo,
                 std::vector<Vec3> inner, Stopwatch& clock, FluidPlan& out) {
  out.search_us = clock.milliseconds() * 1e3;
  out.reason = reason_of(out.status);
  if (out.status != Status::solved) return;
  out.raw_length = env::polyline_length<3>(with_ends(robot, goal, inner));
  clock.restart();
  inner = env::shortcut_path(world, inner);
  out.smooth_us = clock.milliseconds() * 1e3;
  if (const std::string why = path_problem(world, inner, inner.front(), inner.back()); !why.empty())
    throw RunError("internal error: " + algo + " returned a bad path: " + why);
  out.path = with_ends(robot, goal, std::move(inner));
  out.length = env::polyline_length<3>(out.path);
}

}  // namespace

std::string_view to_string(FailReason r) {
  switch (r) {
    case FailReason::none:
      return "";
    case FailReason::start_blocked:
      return "start_blocked";
    case FailReason::goal_blocked:
      return "goal_blocked";
    case FailReason::disconnected:
      return "disconnected";
    case FailReason::budget:
      return "budget";
    case FailReason::cancelled:
      return "cancelled";
  }
  return "";
}

struct FluidReplanner::Incremental {
  using Graph = OccupancyGraph;
  // The heuristic reads only cell coordinates, which every frame's grid shares (the box does
  // not change), so it may look at whichever frame `world` holds.
  struct Octile {
    const std::optional<env::OccupancyWorld>* world;
    LatticeCost operator()(std::uint32_t a, std::uint32_t b) const {
      return full_connectivity_free_distance(occupancy_delta(**world, a, b));
    }
  };
  std::optional<env::OccupancyWorld> world;  // the frame the search is consistent with
  // One object for the whole run: a restart resets it, keeping its arrays' memory.
  search::DStarLite<Graph, Octile> dstar{Octile{&world}};
};

FluidReplanner::FluidReplanner(FluidPlanOptions options) : options_(std::move(options)) {
  if (!is_fluid_planner(options_.algo))
    throw InputError("unknown planner for the simulator: " + options_.algo + " (hpcplan planners " +
                     "--world sim lists them; map3d planners run too)");
  if (options_.escape_cells < 0) throw InputError("--escape must not be negative");
  if (!(options_.step >= 0) || !(options_.rewire_radius >= 0) || !(options_.goal_radius >= 0) ||
      !(options_.goal_bias >= 0 && options_.goal_bias <= 1) || !(options_.time_s > 0))
    throw InputError(
        "the RRT* step and radii must be >= 0, the goal bias in [0, 1] and the time positive");
  if (options_.world != "default" && options_.world != "particles" && options_.world != "occupancy")
    throw InputError("--world must be particles or occupancy, not " + options_.world);
  if (options_.algo == "dstar_lite") incremental_ = std::make_unique<Incremental>();
}
FluidReplanner::~FluidReplanner() = default;
FluidReplanner::FluidReplanner(FluidReplanner&&) noexcept = default;
FluidReplanner& FluidReplanner::operator=(FluidReplanner&&) noexcept = default;

FluidPlan FluidReplanner::plan(const env::FluidSnapshot& snapshot, const Vec3& robot,
                               const Vec3& goal, std::uint64_t replan_index,
                               std::stop_token cancel) {
  const FluidPlanOptions& o = options_;
  FluidPlan out;
  const Stopwatch total;
  const std::uint64_t checks0 = CheckCounter::this_thread();
  const std::uint64_t seed = splitmix64_mix(o.seed * 0x9E3779B97F4A7C15ull + replan_index);
  const bool on_grid = grid_algo(o.algo) || o.world == "occupancy";
  auto finish = [&](FluidPlan& p) -> FluidPlan& {
    p.total_us = total.milliseconds() * 1e3;
    p.collision_checks = CheckCounter::this_thread() - checks0;
    if (p.status != Status::solved) p.path.clear();
    return p;
  };

  if (on_grid) {
    Stopwatch clock;
    if (grid_world_)
      grid_world_->rebuild(snapshot, o.occupancy);
    else
      grid_world_ = std::make_unique<env::OccupancyWorld>(snapshot, o.occupancy);
    const env::OccupancyWorld& world = *grid_world_;
    out.world_us = clock.milliseconds() * 1e3;
    const auto from = escape_cell(world, robot, o.escape_cells);
    const auto to = escape_cell(world, goal, o.escape_cells);
    if (!from || !to) {
      out.reason = !from ? FailReason::start_blocked : FailReason::goal_blocked;
      out.status = Status::no_path;
      return finish(out);
    }
    out.start_escaped = world.cell_of(robot) != *from;
    out.goal_escaped = world.cell_of(goal) != *to;
    const Vec3 a = out.start_escaped ? world.centre(*from) : robot;
    const Vec3 b = out.goal_escaped ? world.centre(*to) : goal;
    std::vector<Vec3> inner;
    clock.restart();
    if (grid_algo(o.algo)) {
      const OccupancyGraph graph(world);
      const std::uint32_t s = world.index(*from), g = world.index(*to);
      std::vector<std::uint32_t> cells;
      // A pocket around either end (the moving fluid often walls one in) settles the replan
      // with a small flood instead of an exhaustive search.
      std::uint64_t flooded = 0;
      const bool pocket =
          search::bounded_reach(graph, g, s, kPocketBudget, &flooded) == search::Reach::exhausted ||
          search::bounded_reach(graph, s, g, kPocketBudget, &flooded) == search::Reach::exhausted;
      if (pocket) {
        out.status = Status::no_path;
        out.expanded = flooded;
      } else if (o.algo == "dstar_lite") {
        Incremental& inc = *incremental_;
        const bool restart = !inc.world || inc.dstar.goal() != g;
        if (restart) {
          if (inc.world)
            *inc.world = world;  // copy into the same storage
          else
            inc.world.emplace(world);
          inc.dstar.reset(graph, s, g);
          out.incremental = "restart";
        } else {
          // Cells whose occupancy changed; every cell next to one of them has changed edges.
          std::vector<std::uint32_t> touched;
          const auto n = world.cells_per_axis();
          for (std::uint32_t i = 0; i < world.cell_count(); ++i) {
            if (world.occupied(i) == inc.world->occupied(i)) continue;
            ++out.changed_cells;
            const Cell c = world.cell_of_index(i);
            for (int dz = -1; dz <= 1; ++dz)
              for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                  const Cell q{c[0] + dx, c[1] + dy, c[2] + dz};
                  if (q[0] >= 0 && q[1] >= 0 && q[2] >= 0 && q[0] < n[0] && q[1] < n[1] &&
                      q[2] < n[2])
                    touched.push_back(world.index(q));
                }
          }
          std::sort(touched.begin(), touched.end());
          touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
          *inc.world = world;
          inc.dstar.move_start(s);
          inc.dstar.edges_changed(graph, touched);
          out.incremental = "repair";
        }
        inc.dstar.reset_counters();
        out.status = inc.dstar.compute(graph, Stop(cancel));
        out.expanded = inc.dstar.expanded();
        if (out.status == Status::solved) {
          cells = inc.dstar.path(graph);
          out.search_cost = inc.dstar.distance_to_goal(s);
        }
        if (out.status == Status::solved && cells.empty()) out.status = Status::no_path;
        if (out.status == Status::cancelled) inc.world.reset();  // half-repaired: start over
      } else {
        search::Options so;
        so.stop = Stop(cancel);
        so.dense_keys = graph.state_count();
        search::Result<std::uint32_t> r;
        if (o.algo == "astar_euclid")
          r = search::best_first_search<search::DenseThenHashPolicy>(
              graph, s, g, OccupancyEuclidean{world, g}, so);
        else
          r = search::best_first_search<search::DenseThenHashPolicy>(graph, s, g,
                                                                     OccupancyOctile{world, g}, so);
        out.status = r.status;
        out.expanded = r.counters.expanded;
        out.search_cost = r.cost;
        cells = std::move(r.path);
      }
      for (std::uint32_t c : cells) inner.push_back(world.centre(world.cell_of_index(c)));
      // The exact ends replace the centres of their own cells (each lies in that cell, which
      // is free, so the segment to the next centre stays in free cells).
      if (!inner.empty()) {
        if (!out.start_escaped) inner.front() = robot;
        if (!out.goal_escaped) inner.back() = goal;
        // Start and goal in one cell: the straight segment between them stays in it (a goal
        // that had to escape is joined by the exempt last leg instead).
        if (inner.size() == 1 && !out.goal_escaped && !(robot == goal)) inner.push_back(goal);
      }
    } else {
      run_registry_planner(world, a, b, o, seed, world.cell_size()[0], cancel, out, inner);
    }
    finish_plan(world, robot, goal, o.algo, std::move(inner), clock, out);
    return finish(out);
  }

  // Continuous: the particle world.
  Stopwatch clock;
  if (ball_world_)
    ball_world_->rebuild(snapshot, o.particles);
  else
    ball_world_ = std::make_unique<env::ParticleWorld>(snapshot, o.particles);
  const env::ParticleWorld& world = *ball_world_;
  out.world_us = clock.milliseconds() * 1e3;
  const double reach = o.escape_cells * o.occupancy.cell;
  const auto a = escape_point(world, robot, reach);
  const auto b = escape_point(world, goal, reach);
  if (!a || !b) {
    out.reason = !a ? FailReason::start_blocked : FailReason::goal_blocked;
    out.status = Status::no_path;
    return finish(out);
  }
  out.start_escaped = !(*a == robot);
  out.goal_escaped = !(*b == goal);
  std::vector<Vec3> inner;
  clock.restart();
  if (o.algo == "rrtstar") {
    tree::TreeOptions to;
    to.seed = seed;
    to.step = o.step;
    to.goal_bias = o.goal_bias;
    to.max_samples = o.iterations;
    to.informed = false;
    to.rewire_radius = o.rewire_radius;
    to.goal_radius = o.goal_radius;
    to.stop = Stop(cancel);
    auto r = tree::rrt_star(world, *a, *b, to);
    out.status = r.status;
    out.expanded = r.counters.samples;
    // A fixed budget that ends without the goal is the seed's "budget" failure.
    if (r.status == Status::no_path) out.status = Status::budget_exceeded;
    inner = std::move(r.path);
  } else {
    run_registry_planner(world, *a, *b, o, seed, o.occupancy.cell, cancel, out, inner);
  }
  finish_plan(world, robot, goal, o.algo, std::move(inner), clock, out);
  return finish(out);
}

bool is_fluid_planner(std::string_view algo) {
  const PlannerRegistry& r = PlannerRegistry::get();
  return r.find("sim", algo) != nullptr || r.find("map3d", algo) != nullptr;
}

std::vector<PlannerSpec> fluid_planner_specs() {
  const std::vector<std::string> sim{"sim"};
  return {
      {"astar",
       "grid search",
       sim,
       {},
       "A* on the fluid's occupancy grid (26-connected, exact octile heuristic)"},
      {"astar_euclid", "grid search", sim, {}, "the same A* with seed 000's Euclidean heuristic"},
      {"dstar_lite",
       "incremental",
       sim,
       {},
       "D* Lite on the occupancy grid, repairing its search between replans"},
      {"rrtstar",
       "tree",
       sim,
       {"iterations", "step", "rewire_radius", "goal_radius", "goal_bias"},
       "seed 000's RRT* on the particle world (2,000 iterations, fixed rewiring radius)"},
  };
}

}  // namespace hpcplan::plan
