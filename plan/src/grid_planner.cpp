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
  GridProblemReport& pr = report.problem;
  pr.dims = problem.dims;
  pr.extent = problem.extent;
  pr.seed = problem.gog.seed;
  pr.threshold = field.threshold();
  pr.blocked_fraction = field.blocked_fraction();
  pr.shift_p = problem.gog.shift_p;
  pr.shift_v = problem.gog.shift_v;
  pr.connectivity = std::string(to_string(problem.connectivity));
  GridOptionsReport& op = report.options;
  op.algorithm = std::string(to_string(options.algorithm));
  op.heuristic =
      options.algorithm == GridAlgorithm::dijkstra || options.algorithm == GridAlgorithm::bfs
          ? "none"
          : std::string(to_string(options.heuristic));
  op.weight = options.algorithm == GridAlgorithm::wastar ? options.weight.value_or(2.0) : 1.0;

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
  pr.start = endpoint(problem.start, 0, +1, "start", pr.start_adjusted);
  pr.goal = endpoint(problem.goal, problem.extent - 1, -1, "goal", pr.goal_adjusted);

  double sq = 0.0;
  for (int i = 0; i < problem.dims; ++i) {
    const double d = pr.goal[i] - pr.start[i];
    sq += d * d;
  }
  pr.straight_line = std::sqrt(sq);

  const KeyLayout layout(problem.dims, problem.extent);
  op.key_words = layout.words() <= 1 ? 1 : layout.words() <= 2 ? 2 : 4;
  op.max_states = options.max_states;
  if (op.max_states == 0) {
    // Stop with budget_exceeded well before the kernel's OOM killer would.
    const std::uint64_t avail = available_memory_bytes();
    op.max_states =
        avail ? avail / 2 / std::max(1, ranks_sharing_memory) / bytes_per_state(op.key_words)
              : 100'000'000;
  }
  return report;
}

void finish_grid_report(GridReport& report) {
  GridResult& r = report.result;
  if (r.status == search::Status::solved)
    r.quality = report.problem.straight_line > 0 ? r.cost / report.problem.straight_line : 1.0;
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
