#include "hpcplan/cli/sim_options.hpp"

#include <omp.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hpcplan/cli/fluid_options.hpp"
#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/cli/output_paths.hpp"
#include "hpcplan/cli/vtk_dir.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/io/sim_checkpoint.hpp"
#include "hpcplan/io/vtk_fluid.hpp"
#include "hpcplan/plan/fluid_planner.hpp"
#include "hpcplan/sph/presets.hpp"

namespace hpcplan::cli {

void add_sim_options(CLI::App* cmd, SimArgs& a) {
  sim::SimOptions& o = a.o;
  add_number(cmd, "--particles", o.particles,
             "Fluid particles (dambreak rounds to its lattice: 2 k^3, k even)", 2, 200'000'000)
      ->capture_default_str();
  cmd->add_option("--scenario", a.scenario,
                  "particles | static | dynamic (the seed's) | dambreak (a water column "
                  "collapsing across the robot's way)")
      ->capture_default_str();
  cmd->add_option("--algo", o.planner.algo,
                  "Planner: astar, astar_euclid, dstar_lite, rrtstar (hpcplan planners --world "
                  "sim), or any map3d planner")
      ->capture_default_str();
  cmd->add_option("--world", o.planner.world,
                  "map3d planners: particles (balls of 0.10) or occupancy (the A* grid)");
  add_number(cmd, "--runs", o.runs, "Runs, numbered 1..R, each seeded from (seed, run)", 1,
             1'000'000)
      ->capture_default_str();
  add_number(cmd, "--seed", o.seed, "Seed of the fluid, the robot and goal, and the planners")
      ->capture_default_str();
  cmd->add_option("--pace", a.pace,
                  "lockstep (deterministic, plans applied after --lockstep-delay frames) | "
                  "realtime (planner thread, frames of at least 0.02 s wall)")
      ->capture_default_str();
  cmd->add_option("--controller", a.controller,
                  "seed (steer along the plan, the seed's) | reactive (keep clear of the moving "
                  "particles between replans)")
      ->capture_default_str();
  add_number(cmd, "--robot-radius", o.safety.robot_radius,
             "The robot's radius for contacts and clearance (particles: the seed's 0.05)", 0, 1e3)
      ->capture_default_str();
  add_number(cmd, "--reactive-horizon", o.reactive.horizon_s,
             "reactive: seconds the particles' motion is extrapolated", 1e-3, 1e3)
      ->capture_default_str();
  add_number(cmd, "--reactive-margin", o.reactive.margin, "reactive: clearance kept beyond contact",
             0, 1e3)
      ->capture_default_str();
  add_number(cmd, "--replan-every", o.replan_every, "Frames between replans", 1, 1'000'000)
      ->capture_default_str();
  add_number(cmd, "--lockstep-delay", o.lockstep_delay,
             "Lockstep: frames between a plan's launch and its use", 0, 1'000'000)
      ->capture_default_str();
  add_number(cmd, "--settle-frames", o.settle_frames,
             "Frames the fluid settles before the robot and goal are placed (default 200; "
             "dambreak 0: the column falls as the run starts)",
             0, 1'000'000);
  add_number(cmd, "--max-sim-s", o.max_sim_s, "Simulated seconds before a run counts as failed",
             1e-3, 1e9)
      ->capture_default_str();
  add_number(cmd, "--max-wall-s", o.max_wall_s,
             "Wall seconds before a run counts as failed (0: no cap)", 0, 1e9)
      ->capture_default_str();
  // The planners' own parameters, declared in the registry (hpcplan planners --world sim).
  add_param(cmd, "iterations", o.planner.iterations)->capture_default_str();
  add_param(cmd, "step", o.planner.step)->capture_default_str();
  add_param(cmd, "rewire_radius", o.planner.rewire_radius)->capture_default_str();
  add_param(cmd, "goal_radius", o.planner.goal_radius)->capture_default_str();
  add_param(cmd, "goal_bias", o.planner.goal_bias)->capture_default_str();
  add_param(cmd, "time", o.planner.time_s)->capture_default_str();
  cmd->add_option("--occupancy", a.occupancy,
                  "How particles block the grid planners' cells: particles (within 0.14 of the "
                  "centre, the seed's) | density (the SPH-interpolated density reaches "
                  "--density-threshold)")
      ->capture_default_str();
  a.density_options = {
      add_number(cmd, "--density-support", o.planner.occupancy.density_support,
                 "occupancy density: the poly6 kernel's support radius", 1e-6, 1e3)
          ->capture_default_str(),
      add_number(cmd, "--density-threshold", o.planner.occupancy.density_threshold,
                 "occupancy density: particle equivalents that block a cell (a lone particle on "
                 "the centre counts 1)",
                 1e-6, 1e9)
          ->capture_default_str()};
  add_number(cmd, "--escape", o.planner.escape_cells,
             "How far (cells of 0.2) a blocked robot or goal may move to plan", 0, 100)
      ->capture_default_str();
  add_number(cmd, "--threads", a.threads, "OpenMP threads of the fluid", 1, 4096);
  cmd->add_option("--backend", o.backend,
                  "The fluid's backend: cpu (OpenMP) | cuda (the GPU; refused with the reason "
                  "where it cannot run)")
      ->capture_default_str();
  add_number(cmd, "--memory-mb", a.memory_mb,
             "Refuse runs needing more memory (default: half the available)", 1, 1e9);
  cmd->add_option("--csv", a.csv, "Write one row per run (seed 000's columns first)");
  cmd->add_option("--replan-log", a.replan_log, "Write one row per replan");
  cmd->add_option("--trajectory", a.trajectory,
                  "Write the robot, the goal and the robot's clearance after every frame");
  cmd->add_option("--vtk", a.vtk_dir,
                  "Write VTK for ParaView: DIR/run_<n>/fluid.pvd (fluid, boxes, robot, goal, plan, "
                  "trail)");
  add_number(cmd, "--every", a.every, "With --vtk: every K-th frame (and the last)", 1, 100'000'000)
      ->capture_default_str();
  cmd->add_flag(
      "--no-timings", a.no_timings,
      "Leave timing columns empty in the CSVs (lockstep runs then compare byte for byte)");
  cmd->add_option("--output", a.output, "Also write the JSON result to this file (atomically)");
  cmd->add_option("--checkpoint", a.checkpoint,
                  "After every run, write the runs so far to this file (atomically)");
  cmd->add_option("--restart", a.restart,
                  "Keep the runs saved in this checkpoint and make the rest (same options)");
  refuse_empty_paths(cmd, {"--checkpoint", "--restart"});
}

io::SimInvocation run_sim(SimArgs& a, const RunControl& control,
                          const std::function<void(const sim::RunRecord&)>& on_run) {
  sim::SimOptions& o = a.o;
  o.scenario = sph::parse_scenario(a.scenario);
  o.pace = sim::parse_pace(a.pace);
  o.controller = sim::parse_controller(a.controller);
  o.planner.occupancy.rule = env::parse_occupancy_rule(a.occupancy);
  // An option that would be silently ignored is an error.
  if (o.planner.occupancy.rule != env::OccupancyRule::density &&
      std::any_of(a.density_options.begin(), a.density_options.end(),
                  [](const CLI::Option* opt) { return opt->count() > 0; }))
    throw InputError("--density-support and --density-threshold need --occupancy density");
  if (o.planner.occupancy.rule == env::OccupancyRule::density &&
      !plan::FluidReplanner(o.planner).plans_on_grid())
    throw InputError(
        "--occupancy applies to the grid planners (astar, astar_euclid, dstar_lite, "
        "or a map3d planner with --world occupancy), not " +
        o.planner.algo);
  sim::validate(o);
  const std::uint64_t need = sph::estimated_bytes(sim::fluid_options(o, o.seed));
  require_memory(need, o.particles, a.memory_mb, " for the fluid");
  for (const auto& [path, option] : {std::pair{a.csv, "--csv"},
                                     {a.replan_log, "--replan-log"},
                                     {a.trajectory, "--trajectory"},
                                     {a.output, "--output"}})
    if (!path.empty()) require_writable_destination(path, option);
  const int threads = a.threads > 0 ? a.threads : omp_get_max_threads();
  // A restart continues the checkpoint's simulation: the same options (--runs may grow).
  io::SimCheckpoint done;
  const std::string options = io::sim_checkpoint_options(o, !a.trajectory.empty());
  if (!a.restart.empty()) {
    done = io::read_sim_checkpoint(a.restart);
    if (done.options != options)
      throw InputError("--restart '" + a.restart +
                       "' continues a simulation with other options (give it the same options, "
                       "--trajectory or not as before; only --runs and --threads may differ)");
    if (done.result.runs.size() > static_cast<std::size_t>(o.runs))
      throw InputError("--restart '" + a.restart + "' holds " +
                       std::to_string(done.result.runs.size()) + " runs, past --runs " +
                       std::to_string(o.runs));
  }
  if (!a.checkpoint.empty()) require_writable_destination(a.checkpoint, "--checkpoint");
  require_distinct_outputs({{&a.checkpoint, "--checkpoint"},
                            {&a.csv, "--csv"},
                            {&a.replan_log, "--replan-log"},
                            {&a.trajectory, "--trajectory"},
                            {&a.output, "--output"}});
  if (!a.vtk_dir.empty()) prepare_vtk_dir(a.vtk_dir);
  if (a.threads > 0) omp_set_num_threads(a.threads);

  io::SimInvocation inv;
  inv.options = o;
  inv.threads = threads;
  std::vector<io::TrajectoryRow> trajectory = std::move(done.trajectory);
  // VTK: one series per run (DIR/run_<n>/fluid.pvd), every K-th frame and the last.
  std::unique_ptr<io::VtkSeries> vtk;
  int vtk_run = 0;
  auto write_vtk = [&](const sim::FrameView& v) {
    if (v.run != vtk_run) {
      const std::string dir = a.vtk_dir + "/run_" + std::to_string(v.run);
      prepare_vtk_dir(dir);
      vtk = std::make_unique<io::VtkSeries>(dir);
      vtk_run = v.run;
    }
    vtk->write(v.frame, v.owner->full_state(), io::vtu_robot(v.robot, v.goal, *v.plan, *v.trail));
  };
  std::function<void(const sim::FrameView&)> on_frame = [&](const sim::FrameView& v) {
    if (!a.trajectory.empty())
      trajectory.push_back({v.run, v.frame, v.fluid->time, v.robot, v.goal, v.clearance});
    if (!a.vtk_dir.empty() && (v.frame % a.every == 0 || v.last)) write_vtk(v);
  };
  int runs_made = 0;  // by this invocation
  const Stopwatch clock;
  inv.result = sim::run_simulation(
      o,
      [&](const sim::RunRecord& r, const sim::SimResult& so_far) {
        if (on_run) on_run(r);
        ++runs_made;
        if (!a.checkpoint.empty())
          write_file_atomically(a.checkpoint,
                                io::encode_sim_checkpoint({options, so_far, trajectory}));
      },
      on_frame, std::move(done.result), [&] { return control.should_stop(); });
  if (inv.result.interrupted) {
    inv.interrupted_by = control.stopped_by();
    inv.checkpoint = a.checkpoint;
    // The dropped run's rows go with it (the restart makes it again).
    std::erase_if(trajectory, [&](const io::TrajectoryRow& r) {
      return r.run > static_cast<int>(inv.result.runs.size());
    });
  }
  inv.seconds = clock.seconds();
  // The last run's checkpoint already holds every run; but a restart with no run left to make
  // has written none, and its new checkpoint must still name them all.
  if (!a.checkpoint.empty() && runs_made == 0)
    write_file_atomically(a.checkpoint,
                          io::encode_sim_checkpoint({options, inv.result, trajectory}));

  const bool timings = !a.no_timings;
  if (!a.csv.empty())
    write_file_atomically(a.csv, io::sim_runs_csv(inv.result.runs, true, timings));
  if (!a.replan_log.empty())
    write_file_atomically(a.replan_log, io::sim_replans_csv(inv.result.replans, timings));
  if (!a.trajectory.empty()) write_file_atomically(a.trajectory, io::trajectory_csv(trajectory));
  if (!a.output.empty()) write_file_atomically(a.output, io::to_json(inv).dump() + "\n");
  return inv;
}

}  // namespace hpcplan::cli
