// `hpcplan sim`: seed 000's experiment: a robot replanning through the live fluid. Per-run and
// per-replan CSV, the robot's trajectory, one JSON summary per invocation, or a readable table.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "hpcplan/cli/sim_options.hpp"
#include "hpcplan/core/error.hpp"

namespace hpcplan::cli {

Action register_sim_command(CLI::App& app) {
  struct Args {
    SimArgs sim;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("sim", "Replan through the live fluid (seed 000's simulator)");
  add_sim_options(cmd, args->sim);
  cmd->add_flag("--json", args->json, "Print the result as one JSON object");
  return [args](const Context& context) {
    if (context.comm && context.comm->size() > 1)
      throw InputError(
          "hpcplan sim runs in one process (a frame loop and a planner thread); "
          "start it without mpirun");
    // SLURM's warning signal (or SIGTERM, Ctrl-C) ends the invocation after the current frame:
    // the run under way is dropped, the finished ones are in the checkpoint (core/interrupt.hpp).
    const int runs = args->sim.o.runs;
    const io::SimInvocation inv =
        run_sim(args->sim, signal_control(), [runs](const sim::RunRecord& r) {
          if (runs > 1)
            std::fprintf(stderr, "run %d/%d: %s after %.1f s simulated (%.1f s wall)\n",
                         r.run_number, runs, std::string(sim::to_string(r.end)).c_str(),
                         r.sim_time_s, r.wall_time_s);
        });
    std::fputs(args->json ? (io::to_json(inv).dump() + "\n").c_str() : io::to_summary(inv).c_str(),
               stdout);
    return kExitOk;
  };
}

}  // namespace hpcplan::cli
