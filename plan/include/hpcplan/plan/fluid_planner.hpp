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
// Blocked ends. An end that is not free moves to the nearest free spot within `escape` cells
// (env/fluid_escape.hpp), and the plan runs from (to) there. The leg from the robot to its
// escape spot and from the goal's escape spot to the goal are the only ones not
// collision-checked, and the plan says it took them (start_escaped, goal_escaped). With no free
// spot in reach the replan ends no_path with the blocked end named (reason start_blocked or
// goal_blocked).
//
// Files: this dispatch (fluid_planner.cpp: the planner table, worlds, escapes, smoothing), the
// occupancy planners (fluid_grid_planners.cpp: A*, D* Lite) and the particle-world planners
// (fluid_particle_planners.cpp: RRT*, the registry's map3d planners).
//
// Threads: plan_in_fluid is reentrant; a FluidReplanner belongs to one thread at a time.
#include <cstdint>
#include <memory>
#include <stop_token>
#include <string>
#include <vector>

#include "hpcplan/core/result.hpp"
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
};

// Which end of a replan had no free spot within reach (the replan then ends no_path).
enum class BlockedEnd { none, start, goal };

// The seed's failure categories, read from how a replan ended: "" (solved), start_blocked,
// goal_blocked, disconnected (no_path otherwise), budget (budget_exceeded or timeout),
// cancelled.
std::string_view failure_reason(Status status, BlockedEnd blocked);

// D* Lite's bookkeeping for one replan: a new search or the previous one repaired.
enum class Incremental { none, restart, repair };
std::string_view to_string(Incremental i);  // "", "restart", "repair"

// The shared Result (path robot .. goal after smoothing, empty unless solved; cost = its
// length; counters: expanded = grid expansions, samples = tree iterations, collision_checks,
// time_ms = the whole replan), plus what a replan through the fluid adds.
struct FluidPlan : Result<env::Vec<3>> {
  BlockedEnd blocked = BlockedEnd::none;
  double raw_length = 0.0;   // the planner's path, before smoothing
  double search_cost = 0.0;  // grid planners: the optimum they proved, in cells
  bool start_escaped = false, goal_escaped = false;
  // dstar_lite: restart (first replan, or the goal changed cell: a new search) or repair (the
  // previous search updated for the moved robot and the changed cells)
  Incremental incremental = Incremental::none;
  std::uint64_t changed_cells = 0;  // dstar_lite repairs: cells whose occupancy changed
  double world_us = 0.0;            // building the world from the snapshot
  double search_us = 0.0;           // the planner
  double smooth_us = 0.0;           // the smoother
  std::string_view reason() const { return failure_reason(status, blocked); }
};

namespace fluid {
enum class Runner : int;  // how a planner of the fluid runs (fluid_planner.cpp's table)
struct DStarState;        // D* Lite's search kept between replans
}  // namespace fluid

// A planner that may keep state between the replans of one run (D* Lite does; the others are
// stateless and simply plan each frame afresh).
class FluidReplanner {
 public:
  // Throws InputError for an unknown planner or bad options.
  explicit FluidReplanner(FluidPlanOptions options);
  ~FluidReplanner();
  FluidReplanner(FluidReplanner&&) noexcept;
  FluidReplanner& operator=(FluidReplanner&&) noexcept;

  // Whether this planner searches the occupancy grid (A*, A* Euclid, D* Lite, or a map3d
  // planner with world = occupancy): only then does FluidPlanOptions::occupancy matter.
  bool plans_on_grid() const { return on_grid_; }

  // One replan from `robot` to `goal` through `snapshot`. `replan_index` varies the random
  // planners' seed from one replan to the next, reproducibly; `cancel` ends it early (status
  // cancelled).
  FluidPlan plan(const env::FluidSnapshot& snapshot, const env::Vec<3>& robot,
                 const env::Vec<3>& goal, std::uint64_t replan_index, std::stop_token cancel = {});

 private:
  void plan_on_grid(const env::FluidSnapshot& snapshot, const env::Vec<3>& robot,
                    const env::Vec<3>& goal, std::uint64_t seed, std::stop_token cancel,
                    FluidPlan& out);
  void plan_on_particles(const env::FluidSnapshot& snapshot, const env::Vec<3>& robot,
                         const env::Vec<3>& goal, std::uint64_t seed, std::stop_token cancel,
                         FluidPlan& out);

  FluidPlanOptions options_;
  fluid::Runner runner_;
  bool on_grid_ = false;
  std::unique_ptr<fluid::DStarState> dstar_;
  // The worlds, rebuilt in place at every replan (their memory is reused, not faulted in anew).
  std::unique_ptr<env::OccupancyWorld> grid_world_;
  std::unique_ptr<env::ParticleWorld> ball_world_;
};

// Whether algo runs in the simulator (a sim planner or a map3d one).
bool is_fluid_planner(std::string_view algo);

}  // namespace hpcplan::plan
