#include "hpcplan/plan/grid_planner.hpp"

#include <algorithm>
#include <cmath>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/format.hpp"
#include "hpcplan/core/memory.hpp"
#include "hpcplan/plan/grid_planner_impl.hpp"

namespace hpcplan {

bool dense_visited_fits(int dims, int extent) {
  // Out-of-range problems are refused by validate(); they must not reach a key layout here.
  if (dims < 1 || dims > kMaxDims || extent < 2 || extent > kMaxExtent) return false;
  const KeyLayout layout(dims, extent);
  return layout.words() == 1 && layout.bits() * dims <= kDenseVisitedBits;
}

GridReport solve_grid(const GridProblem& problem, const GridSearchOptions& options) {
  if (dense_visited_fits(problem.dims, problem.extent))
    return solve_grid_with<search::StampedDensePolicy>(problem, options);
  return solve_grid_with<search::DefaultVisitedMap>(problem, options);
}

GridReport solve_grid(const GogField& field, const GridProblem& problem,
                      const GridSearchOptions& options) {
  if (dense_visited_fits(problem.dims, problem.extent))
    return solve_grid_with<search::StampedDensePolicy>(field, problem, options);
  return solve_grid_with<search::DefaultVisitedMap>(field, problem, options);
}

GridReport prepare_grid_report(const GridProblem& problem, const GridSearchOptions& options,
                               const GogField& field, int ranks_sharing_memory) {
  GridReport report;
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
    report.max_states =
        avail ? avail / 2 / std::max(1, ranks_sharing_memory) / bytes_per_state(report.key_words)
              : 100'000'000;
  }
  return report;
}

void finish_grid_report(GridReport& report) {
  if (report.status == search::Status::solved)
    report.quality = report.straight_line > 0 ? report.cost / report.straight_line : 1.0;
}

double workload_deviation_percent(const std::vector<search::RankCounters>& per_rank) {
  std::uint64_t total = 0;
  for (const auto& r : per_rank) total += r.expanded;
  if (per_rank.size() < 2 || total == 0) return 0.0;
  double lo = 100.0, hi = 0.0;
  for (const auto& r : per_rank) {
    const double share = 100.0 * static_cast<double>(r.expanded) / static_cast<double>(total);
    lo = std::min(lo, share);
    hi = std::max(hi, share);
  }
  return hi - lo;
}

}  // namespace hpcplan
