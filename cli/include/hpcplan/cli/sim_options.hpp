#pragma once
// hpcplan sim's options and run, shared by every front end (the executable, which adds --json
// and prints; the Python module's hpcplan.sim.run): registered on a CLI11 command, checked,
// run, and the requested files (CSVs, trajectory, VTK, JSON, checkpoint) written.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "hpcplan/cli/run_control.hpp"
#include "hpcplan/io/sim_report.hpp"
#include "hpcplan/sim/simulator.hpp"

namespace hpcplan::cli {

struct SimArgs {
  sim::SimOptions o;
  std::string scenario = "particles", pace = "lockstep", controller = "seed",
              occupancy = "particles";
  int threads = 0;
  std::string csv, replan_log, trajectory, output, vtk_dir, checkpoint, restart;
  std::uint64_t every = 5;
  bool no_timings = false;
  std::vector<const CLI::Option*> density_options;  // given only with --occupancy density
  double memory_mb = 0.0;
};

void add_sim_options(CLI::App* command, SimArgs& args);

// Checks the options (InputError), runs the invocation's runs (a restart's kept), writes the
// files asked for and returns the result. `control` ends it after the current frame (the run
// under way dropped, the finished ones in the checkpoint); `on_run` sees each run's record as
// it ends.
io::SimInvocation run_sim(SimArgs& args, const RunControl& control,
                          const std::function<void(const sim::RunRecord&)>& on_run = {});

}  // namespace hpcplan::cli
