#pragma once
// The grid planner on a configuration space (plan/cspace_planner.hpp) as an OMPL planner, so
// it runs inside ompl::tools::Benchmark beside OMPL's planners on the same ProblemDefinition
// and the same space information (sampling/cspace_ompl.hpp):
//  - the start and goal states are the query of a GridProblem whose `cspace` is set;
//    solve_grid() searches the space's lattice (`cells` per axis), joining both ends to it by
//    checked motions, and the report's path in the space's coordinates (start, vertices,
//    goal) becomes the solution, an exact one: its ends are the problem's own states;
//  - the lattice's checks go through the space's own CheckCounter (the graph tests through
//    ConfigSpace::are_valid), the counter OMPL's planners bump through the adapter;
//  - with `smoothing` on, the lattice path is then shortened by OMPL's PathSimplifier through
//    the space information's motion validator, within a budget of `smoothing_budget` times the
//    search's own time (0: until it converges); a smoothed path any of whose motions fails the
//    motion validator afterwards (or that is no shorter) gives way to the lattice path.
// Parameters (declared, so Benchmark logs them): cells (per axis), moves (axes | seed_pairs),
// weight (1 = A*), smoothing (0/1), smoothing_budget, time_limit (s, 0 = none). OMPL's
// termination condition ends the search (stop_when) and the smoothing.
#include <cstdint>
#include <string>

#include <ompl/base/Planner.h>

#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/sampling/cspace_ompl.hpp"

namespace hpcplan::plan {

class CSpaceGridPlanner : public ompl::base::Planner {
 public:
  CSpaceGridPlanner(const sampling::CSpaceOmpl& space, int cells,
                    CSpaceMoves moves = CSpaceMoves::seed_pairs);

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  void setCells(int cells) { cells_ = cells; }
  int getCells() const { return cells_; }
  void setMoves(const std::string& moves) { moves_ = parse_cspace_moves(moves); }
  std::string getMoves() const { return std::string(to_string(moves_)); }
  void setWeight(double w) { weight_ = w; }
  double getWeight() const { return weight_; }
  void setSmoothing(bool s) { smoothing_ = s; }
  bool getSmoothing() const { return smoothing_; }
  void setSmoothingBudget(double factor) { smoothing_budget_ = factor; }
  double getSmoothingBudget() const { return smoothing_budget_; }
  void setTimeLimit(double s) { time_limit_s_ = s; }
  double getTimeLimit() const { return time_limit_s_; }

  // The last search's report (lattice cost, expansions, the lattice path), for callers that
  // want more than the path.
  const GridReport& lastReport() const { return last_; }
  // Seconds the last solve spent smoothing (0 without smoothing).
  double lastSmoothingSeconds() const { return last_smoothing_s_; }
  // Whether the last solve's smoothed path failed the motion re-check (or was no shorter) and
  // the lattice path was returned instead.
  bool lastSmoothingReverted() const { return last_smoothing_reverted_; }

 private:
  sampling::CSpaceOmpl space_;
  int cells_;
  CSpaceMoves moves_;
  double weight_ = 1.0;
  bool smoothing_ = false;
  double smoothing_budget_ = 1.0;
  double time_limit_s_ = 0.0;
  std::uint64_t max_states_ = 0;  // the search's state budget, set at the first solve
  GridReport last_;
  double last_smoothing_s_ = 0.0;
  bool last_smoothing_reverted_ = false;
};

}  // namespace hpcplan::plan
