#pragma once
#include <CLI/CLI.hpp>
#include <functional>

#include "hpcplan/mpi/communicator.hpp"

namespace hpcplan::cli {

// What every subcommand may use at run time: the MPI communicator when the process was
// started by an MPI launcher, null for a plain serial run.
struct Context {
  const mpi::Communicator* comm = nullptr;
  bool is_root() const { return comm == nullptr || comm->rank() == 0; }
};

// Each subcommand registers its options on `app` and returns the action that runs it; the
// action returns the process exit code and may throw InputError / RunError.
using Action = std::function<int(const Context&)>;
Action register_grid_command(CLI::App& app);
Action register_ompl_command(CLI::App& app);
Action register_map3d_command(CLI::App& app);
Action register_sphere2d_command(CLI::App& app);
Action register_planners_command(CLI::App& app);
Action register_sph_command(CLI::App& app);
Action register_sim_command(CLI::App& app);
Action register_scen_command(CLI::App& app);

}  // namespace hpcplan::cli
