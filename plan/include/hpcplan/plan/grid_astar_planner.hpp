#pragma once
// The grid planner (serial lattice A* / weighted A*) as an OMPL planner, so it runs inside
// ompl::tools::Benchmark beside OMPL's planners on the same ProblemDefinition:
//  - the start and goal states are mapped to their lattice cells, solve_grid() searches the
//    seed-002 lattice, and the lattice path becomes continuous cell centres with the exact
//    start and goal states at its ends (a segment inside one cell is always valid);
//  - with `shortcut` on, the path is then shortened in continuous space, within a budget of
//    `smoothing_budget` times the search's own time (building the path included), below the
//    lattice's quality limit (sqrt(d/2) in open space): in 2D to the exact taut path of its
//    homotopy class on the field's cells (env/taut_path_2d.hpp, every segment through the field's
//    exact walk, which is at least as strict as any motion validator the space has); in 3D with
//    hpcplan's tightener and from 4D up with OMPL's PathSimplifier then the tightener, both through
//    the space information's own motion validator;
//  - the lattice's collision checks are added to the world's counter, so checks are counted
//    by one object for every planner.
// Parameters (declared, so Benchmark logs them): weight (1 = A*), heuristic (lattice |
// euclidean), smoothing (0/1: simplify + tighten), smoothing_budget (the smoothing's time as a
// multiple of the search's; 0 = until it converges), time_limit (s, 0 = none). OMPL's
// termination condition ends the search and the smoothing early.
#include <cstdint>
#include <string>

#include <ompl/base/Planner.h>
#include <ompl/geometric/PathGeometric.h>

#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/sampling/gog_space.hpp"

namespace hpcplan::plan {

class GridAStarPlanner : public ompl::base::Planner {
 public:
  // The dimension from which the smoothing starts with OMPL's randomised simplifier.
  static constexpr unsigned kSimplifierFromDims = 4;

  GridAStarPlanner(const sampling::GogSpace& space,
                   Connectivity connectivity = Connectivity::seed_pairs);

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  void setWeight(double w) { weight_ = w; }
  double getWeight() const { return weight_; }
  void setHeuristic(const std::string& h);
  std::string getHeuristic() const { return std::string(to_string(heuristic_)); }
  void setShortcut(bool s) { shortcut_ = s; }
  bool getShortcut() const { return shortcut_; }
  void setSmoothingBudget(double factor) { smoothing_budget_ = factor; }
  double getSmoothingBudget() const { return smoothing_budget_; }
  void setTimeLimit(double s) { time_limit_s_ = s; }
  double getTimeLimit() const { return time_limit_s_; }

  // The last search's report (lattice cost, expansions, ...), for callers that want more
  // than the path.
  const GridReport& lastReport() const { return last_; }
  // Seconds the last solve spent smoothing (0 without smoothing).
  double lastSmoothingSeconds() const { return last_smoothing_s_; }

 private:
  // spent_s: seconds since the search ended (building the path), charged to the budget.
  void smooth(ompl::geometric::PathGeometric& path,
              const ompl::base::PlannerTerminationCondition& ptc, double spent_s);
  void pull_taut_2d(ompl::geometric::PathGeometric& path,
                    const ompl::base::PlannerTerminationCondition& ptc, double budget_s);

  sampling::GogSpace space_;
  Connectivity connectivity_;
  double weight_ = 1.0;
  HeuristicKind heuristic_ = HeuristicKind::lattice;
  bool shortcut_ = true;
  double smoothing_budget_ = 1.0;
  double time_limit_s_ = 0.0;
  std::uint64_t max_states_ = 0;  // the search's state budget, set at the first solve
  GridReport last_;
  double last_smoothing_s_ = 0.0;
};

}  // namespace hpcplan::plan
