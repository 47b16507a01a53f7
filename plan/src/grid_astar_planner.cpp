#include "hpcplan/plan/grid_astar_planner.hpp"

#include <cmath>
#include <memory>

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/memory.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/gog_world.hpp"
#include "hpcplan/env/path_shortcut.hpp"
#include "hpcplan/env/taut_path_2d.hpp"
#include "hpcplan/graph/jump_point_graph.hpp"
#include "hpcplan/sampling/path_tightening.hpp"
#include "hpcplan/sampling/world_space.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace hpcplan::plan {

namespace {

// Whether a path of lattice cells changes direction at cell i (its ends count as turns).
bool turns_at(const std::vector<std::vector<int>>& cells, std::size_t i) {
  if (i == 0 || i + 1 == cells.size()) return true;
  for (std::size_t a = 0; a < cells[i].size(); ++a)
    if (cells[i][a] - cells[i - 1][a] != cells[i + 1][a] - cells[i][a]) return true;
  return false;
}

// A 2D field as the taut path's world: its exact segment test and its cells (the jump point
// search's view of them), counting the cells the walks read. One run, one thread.
class FieldCells2D {
 public:
  static constexpr int kDim = 2;
  explicit FieldCells2D(const GogField& field) : field_(field), cells_(field) {}

  bool segment_free(const env::Vec<2>& a, const env::Vec<2>& b) const {
    const env::GogSegmentWalk walk = env::gog_walk_segment(field_, a.data(), b.data());
    walked_ += walk.cells;
    return walk.free;
  }
  // Cells outside the box are free, as in the walk: the box is convex, so no taut path rests
  // on its walls.
  bool blocked(int x, int y) const {
    const int n = cells_.extent();
    return x >= 0 && y >= 0 && x < n && y < n && !cells_.free(x, y);
  }
  std::uint64_t segment_cells() const { return walked_; }

 private:
  const GogField& field_;
  GogCells2D cells_;
  mutable std::uint64_t walked_ = 0;
};

}  // namespace

GridAStarPlanner::GridAStarPlanner(const sampling::GogSpace& space, Connectivity connectivity)
    : ob::Planner(space.si, "GridAStar"), space_(space), connectivity_(connectivity) {
  specs_.approximateSolutions = false;
  specs_.optimizingPaths = false;  // one answer per solve; it does not improve over time
  specs_.directed = true;
  declareParam<double>("weight", this, &GridAStarPlanner::setWeight, &GridAStarPlanner::getWeight,
                       "1.:0.1:10.");
  declareParam<std::string>("heuristic", this, &GridAStarPlanner::setHeuristic,
                            &GridAStarPlanner::getHeuristic);
  declareParam<bool>("smoothing", this, &GridAStarPlanner::setShortcut,
                     &GridAStarPlanner::getShortcut, "0,1");
  declareParam<double>("smoothing_budget", this, &GridAStarPlanner::setSmoothingBudget,
                       &GridAStarPlanner::getSmoothingBudget, "0.:0.5:100.");
  declareParam<double>("time_limit", this, &GridAStarPlanner::setTimeLimit,
                       &GridAStarPlanner::getTimeLimit, "0.:1.:3600.");
}

void GridAStarPlanner::setHeuristic(const std::string& h) {
  heuristic_ = parse_heuristic(h);
}

ob::PlannerStatus GridAStarPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  checkValidity();
  const ob::State* start = pis_.nextStart();
  if (start == nullptr) return ob::PlannerStatus::INVALID_START;
  const auto* goal = dynamic_cast<const ob::GoalState*>(pdef_->getGoal().get());
  if (goal == nullptr) return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
  const ob::State* goal_state = goal->getState();
  const GogField& field = *space_.field;
  const double* start_x = start->as<ob::RealVectorStateSpace::StateType>()->values;
  const double* goal_x = goal_state->as<ob::RealVectorStateSpace::StateType>()->values;
  if (!env::gog_point_free(field, start_x)) return ob::PlannerStatus::INVALID_START;
  if (!env::gog_point_free(field, goal_x)) return ob::PlannerStatus::INVALID_GOAL;

  GridProblem problem;
  problem.dims = field.dims();
  problem.extent = field.extent();
  problem.gog = field.params();
  problem.gog.threshold = field.threshold();  // the very field the checker uses
  problem.connectivity = connectivity_;
  problem.start = env::gog_cell_of(field, start_x);
  problem.goal = env::gog_cell_of(field, goal_x);
  GridSearchOptions options;
  options.algorithm = weight_ > 1.0 ? GridAlgorithm::wastar : GridAlgorithm::astar;
  if (weight_ > 1.0) options.weight = weight_;
  options.heuristic = heuristic_;
  options.time_limit_s = time_limit_s_;
  options.keep_path = true;
  // The state budget from the machine's memory, read once: reading it costs a /proc parse,
  // which a 2D query would feel.
  if (max_states_ == 0) {
    const std::uint64_t avail = available_memory_bytes();
    const KeyLayout layout(problem.dims, problem.extent);
    const int words = layout.words() <= 1 ? 1 : layout.words() <= 2 ? 2 : 4;
    max_states_ = avail ? avail / 2 / bytes_per_state(words) : 100'000'000;
  }
  options.max_states = max_states_;
  options.stop_when = [&ptc] { return ptc(); };
  last_ = solve_grid(field, problem, options);  // the space's own field, built once
  space_.checks->add(last_.result.counters.collision_checks);
  if (last_.result.status == search::Status::timeout ||
      last_.result.status == search::Status::cancelled)
    return ob::PlannerStatus::TIMEOUT;
  if (last_.result.status != search::Status::solved) return ob::PlannerStatus::ABORT;
  // The smoothing's budget also covers building the continuous path, so the smoothed answer
  // comes within (1 + smoothing_budget) times the search's own time.
  const Stopwatch since_search;

  auto path = std::make_shared<og::PathGeometric>(si_);
  const auto append_centre = [&](const std::vector<int>& cell) {
    ob::State* s = si_->allocState();
    sampling::cell_centre(cell, s);
    path->append(s);
    si_->freeState(s);
  };
  path->append(start);
  // Only the cells where the lattice path turns: the centres between them lie on the same
  // straight segments, so the path is the same curve with a fraction of the vertices, and the
  // smoothing's passes over vertices cost less.
  for (std::size_t i = 0; i < last_.result.path.size(); ++i)
    if (turns_at(last_.result.path, i)) append_centre(last_.result.path[i]);
  path->append(goal_state);
  // Drop the centres that coincide with the exact start or goal (zero-length segments).
  auto& states = path->getStates();
  if (states.size() > 2 && si_->distance(states[0], states[1]) == 0.0) {
    si_->freeState(states[1]);
    states.erase(states.begin() + 1);
  }
  if (states.size() > 2 && si_->distance(states[states.size() - 2], states.back()) == 0.0) {
    si_->freeState(states[states.size() - 2]);
    states.erase(states.end() - 2);
  }
  last_smoothing_s_ = 0.0;
  if (shortcut_ && !ptc()) {
    const Stopwatch smoothing;
    smooth(*path, ptc, since_search.seconds());
    last_smoothing_s_ = smoothing.seconds();
  }
  pdef_->addSolutionPath(path, false, 0.0, getName());
  // Report the answer the moment it exists, as the anytime planners report theirs: a harness
  // that times solve() as a whole (ompl::tools::Benchmark's "time REAL") also counts the join
  // of its polling thread, which sleeps in 1 ms slices, and so rounds a sub-millisecond
  // solve up to the next slice.
  if (const auto& report = pdef_->getIntermediateSolutionCallback()) {
    const std::vector<const ob::State*> states(path->getStates().begin(), path->getStates().end());
    const auto& objective = pdef_->getOptimizationObjective();
    report(this, states, objective ? path->cost(objective) : ob::Cost(path->length()));
  }
  return ob::PlannerStatus::EXACT_SOLUTION;
}

// In 2D the taut path has a closed form on the field's cells (pull_taut_2d). From 4D up, OMPL's
// randomised simplifier is the global step: its shortcuts between points anywhere on two
// segments straighten a high-dimensional staircase better, per check, than any vertex-to-vertex
// pass. It stops short of the taut path around obstacle corners, so the tightener (string
// pulling, then rounds of sliding the bends) finishes. In 3D the lattice path has few bends,
// string pulling already takes most of the gain, and the simplifier only spent the budget the
// tightener could use (at 2D, before the closed form, with the budget at the search's time,
// the tightener alone reached 1.145 against 1.187 with both; at 8D, 1.547 against 1.467).
// Both share one budget, a multiple of the search's own time less what building the path
// took, so the smoothed answer costs a bounded factor of the lattice answer.
void GridAStarPlanner::smooth(og::PathGeometric& path, const ob::PlannerTerminationCondition& ptc,
                              double spent_s) {
  // 0 = no limit (smoothing_budget 0: until it converges).
  double budget_s = 0.0;
  if (smoothing_budget_ > 0) {
    budget_s = smoothing_budget_ * last_.result.counters.time_ms / 1e3 - spent_s;
    if (budget_s <= 0) return;  // building the path spent it all
  }
  if (si_->getStateDimension() == 2) {
    pull_taut_2d(path, ptc, budget_s);
    return;
  }
  const Stopwatch clock;
  const bool simplify = si_->getStateDimension() >= kSimplifierFromDims;
  if (simplify) {
    og::PathSimplifier simplifier(si_, pdef_->getGoal(), pdef_->getOptimizationObjective());
    if (budget_s > 0)
      simplifier.simplify(
          path,
          ob::plannerOrTerminationCondition(ptc, ob::timedPlannerTerminationCondition(budget_s)),
          /*atLeastOnce=*/false);
    else
      simplifier.simplify(path, ptc);
  }
  sampling::TighteningOptions tighten;
  // Cell widths: enough vertices to wrap every corner. Without the simplifier first (3D) the
  // string-pulled path is nearly taut, and longer pieces leave more rounds within the budget:
  // at budget 1, 3D 1.118 -> 1.106 (9 runs), with the converged length unchanged.
  tighten.max_segment = simplify ? 2.0 : 8.0;
  tighten.pull_string = true;
  if (budget_s > 0) {
    tighten.time_limit_s = budget_s - clock.seconds();
    if (tighten.time_limit_s <= 0) return;
  }
  sampling::tighten_path(si_, path, ptc, tighten);
}

// In 2D the obstacles are the field's cells and the taut path has a closed form
// (env/taut_path_2d.hpp): string pulling, then passes that wrap each bend's triangle, two
// passes on the default problem. It reaches the exact shortest path of the string-pulled
// path's class (1.1249 on the default problem), where the sliding tightener was still
// converging at the budget (1.136 at budget 1, 1.129 converged).
void GridAStarPlanner::pull_taut_2d(og::PathGeometric& path,
                                    const ob::PlannerTerminationCondition& ptc, double budget_s) {
  // The budget covers the string pulling too.
  env::TautOptions options;
  options.stop = budget_s > 0 ? Stop::after(budget_s) : Stop();
  options.stop.also_when([&ptc] { return ptc(); });
  const FieldCells2D cells(*space_.field);
  std::vector<env::Vec<2>> points = env::shortcut_path(cells, sampling::points_of<2>(path));
  const env::TautStats stats = env::taut_path_2d(
      cells, [&cells](int x, int y) { return cells.blocked(x, y); }, points, options);
  space_.checks->add(cells.segment_cells() + stats.cells_read);
  sampling::set_path<2>(si_, path, points);
}

void GridAStarPlanner::getPlannerData(ob::PlannerData& data) const {
  Planner::getPlannerData(data);
  data.properties["expanded INTEGER"] = std::to_string(last_.result.counters.expanded);
  data.properties["lattice cost REAL"] = std::to_string(last_.result.cost);
  data.properties["search time REAL"] = std::to_string(last_.result.counters.time_ms / 1e3);
  data.properties["smoothing time REAL"] = std::to_string(last_smoothing_s_);
}

}  // namespace hpcplan::plan
