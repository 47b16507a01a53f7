#pragma once
// One entry point for every planner in a continuous world (3D box maps, the 2D sphere world):
// the grid searches run the shared search engine on a ContinuousGrid, the tree planners are
// hpcplan's own, and "ompl:<name>" hands the same world to an OMPL planner. Every returned
// path starts exactly at the start, ends exactly at the goal and has been re-checked segment
// by segment with the world's exact test (a failure there is an internal error, never an
// answer).
#include <cstdint>
#include <stop_token>
#include <string>
#include <vector>

#include "hpcplan/core/result.hpp"
#include "hpcplan/core/status.hpp"

#include "hpcplan/env/point.hpp"

namespace hpcplan::plan {

struct WorldPlanOptions {
  // a map3d/sphere2d planner of the registry (hpcplan planners): astar, wastar, dijkstra,
  // thetastar, visgraph, rrt, birrt, rrtstar, hybrid, hybrid_pick, hybrid_sample, ompl:<name>
  std::string algo = "astar";
  double resolution = 0.1;  // grid searches
  double weight = 2.0;      // wastar
  double spacing = 0.0;     // visgraph: bend points this far apart; 0 = a 40th of the world
  std::uint64_t seed = 1;
  double time_s = 1.0;             // tree planners: RRT* refines until then; others stop at a path
  bool stop_at_first = false;      // tree and OMPL planners: anytime ones end at their first path
  double step = 0.0;               // tree planners' eta; 0 = a twentieth of the largest extent
  std::uint64_t max_states = 0;    // grid searches' memory budget (states); 0 = none
  int samples_per_expansion = 10;  // hybrid, hybrid_sample
  bool shortcut = false;           // string pulling + tightening after planning
  std::stop_token cancel;          // another thread may end the plan (status cancelled)
};

// The one Result (cost = length of the returned path, after shortcutting when asked;
// counters.time_ms = planning plus shortcutting; counters.peak_states = stored states of the
// searches or vertices of the trees), plus what a world plan adds.
template <int D>
struct WorldPlan : Result<env::Vec<D>> {
  std::string algo;
  double raw_cost = 0.0;  // the path's length as the planner returned it
  double plan_ms = 0.0;   // planning alone
};

// Throws InputError for an unknown algorithm, bad options, or a start/goal that is not free.
template <class W>
WorldPlan<W::kDim> plan_in_world(const W& world, const env::Vec<W::kDim>& start,
                                 const env::Vec<W::kDim>& goal, const WorldPlanOptions& o);

// The exact re-check every plan goes through: ends equal start and goal, every segment free.
// Returns an empty string or what is wrong.
template <class W>
std::string path_problem(const W& world, const std::vector<env::Vec<W::kDim>>& path,
                         const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal);

}  // namespace hpcplan::plan
