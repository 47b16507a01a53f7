// The particle-world planners of the fluid: seed 000's RRT*, and any map3d planner of the
// registry (also on the occupancy grid, world = occupancy).
#include "fluid_planners.hpp"

#include "hpcplan/plan/world_planner.hpp"
#include "hpcplan/tree/rrt_star.hpp"

namespace hpcplan::plan::fluid {

std::vector<env::Vec<3>> rrt_star_in_particles(const env::ParticleWorld& world,
                                               const env::Vec<3>& a, const env::Vec<3>& b,
                                               const FluidPlanOptions& o, std::uint64_t seed,
                                               std::stop_token cancel, FluidPlan& out) {
  tree::TreeOptions to;
  to.seed = seed;
  to.step = o.step;
  to.goal_bias = o.goal_bias;
  to.max_samples = o.iterations;
  to.informed = false;
  to.rewire_radius = o.rewire_radius;
  to.goal_radius = o.goal_radius;
  to.stop = Stop(std::move(cancel));
  auto r = tree::rrt_star(world, a, b, to);
  out.status = r.status;
  out.counters.samples = r.counters.samples;
  // A fixed budget that ends without the goal is the seed's "budget" failure.
  if (r.status == Status::no_path) out.status = Status::budget_exceeded;
  return std::move(r.path);
}

template <class W>
std::vector<env::Vec<3>> registry_planner(const W& world, const env::Vec<3>& a,
                                          const env::Vec<3>& b, const FluidPlanOptions& o,
                                          std::uint64_t seed, double resolution,
                                          std::stop_token cancel, FluidPlan& out) {
  WorldPlanOptions wo;
  wo.algo = o.algo;
  wo.seed = seed;
  wo.time_s = o.time_s;
  wo.resolution = resolution;
  wo.cancel = std::move(cancel);
  auto r = plan_in_world(world, a, b, wo);
  out.status = r.status;
  out.counters.expanded = r.counters.expanded;
  out.counters.samples = r.counters.samples;
  return std::move(r.path);
}

template std::vector<env::Vec<3>> registry_planner(const env::OccupancyWorld&, const env::Vec<3>&,
                                                   const env::Vec<3>&, const FluidPlanOptions&,
                                                   std::uint64_t, double, std::stop_token,
                                                   FluidPlan&);
template std::vector<env::Vec<3>> registry_planner(const env::ParticleWorld&, const env::Vec<3>&,
                                                   const env::Vec<3>&, const FluidPlanOptions&,
                                                   std::uint64_t, double, std::stop_token,
                                                   FluidPlan&);

}  // namespace hpcplan::plan::fluid
