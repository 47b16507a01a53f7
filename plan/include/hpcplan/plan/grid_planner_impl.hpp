#pragma once
// The grid planner's implementation, as templates over the visited-map policy so benchmarks
// can run the identical planner with another hash map. Users call solve_grid().
#include <type_traits>

#include "hpcplan/core/progress.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/graph/jump_point_graph.hpp"
#include "hpcplan/graph/lattice_graph.hpp"
#include "hpcplan/graph/lattice_heuristic.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/stamped_dense_map.hpp"

namespace hpcplan {
namespace detail {

inline search::Options engine_options(const GridSearchOptions& o, double weight,
                                      std::uint64_t budget) {
  search::Options e;
  e.max_states = budget;
  e.stop = Stop::after(o.time_limit_s, o.cancel);
  if (o.stop_when) e.stop.also_when(o.stop_when);
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

// Calls search(h) with the heuristic the options ask for (none for Dijkstra and BFS), so
// every caller that searches a lattice picks heuristics the same way.
template <int W, class Search>
auto with_heuristic(const GridSearchOptions& o, const GridProblem& problem, const KeyLayout& layout,
                    const std::vector<int>& goal, Search&& search) {
  if (o.algorithm == GridAlgorithm::dijkstra || o.algorithm == GridAlgorithm::bfs)
    return search(search::ZeroHeuristic{});
  if (o.heuristic == HeuristicKind::euclidean) return search(EuclideanHeuristic<W>(layout, goal));
  if (problem.connectivity == Connectivity::full)
    return search(FullConnectivityHeuristic<W>(layout, goal));
  return search(SeedRuleHeuristic<W>(layout, goal));
}

// Whether the run searches the lattice's jump points instead of its every state: plain A* on a
// 2D lattice (both connectivities are the same 8 moves there) that the jump graph can span.
inline bool uses_jump_points(const GridProblem& problem, const GridSearchOptions& o) {
  return o.jump_points && o.algorithm == GridAlgorithm::astar && problem.dims == 2 &&
         problem.extent <= JumpPointGraph<GogCells2D>::kMaxExtent;
}

// Searches one of the lattice's graphs (states packed in the lattice's key layout) and fills
// the report. A graph whose moves are runs (the jump points) hands back its path as unit moves,
// so hops and the path count lattice moves either way.
template <class MapPolicy, int W, class Graph>
void search_into_report(const Graph& graph, const GridProblem& problem, const GridSearchOptions& o,
                        GridReport& report) {
  const auto start = graph.pack(report.problem.start);
  const auto goal = graph.pack(report.problem.goal);
  auto eo = engine_options(o, report.options.weight, report.options.max_states);
  if constexpr (std::is_same_v<MapPolicy, search::StampedDensePolicy>)
    eo.dense_keys = graph.layout().dense_index_bound();
  RunProgress progress("hpcplan grid " + report.options.algorithm, report.options.max_states);
  eo.progress = [&progress](std::uint64_t expanded, std::uint64_t stored) {
    progress.update(expanded, stored);
  };

  auto search = [&](const auto& h) {
    return search::best_first_search<MapPolicy>(graph, start, goal, h, eo);
  };
  // The jump points serve plain A* in 2D only, where both connectivities are the same 8 moves:
  // two heuristics, not four (each one a whole instantiation of the search to compile).
  const auto r = [&] {
    if constexpr (requires { graph.unit_steps(std::vector<typename Graph::State>{}); }) {
      if (o.heuristic == HeuristicKind::euclidean)
        return search(EuclideanHeuristic<W>(graph.layout(), report.problem.goal));
      return search(SeedRuleHeuristic<W>(graph.layout(), report.problem.goal));
    } else {
      return with_heuristic<W>(o, problem, graph.layout(), report.problem.goal, search);
    }
  }();
  GridResult& out = report.result;
  out.status = r.status;
  out.cost = r.cost;
  out.counters = r.counters;
  report.options.visited_map = MapPolicy::name;
  auto take_path = [&](const auto& moves) {
    out.hops = moves.empty() ? 0 : moves.size() - 1;
    if (o.keep_path)
      for (const auto& s : moves) {
        const auto c = graph.unpack(s);
        out.path.emplace_back(c.begin(), c.end());
      }
  };
  if constexpr (requires { graph.unit_steps(r.path); })
    take_path(graph.unit_steps(r.path));
  else
    take_path(r.path);
}

template <class MapPolicy, int W>
void run_search(const ObstacleSource& field, const GridProblem& problem, const GridSearchOptions& o,
                GridReport& report) {
  if constexpr (W == 1) {
    if (uses_jump_points(problem, o)) {
      report.options.pruning = "jump_points";
      const std::array<int, 2> goal = {report.problem.goal[0], report.problem.goal[1]};
      if (field.is_occupancy()) {
        const OccupancyCells2D cells(field.occupancy());
        const JumpPointGraph<OccupancyCells2D> graph(cells, goal);
        return search_into_report<MapPolicy, 1>(graph, problem, o, report);
      }
      const GogCells2D cells(field.gog());
      const JumpPointGraph<GogCells2D> graph(cells, goal);
      return search_into_report<MapPolicy, 1>(graph, problem, o, report);
    }
  }
  const LatticeGraph<W> graph(field, problem.connectivity);
  search_into_report<MapPolicy, W>(graph, problem, o, report);
}

}  // namespace detail

// The planner with a chosen visited map on a field already built (problem.gog must be the
// field's parameters, or problem.occupancy the grid). The dense policy serves one-word keys only;
// wider ones fall back to the default hash map.
template <class MapPolicy>
GridReport solve_grid_with(const ObstacleSource& field, const GridProblem& problem,
                           const GridSearchOptions& options, double setup_ms = 0.0) {
  validate(problem, options);
  Stopwatch setup;
  GridReport report = prepare_grid_report(problem, options, field, 1);
  report.result.setup_ms = setup_ms + setup.milliseconds();
  using Wide = std::conditional_t<std::is_same_v<MapPolicy, search::StampedDensePolicy>,
                                  search::DefaultVisitedMap, MapPolicy>;
  switch (report.options.key_words) {
    case 1:
      detail::run_search<MapPolicy, 1>(field, problem, options, report);
      break;
    case 2:
      detail::run_search<Wide, 2>(field, problem, options, report);
      break;
    default:
      detail::run_search<Wide, 4>(field, problem, options, report);
      break;
  }
  finish_grid_report(report);
  return report;
}

// The two visited maps solve_grid() itself runs are instantiated once, in grid_planner.cpp:
// every other file that includes this header (the tests, the benchmarks, the rank simulation)
// links those instead of compiling the whole search again (25 s of one core for the unit test
// that compares the two maps, more under the sanitizers). A policy not listed here is still
// instantiated where it is used.
extern template GridReport solve_grid_with<search::DefaultVisitedMap>(const ObstacleSource&,
                                                                      const GridProblem&,
                                                                      const GridSearchOptions&,
                                                                      double);
extern template GridReport solve_grid_with<search::StampedDensePolicy>(const ObstacleSource&,
                                                                       const GridProblem&,
                                                                       const GridSearchOptions&,
                                                                       double);

// The planner with a chosen visited map, building the problem's field.
template <class MapPolicy>
GridReport solve_grid_with(const GridProblem& problem, const GridSearchOptions& options) {
  validate(problem, options);
  if (problem.occupancy) return solve_grid_with<MapPolicy>(*problem.occupancy, problem, options);
  Stopwatch setup;
  const GogField field(problem.dims, problem.extent, problem.gog);
  return solve_grid_with<MapPolicy>(field, problem, options, setup.milliseconds());
}

}  // namespace hpcplan
