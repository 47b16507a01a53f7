#include "hpcplan/sampling/world_ompl.hpp"

#include <functional>
#include <map>
#include <memory>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/box_world.hpp"
#include "hpcplan/env/gog_world.hpp"
#include "hpcplan/env/occupancy_world.hpp"
#include "hpcplan/env/particle_world.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/sampling/ompl_planners.hpp"
#include "hpcplan/sampling/world_space.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace hpcplan::sampling {

template <class W>
tree::TreeResult<W::kDim> solve_with_ompl(const W& world, const env::Vec<W::kDim>& start,
                                          const env::Vec<W::kDim>& goal, const std::string& name,
                                          double time_s, std::uint64_t seed, std::stop_token cancel,
                                          bool stop_at_first) {
  constexpr int D = W::kDim;
  const OmplPlannerKind* kind = find_ompl_planner(name);
  if (kind == nullptr) throw InputError("unknown OMPL planner '" + name + "'");
  // OMPL seeds its generators once per process, before the first one is made.
  static const bool seeded = [&] {
    ompl::RNG::setSeed(seed);
    return true;
  }();
  (void)seeded;
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

  Stopwatch clock;
  const std::uint64_t checks0 = CheckCounter::this_thread();
  const ob::SpaceInformationPtr si = make_space_information(world);
  const ob::StateSpacePtr& space = si->getStateSpace();
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> s(space), g(space);
  for (int k = 0; k < D; ++k) s[k] = start[k], g[k] = goal[k];
  pdef->setStartAndGoalStates(s, g, 1e-9);
  auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
  // Any path satisfies an infinite threshold: the optimizing planners end at their first.
  if (stop_at_first) objective->setCostThreshold(ob::Cost(std::numeric_limits<double>::infinity()));
  pdef->setOptimizationObjective(objective);
  ob::PlannerPtr planner = kind->make(si);
  planner->setProblemDefinition(pdef);
  planner->setup();
  const ob::PlannerStatus status = planner->solve(ob::plannerOrTerminationCondition(
      ob::timedPlannerTerminationCondition(time_s),
      ob::PlannerTerminationCondition([cancel] { return cancel.stop_requested(); })));

  tree::TreeResult<D> r;
  r.counters.time_ms = clock.milliseconds();
  ob::PlannerData data(si);
  planner->getPlannerData(data);
  r.counters.peak_states = data.numVertices();
  if (status == ob::PlannerStatus::EXACT_SOLUTION && pdef->getSolutionPath()) {
    const auto& path = *pdef->getSolutionPath()->as<og::PathGeometric>();
    for (std::size_t i = 0; i < path.getStateCount(); ++i)
      r.path.push_back(point_of<D>(path.getState(i)));
    if (!r.path.empty() && !(r.path.front() == start)) r.path.insert(r.path.begin(), start);
    if (!r.path.empty() && !(r.path.back() == goal)) {
      if (world.segment_free(r.path.back(), goal))
        r.path.push_back(goal);
      else
        r.path.clear();
    }
  }
  if (!r.path.empty()) {
    r.status = Status::solved;
    r.cost = env::polyline_length<D>(r.path);
    r.hops = r.path.size() - 1;
  } else {
    r.status =
        status == ob::PlannerStatus::TIMEOUT || status == ob::PlannerStatus::APPROXIMATE_SOLUTION
            ? Status::timeout
            : Status::no_path;
  }
  r.counters.collision_checks = CheckCounter::this_thread() - checks0;
  return r;
}

template tree::TreeResult<3> solve_with_ompl(const env::BoxWorld&, const env::Vec<3>&,
                                             const env::Vec<3>&, const std::string&, double,
                                             std::uint64_t, std::stop_token, bool);
template tree::TreeResult<3> solve_with_ompl(const env::GogWorld<3>&, const env::Vec<3>&,
                                             const env::Vec<3>&, const std::string&, double,
                                             std::uint64_t, std::stop_token, bool);
template tree::TreeResult<3> solve_with_ompl(const env::OccupancyWorld&, const env::Vec<3>&,
                                             const env::Vec<3>&, const std::string&, double,
                                             std::uint64_t, std::stop_token, bool);
template tree::TreeResult<3> solve_with_ompl(const env::ParticleWorld&, const env::Vec<3>&,
                                             const env::Vec<3>&, const std::string&, double,
                                             std::uint64_t, std::stop_token, bool);
template tree::TreeResult<2> solve_with_ompl(const env::SphereWorld&, const env::Vec<2>&,
                                             const env::Vec<2>&, const std::string&, double,
                                             std::uint64_t, std::stop_token, bool);

}  // namespace hpcplan::sampling
