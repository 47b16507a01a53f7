// Google Benchmark suite for the serial grid engine. Throughput is measured on sustained
// searches (Dijkstra from the default start until a fixed number of states is stored), so the
// visited map is large and the figure is not an in-cache best case.
#include <benchmark/benchmark.h>

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>

#include "hpcplan/plan/grid_astar_planner.hpp"
#include "hpcplan/plan/grid_planner_impl.hpp"
#include "hpcplan/plan/grid_problem.hpp"
#include "hpcplan/sampling/gog_space.hpp"
#include "visited_maps.hpp"

namespace {

using namespace hpcplan;

constexpr std::uint64_t kThroughputStates = 1'000'000;

template <class MapPolicy>
void run_and_count(benchmark::State& state, const GridProblem& p, const GridSearchOptions& o) {
  std::uint64_t expanded = 0, generated = 0, checks = 0;
  double search_s = 0;
  for (auto _ : state) {
    const GridReport r = solve_grid_with<MapPolicy>(p, o);
    benchmark::DoNotOptimize(r.result.cost);
    expanded += r.result.counters.expanded;
    generated += r.result.counters.generated;
    checks += r.result.counters.collision_checks;
    search_s += r.result.counters.time_ms / 1e3;
  }
  // Rates over search time only (field set-up excluded, as the JSON's time_ms).
  state.counters["generated_per_s"] = benchmark::Counter(generated / search_s);
  state.counters["expanded_per_s"] = benchmark::Counter(expanded / search_s);
  state.counters["checks_per_s"] = benchmark::Counter(checks / search_s);
  state.counters["expanded"] =
      benchmark::Counter(static_cast<double>(expanded) / state.iterations());
}

GridProblem default_problem(int d) {
  GridProblem p;
  p.dims = d;
  return p;
}

template <class MapPolicy>
void BM_Throughput(benchmark::State& state) {
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::dijkstra;
  o.max_states = kThroughputStates;
  run_and_count<MapPolicy>(state, default_problem(static_cast<int>(state.range(0))), o);
}
BENCHMARK(BM_Throughput<search::AbslFlatMap>)
    ->Name("Throughput/absl")
    ->DenseRange(2, 10, 1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Throughput<search::StdUnorderedMap>)
    ->Name("Throughput/std_unordered")
    ->Arg(6)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Throughput<bench::TslRobinMap>)
    ->Name("Throughput/tsl_robin")
    ->Arg(6)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_DefaultProblem(benchmark::State& state) {
  run_and_count<search::DefaultVisitedMap>(state, default_problem(static_cast<int>(state.range(0))),
                                           GridSearchOptions{});
}
BENCHMARK(BM_DefaultProblem)->DenseRange(2, 10, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

// One query of the default problem on a field built once (as the OMPL adapter runs it), with
// the hash map and with the dense store the planner picks for small lattices: the whole
// solve_grid call per iteration (report included), so the figure is what a caller waits for.
// Query/dense_every_state: the same with 2D A*'s jump points off, the figure to compare them
// against in one run.
template <class MapPolicy, bool JumpPoints = true>
void BM_Query(benchmark::State& state) {
  const GridProblem p = default_problem(static_cast<int>(state.range(0)));
  const GogField field(p.dims, p.extent, p.gog);
  GridSearchOptions o;
  o.max_states = 100'000'000;  // as the adapter sets it once (no /proc read per query)
  o.jump_points = JumpPoints;
  std::uint64_t expanded = 0;
  for (auto _ : state) {
    const GridReport r = solve_grid_with<MapPolicy>(field, p, o);
    benchmark::DoNotOptimize(r.result.cost);
    expanded += r.result.counters.expanded;
  }
  state.counters["expanded"] =
      benchmark::Counter(static_cast<double>(expanded) / state.iterations());
}
BENCHMARK(BM_Query<search::AbslFlatMap>)
    ->Name("Query/absl")
    ->DenseRange(2, 3, 1)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_Query<search::StampedDensePolicy>)
    ->Name("Query/dense")
    ->DenseRange(2, 3, 1)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_Query<search::StampedDensePolicy, false>)
    ->Name("Query/dense_every_state")
    ->Arg(2)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

// The same 2D query as an OMPL planner (`hpcplan ompl`'s gridastar_lattice: no smoothing), to
// split its time into the search and what is around it. range(1) = 0: Planner::solve with a
// plain termination condition (the adapter's own cost: problem set-up, the path as OMPL
// states); 1: Planner::solve(fn, 0.1), the call ompl::tools::Benchmark makes, which starts and
// joins a thread that polls the condition, in every run and for every planner; 2: as 0 with the
// default smoothing (`hpcplan ompl`'s gridastar), its quality (length over the straight line)
// as a counter.
void BM_OmplQuery(benchmark::State& state) {
  namespace ob = ompl::base;
  namespace og = ompl::geometric;
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const GridProblem p = default_problem(static_cast<int>(state.range(0)));
  auto field = std::make_shared<const GogField>(p.dims, p.extent, p.gog);
  const sampling::GogSpace space = sampling::make_gog_space(field, 1.0);
  ob::ScopedState<> start(space.space), goal(space.space);
  sampling::cell_centre(adjust_to_free(*field, std::vector<int>(p.dims, 0), +1, "start"),
                        start.get());
  sampling::cell_centre(adjust_to_free(*field, std::vector<int>(p.dims, p.extent - 1), -1, "goal"),
                        goal.get());
  og::SimpleSetup setup(space.si);
  setup.setStartAndGoalStates(start, goal, 1e-6);
  setup.setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(space.si));
  auto planner = std::make_shared<plan::GridAStarPlanner>(space);
  const int mode = static_cast<int>(state.range(1));
  planner->setShortcut(mode == 2);
  setup.setPlanner(planner);
  setup.setup();
  const bool harness_call = mode == 1;
  ob::Planner& base = *planner;  // the overload with a check interval lives on the base
  for (auto _ : state) {
    planner->clear();
    setup.getProblemDefinition()->clearSolutionPaths();
    const ob::PlannerStatus status = harness_call
                                         ? base.solve([] { return false; }, 0.1)
                                         : planner->solve(ob::plannerNonTerminatingCondition());
    if (status != ob::PlannerStatus::EXACT_SOLUTION) state.SkipWithError("not solved");
  }
  state.SetLabel(harness_call ? "solve(fn, 0.1) as ompl::tools::Benchmark"
                 : mode == 2  ? "solve(ptc), smoothed"
                              : "solve(ptc)");
  if (mode == 2)
    state.counters["quality"] = setup.getProblemDefinition()->getSolutionPath()->length() /
                                space.si->distance(start.get(), goal.get());
}
BENCHMARK(BM_OmplQuery)
    ->Name("OmplQuery")
    ->ArgsProduct({{2}, {0, 1, 2}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

// Expansions of A* with each heuristic on a denser field where the search must work.
void BM_Heuristic(benchmark::State& state) {
  GridProblem p = default_problem(static_cast<int>(state.range(0)));
  p.gog.density = 0.7;
  GridSearchOptions o;
  o.heuristic = state.range(1) ? HeuristicKind::euclidean : HeuristicKind::lattice;
  o.max_states = 4'000'000;
  state.SetLabel(o.heuristic == HeuristicKind::lattice ? "lattice" : "euclidean");
  run_and_count<search::DefaultVisitedMap>(state, p, o);
}
BENCHMARK(BM_Heuristic)
    ->ArgsProduct({{2, 3, 4, 6}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
