// The fluid replanner's dispatch: the planner table (each entry with how it runs), the world
// built from the snapshot, the blocked ends moved, the planner run, its path smoothed and
// re-checked. The planners themselves live in fluid_grid_planners.cpp and
// fluid_particle_planners.cpp.
#include "hpcplan/plan/fluid_planner.hpp"

#include <algorithm>

#include "fluid_planners.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/fluid_escape.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/plan/world_planner.hpp"

namespace hpcplan::plan {

namespace {

using Vec3 = env::Vec<3>;
using fluid::Runner;

struct FluidEntry {
  PlannerSpec spec;
  Runner runner;
};

// The simulator's own planners; the registry's map3d planners run too (Runner::registry).
const std::vector<FluidEntry>& fluid_entries() {
  static const std::vector<FluidEntry> table = [] {
    const std::vector<std::string> sim{"sim"};
    return std::vector<FluidEntry>{
        {{"astar",
          "grid search",
          sim,
          {},
          "A* on the fluid's occupancy grid (26-connected, exact octile heuristic)"},
         Runner::astar_octile},
        {{"astar_euclid",
          "grid search",
          sim,
          {},
          "the same A* with seed 000's Euclidean heuristic"},
         Runner::astar_euclid},
        {{"dstar_lite",
          "incremental",
          sim,
          {},
          "D* Lite on the occupancy grid, repairing its search between replans"},
         Runner::dstar_lite},
        {{"rrtstar",
          "tree",
          sim,
          {"iterations", "step", "rewire_radius", "goal_radius", "goal_bias"},
          "seed 000's RRT* on the particle world (2,000 iterations, fixed rewiring radius)"},
         Runner::rrtstar},
    };
  }();
  return table;
}

bool searches_the_grid(Runner r) {
  return r == Runner::astar_octile || r == Runner::astar_euclid || r == Runner::dstar_lite;
}

// The world of this frame, rebuilt in the memory of the previous replan's (built on the first).
template <class World, class Config>
const World& rebuilt(std::unique_ptr<World>& world, const env::FluidSnapshot& snapshot,
                     const Config& config) {
  if (world)
    world->rebuild(snapshot, config);
  else
    world = std::make_unique<World>(snapshot, config);
  return *world;
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

// After the search: for a solved plan the smoother (in the planner's world), the exact
// re-check of the part that is checked, and the exempt legs around it.
template <class W>
void finish_plan(const W& world, const Vec3& robot, const Vec3& goal, const std::string& algo,
                 std::vector<Vec3> inner, Stopwatch& clock, FluidPlan& out) {
  out.search_us = clock.milliseconds() * 1e3;
  if (out.status != Status::solved) return;
  out.raw_length = env::polyline_length<3>(with_ends(robot, goal, inner));
  clock.restart();
  inner = env::shortcut_path(world, inner);
  out.smooth_us = clock.milliseconds() * 1e3;
  if (const std::string why = path_problem(world, inner, inner.front(), inner.back()); !why.empty())
    throw RunError("internal error: " + algo + " returned a bad path: " + why);
  out.path = with_ends(robot, goal, std::move(inner));
  out.cost = env::polyline_length<3>(out.path);
  out.hops = out.path.size() - 1;
}

}  // namespace

std::string_view failure_reason(Status status, BlockedEnd blocked) {
  switch (status) {
    case Status::solved:
      return "";
    case Status::no_path:
      return blocked == BlockedEnd::start  ? "start_blocked"
             : blocked == BlockedEnd::goal ? "goal_blocked"
                                           : "disconnected";
    case Status::budget_exceeded:
    case Status::timeout:
      return "budget";
    case Status::cancelled:
    case Status::interrupted:
      return "cancelled";
  }
  return "disconnected";
}

std::string_view to_string(Incremental i) {
  return i == Incremental::restart ? "restart" : i == Incremental::repair ? "repair" : "";
}

FluidReplanner::FluidReplanner(FluidPlanOptions options) : options_(std::move(options)) {
  const auto& table = fluid_entries();
  const auto entry = std::find_if(table.begin(), table.end(), [&](const FluidEntry& e) {
    return e.spec.name == options_.algo;
  });
  if (entry != table.end())
    runner_ = entry->runner;
  else if (PlannerRegistry::get().find("map3d", options_.algo))
    runner_ = Runner::registry;
  else
    throw InputError("unknown planner for the simulator: " + options_.algo + " (hpcplan planners " +
                     "--world sim lists them; map3d planners run too)");
  if (options_.escape_cells < 0) throw InputError("--escape must not be negative");
  if (!(options_.step >= 0) || !(options_.rewire_radius >= 0) || !(options_.goal_radius >= 0) ||
      !(options_.goal_bias >= 0 && options_.goal_bias <= 1) || !(options_.time_s > 0))
    throw InputError(
        "the RRT* step and radii must be >= 0, the goal bias in [0, 1] and the time positive");
  if (options_.world != "default" && options_.world != "particles" && options_.world != "occupancy")
    throw InputError("--world must be particles or occupancy, not " + options_.world);
  // world = occupancy puts every planner that is not a grid search on the grid through the
  // registry (rrtstar then is the registry's informed RRT*, as any map3d planner).
  on_grid_ = searches_the_grid(runner_) || options_.world == "occupancy";
  if (runner_ == Runner::dstar_lite) dstar_ = std::make_unique<fluid::DStarState>();
}
FluidReplanner::~FluidReplanner() = default;
FluidReplanner::FluidReplanner(FluidReplanner&&) noexcept = default;
FluidReplanner& FluidReplanner::operator=(FluidReplanner&&) noexcept = default;

FluidPlan FluidReplanner::plan(const env::FluidSnapshot& snapshot, const Vec3& robot,
                               const Vec3& goal, std::uint64_t replan_index,
                               std::stop_token cancel) {
  FluidPlan out;
  const Stopwatch total;
  const std::uint64_t checks0 = CheckCounter::this_thread();
  const std::uint64_t seed = splitmix64_mix(options_.seed * 0x9E3779B97F4A7C15ull + replan_index);
  if (on_grid_)
    plan_on_grid(snapshot, robot, goal, seed, std::move(cancel), out);
  else
    plan_on_particles(snapshot, robot, goal, seed, std::move(cancel), out);
  out.counters.time_ms = total.milliseconds();
  out.counters.collision_checks = CheckCounter::this_thread() - checks0;
  if (out.status != Status::solved) out.path.clear();
  return out;
}

void FluidReplanner::plan_on_grid(const env::FluidSnapshot& snapshot, const Vec3& robot,
                                  const Vec3& goal, std::uint64_t seed, std::stop_token cancel,
                                  FluidPlan& out) {
  const FluidPlanOptions& o = options_;
  Stopwatch clock;
  const env::OccupancyWorld& world = rebuilt(grid_world_, snapshot, o.occupancy);
  out.world_us = clock.milliseconds() * 1e3;
  const auto from = env::escape_cell(world, robot, o.escape_cells);
  const auto to = env::escape_cell(world, goal, o.escape_cells);
  if (!from || !to) {
    out.blocked = !from ? BlockedEnd::start : BlockedEnd::goal;
    out.status = Status::no_path;
    return;
  }
  out.start_escaped = world.cell_of(robot) != *from;
  out.goal_escaped = world.cell_of(goal) != *to;
  std::vector<Vec3> inner;
  clock.restart();
  if (searches_the_grid(runner_)) {
    const std::vector<std::uint32_t> cells = fluid::search_occupancy(
        runner_, world, world.index(*from), world.index(*to), dstar_.get(), cancel, out);
    for (std::uint32_t c : cells) inner.push_back(world.centre(world.cell_of_index(c)));
    // The exact ends replace the centres of their own cells (each lies in that cell, which is
    // free, so the segment to the next centre stays in free cells).
    if (!inner.empty()) {
      if (!out.start_escaped) inner.front() = robot;
      if (!out.goal_escaped) inner.back() = goal;
      // Start and goal in one cell: the straight segment between them stays in it (a goal that
      // had to escape is joined by the exempt last leg instead).
      if (inner.size() == 1 && !out.goal_escaped && !(robot == goal)) inner.push_back(goal);
    }
  } else {
    const Vec3 a = out.start_escaped ? world.centre(*from) : robot;
    const Vec3 b = out.goal_escaped ? world.centre(*to) : goal;
    inner = fluid::registry_planner(world, a, b, o, seed, world.cell_size()[0], cancel, out);
  }
  finish_plan(world, robot, goal, o.algo, std::move(inner), clock, out);
}

void FluidReplanner::plan_on_particles(const env::FluidSnapshot& snapshot, const Vec3& robot,
                                       const Vec3& goal, std::uint64_t seed, std::stop_token cancel,
                                       FluidPlan& out) {
  const FluidPlanOptions& o = options_;
  Stopwatch clock;
  const env::ParticleWorld& world = rebuilt(ball_world_, snapshot, o.particles);
  out.world_us = clock.milliseconds() * 1e3;
  const double reach = o.escape_cells * o.occupancy.cell;
  const auto a = env::escape_point(world, robot, reach);
  const auto b = env::escape_point(world, goal, reach);
  if (!a || !b) {
    out.blocked = !a ? BlockedEnd::start : BlockedEnd::goal;
    out.status = Status::no_path;
    return;
  }
  out.start_escaped = !(*a == robot);
  out.goal_escaped = !(*b == goal);
  clock.restart();
  std::vector<Vec3> inner =
      runner_ == Runner::rrtstar
          ? fluid::rrt_star_in_particles(world, *a, *b, o, seed, cancel, out)
          : fluid::registry_planner(world, *a, *b, o, seed, o.occupancy.cell, cancel, out);
  finish_plan(world, robot, goal, o.algo, std::move(inner), clock, out);
}

bool is_fluid_planner(std::string_view algo) {
  const PlannerRegistry& r = PlannerRegistry::get();
  return r.find("sim", algo) != nullptr || r.find("map3d", algo) != nullptr;
}

std::vector<PlannerSpec> fluid_planner_specs() {
  std::vector<PlannerSpec> specs;
  for (const FluidEntry& e : fluid_entries()) specs.push_back(e.spec);
  return specs;
}

}  // namespace hpcplan::plan
