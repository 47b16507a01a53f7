#pragma once
// The grid planner's implementation, as templates over the visited-map policy so benchmarks
// can run the identical planner with another hash map. Users call solve_grid().
#include <cmath>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/format.hpp"
#include "hpcplan/core/memory.hpp"
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
  GridReport report;
  const GogField field(problem.dims, problem.extent, problem.gog);
  report.dims = problem.dims;
  report.extent = problem.extent;
  report.seed = problem.gog.seed;
  report.threshold = field.threshold();
  report.blocked_fraction = field.blocked_fraction();
  report.shift_p = problem.gog.shift_p;
  report.shift_v = problem.gog.shift_v;
  report.connectivity = std::string(to_string(problem.connectivity));
  report.algorithm = std::string(to_string(options.algorithm));
  report.heuristic =
      options.algorithm == GridAlgorithm::dijkstra || options.algorithm == GridAlgorithm::bfs
          ? "none"
          : std::string(to_string(options.heuristic));
  report.weight = options.algorithm == GridAlgorithm::wastar ? options.weight.value_or(2.0) : 1.0;

  auto endpoint = [&](const std::optional<std::vector<int>>& given, int corner, int direction,
                      const char* what, bool& adjusted) {
    if (given) {
      if (!field.is_free(*given)) {
        throw InputError(std::string("--") + what + " (" + join_coordinates(*given) +
                         ") is inside an obstacle");
      }
      return *given;
    }
    std::vector<int> nominal(problem.dims, corner);
    auto free = adjust_to_free(field, nominal, direction, what);
    adjusted = free != nominal;
    return free;
  };
  report.start = endpoint(problem.start, 0, +1, "start", report.start_adjusted);
  report.goal = endpoint(problem.goal, problem.extent - 1, -1, "goal", report.goal_adjusted);

  double sq = 0.0;
  for (int i = 0; i < problem.dims; ++i) {
    const double d = report.goal[i] - report.start[i];
    sq += d * d;
  }
  report.straight_line = std::sqrt(sq);

  const KeyLayout layout(problem.dims, problem.extent);
  report.key_words = layout.words() <= 1 ? 1 : layout.words() <= 2 ? 2 : 4;
  report.max_states = options.max_states;
  if (report.max_states == 0) {
    // Stop with budget_exceeded well before the kernel's OOM killer would.
    const std::uint64_t avail = available_memory_bytes();
    report.max_states = avail ? avail / 2 / bytes_per_state(report.key_words) : 100'000'000;
  }
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
  if (report.status == search::Status::solved)
    report.quality = report.straight_line > 0 ? report.cost / report.straight_line : 1.0;
  return report;
}

}  // namespace hpcplan
