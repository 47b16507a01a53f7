#include "hpcplan/plan/cspace_grid_planner.hpp"

#include <memory>
#include <vector>

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/util/Console.h>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/memory.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/plan/cspace_planner.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace hpcplan::plan {

CSpaceGridPlanner::CSpaceGridPlanner(const sampling::CSpaceOmpl& space, int cells,
                                     CSpaceMoves moves)
    : ob::Planner(space.si, "CSpaceGrid"), space_(space), cells_(cells), moves_(moves) {
  specs_.approximateSolutions = false;
  specs_.optimizingPaths = false;  // one answer per solve; it does not improve over time
  specs_.directed = true;
  declareParam<int>("cells", this, &CSpaceGridPlanner::setCells, &CSpaceGridPlanner::getCells,
                    "2:1:65535");
  declareParam<std::string>("moves", this, &CSpaceGridPlanner::setMoves,
                            &CSpaceGridPlanner::getMoves);
  declareParam<double>("weight", this, &CSpaceGridPlanner::setWeight, &CSpaceGridPlanner::getWeight,
                       "1.:0.1:10.");
  declareParam<bool>("smoothing", this, &CSpaceGridPlanner::setSmoothing,
                     &CSpaceGridPlanner::getSmoothing, "0,1");
  declareParam<double>("smoothing_budget", this, &CSpaceGridPlanner::setSmoothingBudget,
                       &CSpaceGridPlanner::getSmoothingBudget, "0.:0.5:100.");
  declareParam<double>("time_limit", this, &CSpaceGridPlanner::setTimeLimit,
                       &CSpaceGridPlanner::getTimeLimit, "0.:1.:3600.");
}

ob::PlannerStatus CSpaceGridPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  checkValidity();
  const ob::State* start = pis_.nextStart();
  if (start == nullptr) return ob::PlannerStatus::INVALID_START;
  const auto* goal = dynamic_cast<const ob::GoalState*>(pdef_->getGoal().get());
  if (goal == nullptr) return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
  const ob::State* goal_state = goal->getState();

  GridProblem problem;
  problem.dims = space_.space->dims();
  problem.extent = cells_;
  problem.cspace = CSpaceQuery{space_.space, moves_, sampling::cspace_values(space_, start),
                               sampling::cspace_values(space_, goal_state)};
  GridSearchOptions options;
  options.algorithm = weight_ > 1.0 ? GridAlgorithm::wastar : GridAlgorithm::astar;
  if (weight_ > 1.0) options.weight = weight_;
  options.time_limit_s = time_limit_s_;
  options.keep_path = true;
  // The state budget from the machine's memory, read once: reading it costs a /proc parse,
  // which a small query would feel.
  if (max_states_ == 0) {
    const std::uint64_t avail = available_memory_bytes();
    max_states_ = avail ? avail / 2 / bytes_per_state(CSpaceGraph::kWords) : 100'000'000;
  }
  options.max_states = max_states_;
  options.stop_when = [&ptc] { return ptc(); };
  try {
    last_ = solve_grid(problem, options);
  } catch (const InputError& e) {
    // A start or goal in collision or out of the bounds, a lattice the space cannot have: the
    // query's fault, which OMPL reports as a failed solve rather than an exception.
    OMPL_ERROR("%s: %s", getName().c_str(), e.what());
    return ob::PlannerStatus::ABORT;
  }
  last_smoothing_s_ = 0.0;
  const search::Status status = last_.result.status;
  if (status == search::Status::timeout || status == search::Status::cancelled)
    return ob::PlannerStatus::TIMEOUT;
  if (status != search::Status::solved || !last_.cspace) return ob::PlannerStatus::ABORT;
  const Stopwatch since_search;

  // The report's path, its ends replaced by the problem's own states: they are at distance 0
  // from the report's (which are wrapped into the bounds, or the vertex an end sits on), and
  // an exact solution must begin and end at them bit for bit.
  const auto& points = last_.cspace->path;
  auto path = std::make_shared<og::PathGeometric>(si_);
  path->append(start);
  ob::State* s = si_->allocState();
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    double* x = s->as<ob::RealVectorStateSpace::StateType>()->values;
    std::copy(points[i].begin(), points[i].end(), x);
    path->append(s);
  }
  si_->freeState(s);
  path->append(goal_state);

  last_smoothing_reverted_ = false;
  if (smoothing_ && !ptc()) {
    const Stopwatch smoothing;
    const og::PathGeometric lattice_path(*path);
    og::PathSimplifier simplifier(si_, pdef_->getGoal(), pdef_->getOptimizationObjective());
    if (smoothing_budget_ > 0) {
      // Building the path is charged to the budget too, so the smoothed answer comes within
      // (1 + smoothing_budget) times the search's own time.
      const double budget_s =
          smoothing_budget_ * last_.result.counters.time_ms / 1e3 - since_search.seconds();
      if (budget_s > 0)
        simplifier.simplify(
            *path,
            ob::plannerOrTerminationCondition(ptc, ob::timedPlannerTerminationCondition(budget_s)),
            /*atLeastOnce=*/false);
    } else {
      simplifier.simplify(*path, ptc);
    }
    // The simplifier's shortcuts keep pieces of the lattice's motions, whose samples differ
    // from the motion's own: a motion valid at its samples can have a piece whose samples are
    // not (chain-12, 12 cells: a 0.41 rad piece of a 0.74 rad edge, every few runs), and the
    // simplifier's closing repair then returns such a path, or a longer one. Every motion of
    // the result is checked again; a path that fails, or is no shorter, gives way to the
    // lattice's.
    bool keep = path->length() < lattice_path.length();
    for (std::size_t i = 1; keep && i < path->getStateCount(); ++i)
      keep = si_->checkMotion(path->getState(i - 1), path->getState(i));
    if (!keep) {
      *path = lattice_path;
      last_smoothing_reverted_ = true;
    }
    last_smoothing_s_ = smoothing.seconds();
  }
  pdef_->addSolutionPath(path, false, 0.0, getName());
  // Report the answer the moment it exists, as the anytime planners report theirs (the
  // harness's first-solution time), rather than at the join of Benchmark's polling thread.
  if (const auto& report = pdef_->getIntermediateSolutionCallback()) {
    const std::vector<const ob::State*> states(path->getStates().begin(), path->getStates().end());
    const auto& objective = pdef_->getOptimizationObjective();
    report(this, states, objective ? path->cost(objective) : ob::Cost(path->length()));
  }
  return ob::PlannerStatus::EXACT_SOLUTION;
}

void CSpaceGridPlanner::getPlannerData(ob::PlannerData& data) const {
  Planner::getPlannerData(data);
  data.properties["expanded INTEGER"] = std::to_string(last_.result.counters.expanded);
  data.properties["lattice cost REAL"] = std::to_string(last_.result.cost);
  data.properties["search time REAL"] = std::to_string(last_.result.counters.time_ms / 1e3);
  data.properties["smoothing time REAL"] = std::to_string(last_smoothing_s_);
}

}  // namespace hpcplan::plan
