#include "hpcplan/plan/ompl_benchmark.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/stride/STRIDE.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/progress.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/benchmark_spaces.hpp"
#include "hpcplan/env/gog_world.hpp"
#include "hpcplan/env/hypercube.hpp"
#include "hpcplan/graph/cspace_graph.hpp"
#include "hpcplan/plan/cspace_grid_planner.hpp"
#include "hpcplan/plan/grid_astar_planner.hpp"
#include "hpcplan/plan/grid_problem.hpp"
#include "hpcplan/plan/planner_registry.hpp"
#include "hpcplan/sampling/cspace_ompl.hpp"
#include "hpcplan/sampling/gog_space.hpp"
#include "hpcplan/sampling/ompl_planners.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace hpcplan::plan {

// The harness drives the OMPL adapters of the sampling layer throughout.
using namespace sampling;

namespace {

// What one invocation plans on: the GOG field or a configuration space, with what the
// harness needs of either (the space information every planner shares, the check counter,
// the independent path re-check, the query).
struct BenchWorld {
  std::optional<GogSpace> gog;
  std::optional<CSpaceOmpl> cspace;
  int cells = 0;       // c-space: the lattice's cells per axis
  double range = 0.0;  // > 0: every planner's "range" (the hypercube's half corridor width)
  std::vector<double> start, goal;

  const ob::SpaceInformationPtr& si() const { return gog ? gog->si : cspace->si; }
  std::uint64_t checks() const {
    return gog ? gog->checks->value() : cspace->space->checks().value();
  }
  // -1 when every state and motion of the path is valid (the re-check's own look-ups are not
  // part of any run's count: the rows read the counter before it).
  long first_invalid(const std::vector<std::vector<double>>& points) const {
    return gog ? first_invalid_step(*gog, points) : first_invalid_motion(*cspace->space, points);
  }
};

// OMPL's planners without Benchmark's progress properties (sampling/ompl_planners.hpp says
// why), for the c-space-only kinds below.
template <class P>
class WithoutProgress : public P {
 public:
  explicit WithoutProgress(const ob::SpaceInformationPtr& si) : P(si) {
    this->plannerProgressProperties_.clear();
  }
};

// User-facing name -> how to build it: the grid planner in two forms, every planner of
// sampling's one OMPL table, and the planners of OMPL's own chain and hypercube benchmarks that
// the table lacks (configuration spaces only: KPIECE1's default projection aborts on a 2D real
// vector space, sampling/ompl_planners.cpp). The OMPL names must be unique within one log.
struct PlannerKind {
  std::string ompl_name;
  std::function<ob::PlannerPtr(const BenchWorld&, const OmplBenchOptions&)> make;
  bool cspace_only = false;
};

ob::PlannerPtr grid(const BenchWorld& w, const OmplBenchOptions& o, bool smoothing) {
  if (w.cspace) {
    auto p = std::make_shared<CSpaceGridPlanner>(*w.cspace, w.cells);
    p->setSmoothing(smoothing);
    p->setWeight(o.grid_weight);
    p->setSmoothingBudget(o.smoothing_budget);
    p->setTimeLimit(o.time_s);
    return p;
  }
  auto p = std::make_shared<GridAStarPlanner>(*w.gog);
  p->setShortcut(smoothing);
  p->setWeight(o.grid_weight);
  p->setSmoothingBudget(o.smoothing_budget);
  p->setTimeLimit(o.time_s);
  return p;
}

// FMT* (either connection rule) gets seed 002 eq. 1's sample count; on GOG also the field's
// free volume. A configuration space keeps OMPL's default, the state space's measure: its free
// volume has no closed form, and an estimate by sampling would spend checks no other planner
// is charged for.
ob::PlannerPtr configure(ob::PlannerPtr p, const BenchWorld& w, const OmplBenchOptions& o) {
  if (auto* fmt = dynamic_cast<og::FMT*>(p.get())) {
    fmt->setNumSamples(fmt_samples(o.dims));
    if (w.gog) fmt->setFreeSpaceVolume(env::gog_free_volume(*w.gog->field));
  }
  if (w.range > 0 && p->params().hasParam("range"))
    p->params().setParam("range", std::to_string(w.range));
  return p;
}

template <class P>
PlannerKind cspace_kind(std::string ompl_name) {
  return {std::move(ompl_name),
          [](const BenchWorld& w, const OmplBenchOptions& o) {
            return configure(std::make_shared<WithoutProgress<P>>(w.si()), w, o);
          },
          true};
}

const std::map<std::string, PlannerKind>& planner_table() {
  static const std::map<std::string, PlannerKind> table = [] {
    std::map<std::string, PlannerKind> t = {
        {"gridastar",
         {"GridAStar",
          [](const BenchWorld& w, const OmplBenchOptions& o) { return grid(w, o, o.shortcut); }}},
        // The lattice path as found, for the time and quality of the search alone.
        {"gridastar_lattice",
         {"GridAStarLattice",
          [](const BenchWorld& w, const OmplBenchOptions& o) { return grid(w, o, false); }}},
        {"kpiece", cspace_kind<og::KPIECE1>("KPIECE1")},
        {"stride", cspace_kind<og::STRIDE>("STRIDE")},
        {"prm", cspace_kind<og::PRM>("PRM")},
        {"est", cspace_kind<og::EST>("EST")},
    };
    for (const OmplPlannerKind& k : ompl_planners())
      t[k.name] = {k.ompl_name, [&k](const BenchWorld& w, const OmplBenchOptions& o) {
                     return configure(k.make(w.si()), w, o);
                   }};
    return t;
  }();
  return table;
}

std::string experiment_name(const OmplBenchOptions& o) {
  if (!o.experiment.empty()) return o.experiment;
  if (o.world == "gog") return "gog-" + std::to_string(o.dims) + "d";
  return o.world + "-" + std::to_string(o.dims);
}

// The world and its query: GOG's start and goal are seed 002's (III-B) cell centres; a
// benchmark space's are the benchmark's own.
BenchWorld make_world(const OmplBenchOptions& o) {
  BenchWorld w;
  if (o.world == "gog") {
    GogParams gog = o.gog;
    gog.seed = o.seed;
    auto field = std::make_shared<const GogField>(o.dims, o.extent, gog);
    w.gog = make_gog_space(field, o.resolution_cells, parse_motion_check(o.motion));
    const auto start = adjust_to_free(*field, std::vector<int>(o.dims, 0), +1, "start");
    const auto goal = adjust_to_free(*field, std::vector<int>(o.dims, o.extent - 1), -1, "goal");
    for (int a = 0; a < o.dims; ++a) {
      w.start.push_back(start[a] + 0.5);
      w.goal.push_back(goal[a] + 0.5);
    }
    return w;
  }
  BenchmarkSpace b = make_benchmark_space(o.world, o.dims, o.resolution_fraction);
  w.cells = o.cells > 0 ? o.cells : b.cells;
  // The lattice's limits (cells per axis, key bits) as an InputError now, not as every run of
  // the grid planner failing.
  (void)CSpaceGraph(*b.space, w.cells, CSpaceMoves::seed_pairs);
  if (const auto* cube = dynamic_cast<const Hypercube*>(b.space.get()))
    w.range = 0.5 * cube->edge_width();
  // The benchmark's query as OMPL defines it can be in collision (the 2-link chain's start
  // crosses its horn): say so once, rather than every run of every planner failing at its
  // first check.
  for (const auto* end : {&b.start, &b.goal})
    if (!b.space->is_valid(end->data()))
      throw InputError(std::string("the ") + (end == &b.start ? "start" : "goal") + " of " +
                       o.world + "-" + std::to_string(o.dims) + " is in collision (" +
                       b.space->name() + ")");
  w.cspace = make_cspace_ompl(b.space);
  w.start = std::move(b.start);
  w.goal = std::move(b.goal);
  return w;
}

}  // namespace

std::vector<PlannerSpec> ompl_harness_specs() {
  std::vector<PlannerSpec> specs = {
      {"gridastar",
       "grid search",
       {"ompl"},
       {"grid_weight", "no_shortcut", "smoothing_budget"},
       "the grid planner inside OMPL: lattice A*, then shortened within a budget of the "
       "search's own time (GOG: simplified and tightened; chain/hypercube: the c-space "
       "lattice, then OMPL's PathSimplifier)"},
      {"gridastar_lattice",
       "grid search",
       {"ompl"},
       {"grid_weight"},
       "the grid planner inside OMPL, its lattice path as found"},
  };
  for (const OmplPlannerKind& k : ompl_planners())
    specs.push_back({k.name, "ompl", {"ompl"}, {}, k.help});
  return specs;
}

const std::vector<std::string>& cspace_only_planners() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, kind] : planner_table())
      if (kind.cspace_only) n.push_back(name);
    return n;
  }();
  return names;
}

bool is_cspace_world(const std::string& world) {
  return is_benchmark_space(world);
}

const std::vector<std::string>& known_planners() {
  static const std::vector<std::string> names = PlannerRegistry::get().names("ompl");
  return names;
}

unsigned fmt_samples(int dims) {
  const unsigned k = static_cast<unsigned>(dims - 2);
  return 2000u + 1500u * k * k;
}

void validate(const OmplBenchOptions& o) {
  const bool cspace = is_cspace_world(o.world);
  if (!cspace && o.world != "gog")
    throw InputError("--world must be gog, chain or hypercube, got '" + o.world + "'");
  const int max_dims = cspace ? kBenchmarkMaxDims : 10;
  if (o.dims < 2 || o.dims > max_dims)
    throw InputError("--dims must be in 2.." + std::to_string(max_dims) + " for --world " +
                     o.world + ", got " + std::to_string(o.dims));
  if (o.extent < 2 || o.extent > 1000)
    throw InputError("--extent must be in 2..1000, got " + std::to_string(o.extent));
  if (!cspace && (o.cells != 0 || o.resolution_fraction != 0.0))
    throw InputError("--cells and --resolution-fraction are for --world chain|hypercube");
  if (o.cells < 0 || o.cells == 1 || o.cells > 65535)
    throw InputError("--cells must be in 2..65535 (0: the benchmark's default), got " +
                     std::to_string(o.cells));
  if (!(o.resolution_fraction >= 0.0 && o.resolution_fraction < 1.0))
    throw InputError("--resolution-fraction must be in (0, 1) (0: the benchmark's default)");
  if (!(o.time_s > 0.0) || o.time_s > 3600.0)
    throw InputError("--time must be in (0, 3600] seconds");
  if (o.runs < 1 || o.runs > 10000) throw InputError("--runs must be in 1..10000");
  if (o.warmup < 0 || o.warmup > 100) throw InputError("--warmup must be in 0..100");
  if (o.planners.empty()) throw InputError("--planners: name at least one planner");
  for (std::size_t i = 0; i < o.planners.size(); ++i) {
    // The c-space-only planners are not in the registry's "ompl" setting, whose every planner
    // runs on every world of the harness.
    const auto kind = planner_table().find(o.planners[i]);
    const bool cspace_only = kind != planner_table().end() && kind->second.cspace_only;
    if (cspace_only && !cspace)
      throw InputError("planner '" + o.planners[i] + "' runs on --world chain|hypercube only");
    if (!cspace_only) PlannerRegistry::get().require("ompl", o.planners[i]);
    for (std::size_t j = 0; j < i; ++j)
      if (o.planners[j] == o.planners[i])
        throw InputError("planner '" + o.planners[i] + "' is listed twice");
  }
  if (!(o.resolution_cells > 0.0 && o.resolution_cells <= 1.0))
    throw InputError("--resolution must be in (0, 1] cell widths");
  (void)parse_motion_check(o.motion);
  if (!(o.grid_weight >= 1.0)) throw InputError("--grid-weight must be >= 1");
  if (!(o.smoothing_budget >= 0.0 && o.smoothing_budget <= 1e6))
    throw InputError("--smoothing-budget must be in [0, 1e6]");
  if (!(o.gog.density > 0.0 && o.gog.density < 1.0))
    throw InputError("--density must be in (0, 1)");
}

OmplBenchResult run_ompl_benchmark(const OmplBenchOptions& o) {
  validate(o);
  // OMPL draws every planner's generator from one seeded sequence, so an invocation is
  // reproducible run by run; the seed must be set before any generator exists.
  ompl::RNG::setSeed(o.seed);
  const BenchWorld world = make_world(o);
  const ob::SpaceInformationPtr& si = world.si();
  OmplBenchResult result;
  result.start = world.start;
  result.goal = world.goal;
  result.cells = world.cells;
  ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
  for (int a = 0; a < o.dims; ++a) {
    start[a] = world.start[a];
    goal[a] = world.goal[a];
  }
  result.straight_line = si->distance(start.get(), goal.get());

  og::SimpleSetup setup(si);
  setup.setStartAndGoalStates(start, goal, 1e-6);
  setup.setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));

  std::vector<ob::PlannerPtr> planners;
  std::map<std::string, std::string> user_name;  // OMPL name -> user name
  for (const auto& name : o.planners) {
    const auto& kind = planner_table().at(name);
    ob::PlannerPtr p = kind.make(world, o);
    p->setName(kind.ompl_name);  // BIT* may amend it (k-nearest BIT* is "kBITstar")
    user_name[p->getName()] = name;
    planners.push_back(p);
  }
  // Without a warm-up the first planner's first runs also pay for the process's first searches
  // (pools created, pages faulted in): at 4D the smoothed grid planner, listed first, took
  // 10.8, 6.4 and then 1.75 ms. Each warm-up is a plain solve through the same setup, as the
  // benchmark's own runs are, and is cleared afterwards; it records nothing.
  for (int w = 0; w < o.warmup; ++w)
    for (const auto& p : planners) {
      setup.setPlanner(p);
      setup.solve(std::min(o.time_s, 1.0));
      setup.clear();
    }

  ompl::tools::Benchmark bench(setup, experiment_name(o));
  // OMPL's benchmarks of these spaces record their size as an experiment parameter.
  if (o.world == "chain")
    bench.addExperimentParameter("num_links", "INTEGER", std::to_string(o.dims));
  if (o.world == "hypercube")
    bench.addExperimentParameter("num_dims", "INTEGER", std::to_string(o.dims));
  for (const auto& p : planners) bench.addPlanner(p);

  // Per-run bookkeeping shared by the events (Benchmark runs one planner at a time; the
  // planner may call back from its own thread, hence the plain data behind one run).
  Stopwatch clock;
  std::vector<std::pair<double, double>> improvements;
  std::uint64_t checks_before = 0;
  std::map<std::string, int> run_index;
  Progress progress("hpcplan ompl", o.planners.size() * static_cast<std::size_t>(o.runs));
  bench.setPreRunEvent([&](const ob::PlannerPtr& planner) {
    checks_before = world.checks();
    improvements.clear();
    planner->getProblemDefinition()->setIntermediateSolutionCallback(
        [&](const ob::Planner*, const std::vector<const ob::State*>&, const ob::Cost cost) {
          improvements.emplace_back(clock.seconds(), cost.value());
        });
    clock = Stopwatch();
  });
  bench.setPostRunEvent(
      [&](const ob::PlannerPtr& planner, ompl::tools::Benchmark::RunProperties& run) {
        OmplRunRow row;
        row.planner = user_name.at(planner->getName());
        row.dims = o.dims;
        row.run = run_index[row.planner]++;
        row.seed = o.seed;
        row.collision_checks = world.checks() - checks_before;  // before re-validation
        if (const auto* grid = dynamic_cast<const GridAStarPlanner*>(planner.get()))
          row.smoothing_s = grid->lastSmoothingSeconds();
        if (const auto* grid = dynamic_cast<const CSpaceGridPlanner*>(planner.get()))
          row.smoothing_s = grid->lastSmoothingSeconds();
        const auto t = run.find("time REAL");
        row.time_s = t != run.end() ? std::stod(t->second) : clock.seconds();
        const auto pdef = planner->getProblemDefinition();
        row.solved = pdef->hasExactSolution();
        row.improvements = improvements;
        row.anytime = planner->getSpecs().optimizingPaths && !improvements.empty();
        if (row.solved) {
          const auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
          row.length_final = path->length();
          std::vector<std::vector<double>> points;
          const std::size_t n = path->getStateCount();
          for (std::size_t i = 0; i < n; ++i) {
            const double* x = path->getState(i)->as<ob::RealVectorStateSpace::StateType>()->values;
            points.emplace_back(x, x + o.dims);
          }
          const bool ends_ok = n > 0 && si->distance(path->getState(0), start.get()) < 1e-9 &&
                               si->distance(path->getState(n - 1), goal.get()) < 1e-6;
          row.path_valid = ends_ok && world.first_invalid(points) < 0;
          if (row.improvements.empty()) row.improvements.emplace_back(row.time_s, row.length_final);
          row.time_first_s = row.improvements.front().first;
          row.length_first = row.improvements.front().second;
          row.quality_first = row.length_first / result.straight_line;
          row.quality_final = row.length_final / result.straight_line;
        }
        run["collision checks INTEGER"] = std::to_string(row.collision_checks);
        run["path valid BOOLEAN"] = row.path_valid ? "1" : "0";
        if (row.solved) {
          run["time first REAL"] = std::to_string(row.time_first_s);
          run["quality first REAL"] = std::to_string(row.quality_first);
          run["quality final REAL"] = std::to_string(row.quality_final);
        }
        progress.step(row.planner + " run " + std::to_string(row.run));
        result.rows.push_back(std::move(row));
        planner->getProblemDefinition()->setIntermediateSolutionCallback(nullptr);
      });

  ompl::tools::Benchmark::Request request(o.time_s, o.memory_mb, static_cast<unsigned>(o.runs),
                                          0.05, false, false, false);
  bench.benchmark(request);

  // The "best" solution needs the reference quality, known only once every run is done.
  for (const auto& r : result.rows)
    if (r.solved && (result.reference_quality < 0 || r.quality_final < result.reference_quality))
      result.reference_quality = r.quality_final;
  for (auto& r : result.rows) {
    if (!r.solved || !r.anytime) continue;
    const double target = 0.5 * (r.quality_first + result.reference_quality);
    for (const auto& [time, length] : r.improvements)
      if (length / result.straight_line <= target + 1e-12) {
        r.time_best_s = time;
        r.quality_best = length / result.straight_line;
        break;
      }
  }

  std::ostringstream log;
  if (!bench.saveResultsToStream(log)) throw RunError("could not format the OMPL log");
  result.ompl_log = log.str();
  return result;
}

}  // namespace hpcplan::plan
