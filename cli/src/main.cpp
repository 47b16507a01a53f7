// hpcplan: one executable, one subcommand per planning setting. Started by an MPI launcher
// (mpirun, srun), it initialises MPI and the grid planner runs distributed over the ranks;
// otherwise it runs serially without touching MPI.
#include <cstdio>
#include <exception>
#include <new>
#include <optional>
#include <string>

#include "commands.hpp"
#include "hpcplan/core/error.hpp"

namespace {

int report(int code, const std::string& message) {
  std::fprintf(stderr, "hpcplan: error: %s\n", hpcplan::one_line(message).c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  std::optional<hpcplan::mpi::Session> session;
  std::optional<hpcplan::mpi::Communicator> comm;
  try {
    if (hpcplan::mpi::launched_by_mpi()) {
      session.emplace(argc, argv);
      comm.emplace();
    }
  } catch (const std::exception& e) {
    return report(hpcplan::kExitRunFailure, e.what());
  }
  const hpcplan::cli::Context context{comm ? &*comm : nullptr};
  const bool root = context.is_root();
  const bool many_ranks = comm && comm->size() > 1;

  CLI::App app{"hpcplan: HPC motion planning on implicit grids, sampling planners and fluids"};
  app.require_subcommand(1);
  hpcplan::cli::Action grid = hpcplan::cli::register_grid_command(app);
  hpcplan::cli::Action ompl = hpcplan::cli::register_ompl_command(app);
  hpcplan::cli::Action map3d = hpcplan::cli::register_map3d_command(app);
  hpcplan::cli::Action sphere2d = hpcplan::cli::register_sphere2d_command(app);
  hpcplan::cli::Action planners = hpcplan::cli::register_planners_command(app);
  hpcplan::cli::Action sph = hpcplan::cli::register_sph_command(app);
  hpcplan::cli::Action sim = hpcplan::cli::register_sim_command(app);
  hpcplan::cli::Action scen = hpcplan::cli::register_scen_command(app);
  // Bad input is detected identically on every rank before any communication, so every rank
  // returns and only rank 0 speaks.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return root ? app.exit(e) : 0;  // --help
    return root ? report(hpcplan::kExitBadInput, e.what()) : hpcplan::kExitBadInput;
  }
  // A failure during the search may hit one rank only while the others wait for it in a
  // collective: such a rank ends the whole job rather than leave them hanging.
  auto fail = [&](int code, const std::string& message) {
    if (!many_ranks) return report(code, message);
    report(code, "rank " + std::to_string(comm->rank()) + ": " + message);
    comm->abort(code);
  };
  try {
    if (app.got_subcommand("grid")) return grid(context);
    if (app.got_subcommand("ompl")) return ompl(context);
    if (app.got_subcommand("map3d")) return map3d(context);
    if (app.got_subcommand("sphere2d")) return sphere2d(context);
    if (app.got_subcommand("planners")) return planners(context);
    if (app.got_subcommand("sph")) return sph(context);
    if (app.got_subcommand("sim")) return sim(context);
    if (app.got_subcommand("scen")) return scen(context);
    return root ? report(hpcplan::kExitBadInput, "no subcommand given") : hpcplan::kExitBadInput;
  } catch (const hpcplan::InputError& e) {
    return root ? report(hpcplan::kExitBadInput, e.what()) : hpcplan::kExitBadInput;
  } catch (const hpcplan::RunError& e) {
    return fail(hpcplan::kExitRunFailure, e.what());
  } catch (const std::bad_alloc&) {
    return fail(hpcplan::kExitRunFailure,
                "out of memory; lower the problem size (--max-states, --particles, --memory-mb)");
  } catch (const std::exception& e) {
    return fail(hpcplan::kExitRunFailure, e.what());
  }
}
