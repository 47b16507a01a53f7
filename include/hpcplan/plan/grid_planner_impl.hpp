#pragma once
// The grid planner's implementation, as templates over the visited-map policy so benchmarks
// can run the identical planner with another hash map. Users call solve_grid().

#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/graph/lattice_graph.hpp"
#include "hpcplan/graph/lattice_heuristic.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/search/best_first.hpp"

namespace hpcplan {
namespace detail {

inline search::Options engine_options(const GridSearchOptions& o, double weight,
                                      std::uint64_t budget) {
  search::Options e;
  e.max_states = budget;
  e.time_limit_s = o.time_limit_s;
  e.weight = weight;
  switch (o.algorithm) {
    case GridAlgorithm::astar:
    case GridAlgorithm::dijkstra:
      break;
    case GridAlgorithm::wastar:
      e.reopen_closed = false;
      break;
    case GridAlgorithm::bfs:
      e.frontier = search::Frontier::fifo;
      break;
  }
  return e;
}

template <class MapPolicy, int W>
void run_search(const GogField& field, const GridProblem& problem, const GridSearchOptions& o,
                GridReport& report) {
  LatticeGraph<W> graph(field, problem.connectivity);
  const auto start = graph.pack(report.start);
  const auto goal = graph.pack(report.goal);
  const auto eo = engine_options(o, report.weight, report.max_states);

  search::Result<PackedKey<W>> r;
  if (o.algorithm == GridAlgorithm::dijkstra || o.algorithm == GridAlgorithm::bfs) {
    r = search::best_first_search<MapPolicy>(graph, start, goal, search::ZeroHeuristic{}, eo);
  } else if (o.heuristic == HeuristicKind::euclidean) {
    r = search::best_first_search<MapPolicy>(
        graph, start, goal, EuclideanHeuristic<W>(graph.layout(), report.goal), eo);
  } else if (problem.connectivity == Connectivity::full) {
    r = search::best_first_search<MapPolicy>(
        graph, start, goal, FullConnectivityHeuristic<W>(graph.layout(), report.goal), eo);
  } else {
    r = search::best_first_search<MapPolicy>(graph, start, goal,
                                             SeedRuleHeuristic<W>(graph.layout(), report.goal), eo);
  }
  report.status = r.status;
  report.cost = r.cost;
  report.hops = r.hops;
  report.counters = r.counters;
  report.visited_map = MapPolicy::name;
  if (o.keep_path)
    for (const auto& s : r.path) report.path.push_back(graph.unpack(s));
}

}  // namespace detail

// The planner with a chosen visited map; solve_grid() is this with the default map.
template <class MapPolicy>
GridReport solve_grid_with(const GridProblem& problem, const GridSearchOptions& options) {
  validate(problem, options);
  Stopwatch setup;
  const GogField field(problem.dims, problem.extent, problem.gog);
  GridReport report = prepare_grid_report(problem, options, field, 1);
  report.setup_ms = setup.milliseconds();
  switch (report.key_words) {
    case 1:
      detail::run_search<MapPolicy, 1>(field, problem, options, report);
      break;
    case 2:
      detail::run_search<MapPolicy, 2>(field, problem, options, report);
      break;
    default:
      detail::run_search<MapPolicy, 4>(field, problem, options, report);
      break;
  }
  finish_grid_report(report);
  return report;
}

}  // namespace hpcplan
