#include "hpcplan/plan/grid_planner.hpp"

#include "hpcplan/plan/grid_planner_impl.hpp"

namespace hpcplan {

GridReport solve_grid(const GridProblem& problem, const GridSearchOptions& options) {
  return solve_grid_with<search::DefaultVisitedMap>(problem, options);
}

}  // namespace hpcplan
