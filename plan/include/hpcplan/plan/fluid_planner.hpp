#pragma once
// Planning through one frame of the fluid (seed 000's replanning step): the world is built from
// an immutable snapshot, the robot's and the goal's ends are made plannable, a planner runs and
// the seed's greedy line-of-sight smoother (env::shortcut_path) runs on its path in the same
// world the planner used.
//
// Planners (setting "sim" of the registry):
//   astar         26-connected A* on the occupancy grid, exact octile heuristic
//   astar_euclid  the same with the seed's Euclidean heuristic (same paths' cost, more states)
//   dstar_lite    D* Lite on the occupancy grid: keeps its search between replans and repairs
//                 only what the moved cells and the moved goal invalidate (FluidReplanner)
//   rrtstar       the seed's RRT* on the particle world: 2,000 iterations, step 0.3, goal bias
//                 10%, fixed rewiring radius 0.6, goal captured within 0.3; rewiring passes cost
//                 savings down the subtree, nearest-neighbour and radius queries on an
//                 incremental KD-tree
//   any planner of the map3d setting (birrt, rrt, thetastar, ompl:RRTConnect, ...) by name, on
//   the particle world, or on the occupancy world with world = occupancy.
//
// Blocked ends. The robot and the goal are particles in a moving fluid, so a frame often puts a
// neighbour within reach of one of them. Rather than failing, an end that is not free moves to
// the nearest free spot within `escape` (grid: the centre of the nearest free cell within that
// many cells, Chebyshev; continuous: the first free point on rays in 26 directions at
// 0.05-wide steps out to `escape` cells' length), and the plan runs from (to) there. The leg
// from the robot to its escape spot and from the goal's escape spot to the goal are the only
// ones not collision-checked, and the plan says it took them (start_escaped, goal_escaped).
// With no free spot in reach the replan fails with reason start_blocked or goal_blocked.
//
// Threads: plan_in_fluid is reentrant; a FluidReplanner belongs to one thread at a time.
#include <cstdint>
#include <memory>
#include <stop_token>
#include <string>
#include <vector>

#include "hpcplan/core/status.hpp"
#include "hpcplan/env/fluid_snapshot.hpp"
#include "hpcplan/env/occupancy_world.hpp"
#include "hpcplan/env/particle_world.hpp"
#include "hpcplan/plan/planner_registry.hpp"

namespace hpcplan::plan {

struct FluidPlanOptions {
  std::string algo = "astar";
  std::string world = "default";  // map3d planners: particles (default) or occupancy
  env::OccupancyConfig occupancy;
  env::ParticleWorldConfig particles;
  std::uint64_t seed = 1;
  int escape_cells = 2;  // how far a blocked end may move, in occupancy cells
  // rrtstar (seed 000)
  std::uint64_t iterations = 2000;
  double step = 0.3;
  double goal_bias = 0.1;
  double rewire_radius = 0.6;
  double goal_radius = 0.3;
  // map3d planners: their time budget (anytime planners refine until then) and grid resolution
  double time_s = 0.05;
  std::stop_token cancel;  // ends a plan early (status cancelled)
};

// Why a replan failed (empty when it did not).
enum class FailReason { none, start_blocked, goal_blocked, disconnected, budget, cancelled };
std::string_view to_string(FailReason r);

struct FluidPlan {
  Status status = Status::no_path;
  FailReason reason = FailReason::disconnected;
  std::vector<env::Vec<3>> path;  // robot .. goal after smoothing (empty unless solved)
  double raw_length = 0.0;        // the planner's path, before smoothing
  double search_cost = 0.0;       // grid planners: the optimum they proved, in cells
  double length = 0.0;            // the returned path
  bool start_escaped = false, goal_escaped = false;
  // dstar_lite: "restart" (first replan, or the goal changed cell: a new search) or "repair"
  // (the previous search updated for the moved robot and the changed cells); else empty.
  std::string incremental;
  std::uint64_t changed_cells = 0;  // dstar_lite repairs: cells whose occupancy changed
  std::uint64_t expanded = 0;       // grid searches: expansions; trees: iterations
  std::uint64_t collision_checks = 0;
  double world_us = 0.0;   // building the world from the snapshot
  double search_us = 0.0;  // the planner
  double smooth_us = 0.0;  // the smoother
  double total_us = 0.0;
};

// A planner that may keep state between the replans of one run (D* Lite does; the others are
// stateless and simply plan each frame afresh).
class FluidReplanner {
 public:
  // Throws InputError for an unknown planner or bad options.
  explicit FluidReplanner(FluidPlanOptions options);
  ~FluidReplanner();
  FluidReplanner(FluidReplanner&&) noexcept;
  FluidReplanner& operator=(FluidReplanner&&) noexcept;

  // One replan from `robot` to `goal` through `snapshot`. `replan_index` varies the random
  // planners' seed from one replan to the next, reproducibly.
  FluidPlan plan(const env::FluidSnapshot& snapshot, const env::Vec<3>& robot,
                 const env::Vec<3>& goal, std::uint64_t replan_index, std::stop_token cancel = {});

 private:
  struct Incremental;  // D* Lite's state between replans
  FluidPlanOptions options_;
  std::unique_ptr<Incremental> incremental_;
  // The worlds, rebuilt in place at every replan (their memory is reused, not faulted in anew).
  std::unique_ptr<env::OccupancyWorld> grid_world_;
  std::unique_ptr<env::ParticleWorld> ball_world_;
};

// Whether algo runs in the simulator (a sim planner or a map3d one).
bool is_fluid_planner(std::string_view algo);

}  // namespace hpcplan::plan
