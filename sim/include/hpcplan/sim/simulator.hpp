#pragma once
// Seed 000's experiment: a robot crossing the live fluid towards a goal particle, replanning
// every few frames.
//
// One run: the fluid is built and settles for `settle_frames`; then a robot and a goal are
// drawn from the fluid particles at least 0.5 L apart (seeded; the robot's particle leaves the
// fluid, see below), and the frame loop runs: step the fluid, take any finished plan, move the
// robot, stop at the goal (within 4 particle radii) or at a cap, and every `replan_every` frames
// ask for a plan from the robot to where the goal is now. Replans count from the first one after
// the robot and goal exist; a run that hits --max-sim-s or --max-wall-s is recorded as failed.
//
// Scenarios: the seed's particles, static and dynamic (seed preset), and dambreak (beyond the
// seed; the water preset's `column`): a 1 m x 1 m x 2 m water column in the middle of a tank
// 4 m x 1 m x 3 m collapses as the run starts (no settling), and the robot crosses the tank from
// a seeded point in one end bay (x within 0.2..1.0 m of its end wall, 0.2..0.8 m off the side
// walls, 0.3..1.0 m above the floor) to a fixed goal drawn the same way in the other bay.
//
// The robot and its particle (seed 000: "two particles are designated as robot and goal"; the
// robot *is* its particle): the robot takes its particle's place, and the particle leaves the
// fluid there and then (without_particle below), so there is one body where the robot is, and
// every particle the fluid holds is an obstacle to the planners' snapshot, the reactive layer
// and the contact metric, but the goal's, which the robot is to reach. (Until issue 46 the
// particle stayed in the fluid and drifted with it while all three skipped it: the robot could
// overlap a particle no one saw.) The robot does not push the fluid: it is the seed's
// proportional controller moving a point, not an SPH particle (robot.hpp), before and after.
// The goal's particle stays in the fluid and the goal moves with it. A run's particle_count is
// the fluid as built (the robot's particle included).
//
// Pacing:
//   realtime  the seed's: plans run on the planner thread (one at a time) while frames go on,
//             and a frame never takes less than its 0.02 s of wall time, so a slow plan costs
//             simulated time as on a real robot;
//   lockstep  deterministic: a plan runs on the frame loop's thread at its frame and is applied
//             `lockstep_delay` frames later. Fluid, robot, replans and paths then depend only
//             on the seed and the thread count (timings aside).
//
// Threads: run_simulation owns its fluid, robot and planner thread; observers are called on the
// frame loop's thread.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hpcplan/plan/fluid_planner.hpp"
#include "hpcplan/sim/metrics.hpp"
#include "hpcplan/sim/reactive_controller.hpp"
#include "hpcplan/sim/robot.hpp"
#include "hpcplan/sph/fluid.hpp"
#include "hpcplan/sph/fluid_state.hpp"
#include "hpcplan/sph/presets.hpp"

namespace hpcplan::sim {

enum class Pace { realtime, lockstep };
Pace parse_pace(std::string_view name);  // InputError if unknown
std::string_view to_string(Pace p);

struct SimOptions {
  sph::Scenario scenario = sph::Scenario::particles;
  std::size_t particles = 1500;
  plan::FluidPlanOptions planner;  // planner.algo names the planner
  int runs = 1;
  std::uint64_t seed = 1;
  Pace pace = Pace::lockstep;
  int replan_every = 10;     // frames
  int lockstep_delay = 1;    // frames between a lockstep plan's launch and its use
  int settle_frames = -1;    // -1: the scenario's (the seed's 200; dambreak 0)
  double max_sim_s = 300.0;  // simulated seconds before a run is failed
  double max_wall_s = 0.0;   // wall seconds before a run is failed; 0 = none
  double goal_radius = 0.2;  // 4 particle radii of 0.05
  RobotParams robot;
  SafetyParams safety;                       // the radii contacts are measured with
  Controller controller = Controller::seed;  // reactive: the layer of reactive_controller.hpp
  ReactiveParams reactive;
  std::string backend = "cpu";  // the fluid's: cpu or cuda (sph::make_backend)
  // Scenes of one's own (tests, studies): when set, builds each run's fluid from the run's seed
  // instead of the seed preset, and `place` (if set) picks the robot's and goal's particles.
  std::function<sph::FluidState(std::uint64_t seed)> make_fluid;
  std::function<std::pair<std::uint32_t, std::uint32_t>(const sph::FluidState&)> place;
};

// What the frame loop shows an observer after each frame (for VTK and pictures).
struct FrameView {
  int run = 0;
  std::uint64_t frame = 0;                 // since the robot and goal were placed
  const sph::FluidState* fluid = nullptr;  // positions, ids and wall flags current
  const sph::Fluid* owner = nullptr;       // owner->full_state(): every array (VTK)
  env::Vec<3> robot{}, goal{};
  const std::vector<env::Vec<3>>* plan = nullptr;   // the path the robot follows (may be empty)
  const std::vector<env::Vec<3>>* trail = nullptr;  // where the robot has been
  double clearance = 0.0;                           // the robot's, this frame (safety.hpp)
  bool last = false;                                // the run ends after this frame
};

struct SimResult {
  std::vector<RunRecord> runs;
  std::vector<ReplanRecord> replans;
  bool interrupted = false;  // should_stop ended it; `runs` are those finished before
};

// Where the robot and the goal start. The seed's scenarios: two fluid particles at least half
// the box apart, drawn by id from a generator seeded with `seed` (the farthest pair drawn if
// 10,000 draws find none); the robot's particle then leaves the fluid (see above) and the goal
// moves with its particle. dambreak: two fixed points, one in each end bay (see above),
// neither a particle.
inline constexpr std::uint32_t kNoParticle = 0xFFFFFFFFu;
struct Placement {
  std::uint32_t robot_id = kNoParticle, goal_id = kNoParticle;
  env::Vec<3> robot{}, goal{};
};
Placement place_robot_and_goal(sph::Scenario scenario, const sph::FluidState& state,
                               std::uint64_t seed);

// `state` without the particle of this id (the robot's, when the robot takes its place): every
// other particle keeps its entries and its order, the fluid count (for a fluid particle) drops
// by one and the neighbour grid is rebuilt. RunError if no particle has the id.
sph::FluidState without_particle(sph::FluidState state, std::uint32_t id);

// The fluid a run of this scenario starts from (preset, scenario, particles, seed).
sph::FluidOptions fluid_options(const SimOptions& options, std::uint64_t seed);
int settle_frames(const SimOptions& options);  // the options' or the scenario's default

// Checks the options (InputError with a one-line reason).
void validate(const SimOptions& options);

// Runs options.runs runs (run numbers 1..runs, each seeded from (seed, run number)).
// `on_run` sees each run's record as it ends, with every record so far (progress, checkpoints);
// `on_frame` every frame. `done`: the runs already made (a restart's), which are kept and not
// run again: the runs are independent, so the result is the uninterrupted one (lockstep pace).
// `should_stop`, asked after every frame, ends the invocation there: the run under way is
// dropped whole (its records, its plan in flight cancelled) and the result is interrupted.
SimResult run_simulation(
    const SimOptions& options,
    const std::function<void(const RunRecord&, const SimResult& so_far)>& on_run = {},
    const std::function<void(const FrameView&)>& on_frame = {}, SimResult done = {},
    const std::function<bool()>& should_stop = {});

}  // namespace hpcplan::sim
