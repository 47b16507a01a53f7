#include "hpcplan/plan/planner_registry.hpp"

#include <stdexcept>

#include "hpcplan/core/error.hpp"

namespace hpcplan::plan {

namespace {

ParamSpec real(std::string name, double lo, double hi, std::string def, std::string help) {
  return {std::move(name), ParamType::real, lo, hi, {}, std::move(def), std::move(help)};
}
ParamSpec integer(std::string name, double lo, double hi, std::string def, std::string help) {
  return {std::move(name), ParamType::integer, lo, hi, {}, std::move(def), std::move(help)};
}
ParamSpec flag(std::string name, std::string help) {
  return {std::move(name), ParamType::flag, 0, 1, {}, "false", std::move(help)};
}
ParamSpec choice(std::string name, std::vector<std::string> choices, std::string help) {
  std::string def = choices.front();
  return {std::move(name), ParamType::choice, 0, 0, std::move(choices),
          std::move(def),  std::move(help)};
}

// The parameters planners declare, once: the CLI's ranges and help come from here.
std::vector<ParamSpec> parameter_table() {
  return {
      // The GOG lattice (hpcplan grid).
      real("weight", 1, 1e9, "2", "weighted A*: f = g + w h, cost <= w x optimal"),
      choice("heuristic", {"lattice", "euclidean"},
             "lattice: exact obstacle-free lattice cost; euclidean: straight line"),
      choice("connectivity", {"seed", "full"}, "seed: 1 or 2 axes per move; full: any (d <= 4)"),
      integer("max_states", 0, 1.8e19, "0",
              "stop with budget_exceeded beyond this many stored states (0: the grid derives it "
              "from available memory; worlds: none)"),
      real("time_limit", 0, 1e9, "0", "seconds (0 = none)"),
      flag("no_jump_points", "2D A*: expand every lattice state, not only the jump points"),
      choice("engine", {"auto", "dense", "sparse"},
             "dense: bit-parallel BFS / Dijkstra over the whole lattice; sparse: the best-first "
             "engine; auto: dense for bfs and dijkstra when the lattice fits the memory budget "
             "(and the build compiles its dimension: all 16 unless HPCPLAN_DENSE_DIMS)"),
      integer("threads", 0, 4096, "0",
              "dense engine: OpenMP threads per process (0: this process's share of the cores)"),
      integer("slab_layers", 0, 65535, "0",
              "dense engine: sections (layers, or rows of layers past 16 layers per worker) "
              "per block, blocks dealt round the ranks and threads (0: about 4 blocks per "
              "thread, at least 4 sections each)"),
      flag("contiguous_slabs",
           "dense engine: one slab per rank and thread, balanced by free states, instead of "
           "dealt blocks"),
      integer("memory_budget", 0, 1.8e19, "0",
              "dense engine: bytes each process may use (0: what --max-states buys the sparse "
              "engine, by default half the available memory)"),
      // Box maps and sphere worlds (hpcplan map3d / sphere2d).
      real("resolution", 1e-9, 1e9, "0.1 (map3d), 0.25 (sphere2d)", "grid spacing of the searches"),
      real("spacing", 0, 1e9, "0",
           "bend points this far apart along obstacle edges (0 = a 40th of "
           "the world's largest side)"),
      integer("seed", 0, 1.8e19, "1", "random seed"),
      real("time", 1e-6, 1e9, "1",
           "seconds: anytime planners refine until then, the others give up then"),
      real("step", 0, 1e9, "0", "tree planners' steering distance (0 = a twentieth of the world)"),
      integer("samples", 1, 1e6, "10", "hybrid: random points drawn per expansion"),
      flag("shortcut", "string pulling and tightening after planning"),
      flag("stop_at_first",
           "tree and OMPL planners: end at the first path, anytime ones too (--time is then "
           "only a guard)"),
      // The simulator's RRT* (hpcplan sim): seed 000's values are the defaults.
      integer("iterations", 1, 1e9, "2000", "RRT* samples per replan"),
      real("rewire_radius", 0, 1e9, "0.6", "RRT*: rewire within this radius (0: shrinking r(n))"),
      real("goal_radius", 0, 1e9, "0.3", "RRT*: join the goal from within this distance"),
      real("goal_bias", 0, 1, "0.1", "RRT*: probability of sampling the goal"),
      // The OMPL harness (hpcplan ompl).
      real("grid_weight", 1, 1e9, "1", "the grid planner's weight (1 = A*)"),
      flag("no_shortcut", "the grid planner keeps its lattice path"),
      real("smoothing_budget", 0, 1e6, "1",
           "the grid planner's smoothing time as a multiple of its search time (0 = until it "
           "converges)"),
  };
}

}  // namespace

std::string ParamSpec::option() const {
  std::string o = "--" + name;
  for (char& c : o)
    if (c == '_') c = '-';
  return o;
}

PlannerRegistry::PlannerRegistry() : params_(parameter_table()) {
  for (auto* specs :
       {&grid_planner_specs, &world_planner_specs, &ompl_harness_specs, &fluid_planner_specs})
    for (PlannerSpec& s : specs()) planners_.push_back(std::move(s));
  // Every declared parameter must exist: a typo here would otherwise surface as a missing
  // option at run time.
  for (const PlannerSpec& s : planners_)
    for (const std::string& p : s.params) (void)param(p);
}

const PlannerRegistry& PlannerRegistry::get() {
  static const PlannerRegistry registry;
  return registry;
}

const ParamSpec& PlannerRegistry::param(std::string_view name) const {
  for (const ParamSpec& p : params_)
    if (p.name == name) return p;
  throw std::logic_error("planner parameter '" + std::string(name) + "' is not declared");
}

const PlannerSpec* PlannerRegistry::find(std::string_view world, std::string_view name) const {
  for (const PlannerSpec& s : planners_)
    if (s.name == name)
      for (const std::string& w : s.worlds)
        if (w == world) return &s;
  return nullptr;
}

std::vector<std::string> PlannerRegistry::names(std::string_view world) const {
  std::vector<std::string> out;
  for (const PlannerSpec& s : planners_)
    for (const std::string& w : s.worlds)
      if (w == world) out.push_back(s.name);
  return out;
}

const PlannerSpec& PlannerRegistry::require(std::string_view world, std::string_view name) const {
  if (const PlannerSpec* s = find(world, name)) return *s;
  std::string list;
  for (const std::string& n : names(world)) list += (list.empty() ? "" : ", ") + n;
  throw InputError("unknown algorithm '" + std::string(name) + "' for " + std::string(world) +
                   " (known: " + list + "; see hpcplan planners)");
}

}  // namespace hpcplan::plan
