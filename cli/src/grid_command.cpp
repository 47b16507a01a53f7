// `hpcplan grid`: seed-002 grid search on the GOG field, serial or over the MPI ranks.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "hpcplan/cli/grid_options.hpp"
#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/distributed/grid_planner_mpi.hpp"
#include "hpcplan/io/grid_report_json.hpp"
#include "hpcplan/io/rank_simulation_json.hpp"
#include "hpcplan/partition/rank_simulation.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan::cli {
namespace {

// The shared options (grid_options.hpp) and the executable's own: the distributed schedule
// and ownership, the rank prediction, --json.
struct GridCommandArgs {
  GridArgs grid;
  bool json = false;
  distributed::DistGridOptions dist;
  std::string mode = "async";
  std::vector<int> simulate_ranks;
  std::vector<int> simulate_shifts{0, 1};
};

}  // namespace

Action register_grid_command(CLI::App& app) {
  auto args = std::make_shared<GridCommandArgs>();
  CLI::App* cmd = app.add_subcommand("grid", "Grid BFS/A* on the GOG procedural obstacle field");
  add_grid_options(cmd, args->grid);
  add_field_option(cmd, args->grid);
  auto& d = args->dist;
  const char* mpi = "Distributed (under mpirun/srun)";
  cmd->add_option("--mode", args->mode,
                  "Distributed A*/Dijkstra schedule: async (HDA*) | bulk (seed 002 Alg. 6-7); "
                  "BFS is always level-synchronous")
      ->capture_default_str()
      ->group(mpi);
  add_number(cmd, "--owner-coarsen", d.coarsen_shift,
             "Ownership hashes each coordinate >> k, keeping 2^k-wide cells on one rank", 0, 16)
      ->capture_default_str()
      ->group(mpi);
  add_number(cmd, "--owner-slabs", d.slab_width,
             "Ownership by slabs this wide along the last axis, dealt round the ranks, instead "
             "of the hash (0 = hash)",
             0, 1 << 30)
      ->capture_default_str()
      ->group(mpi);
  add_number(cmd, "--owner-cuts", d.prefix_cuts,
             "Ownership by P - 1 cuts of the states ordered by their last two coordinates "
             "(position c_d * extent + c_(d-1)), instead of the hash; --simulate-ranks prints "
             "the positions that balance the work",
             1, 4294967295.0)
      ->delimiter(',')
      ->group(mpi);
  add_number(cmd, "--batch", d.batch, "Async: records per message", 1, 1048576)
      ->capture_default_str()
      ->group(mpi);
  add_number(cmd, "--batch-age-ms", d.batch_age_ms, "Async: longest a record waits to be sent", 0,
             1000)
      ->capture_default_str()
      ->group(mpi);
  add_number(cmd, "--sync-every", d.sync_every, "Bulk: expansions between exchanges", 1, 1e18)
      ->capture_default_str()
      ->group(mpi);
  add_number(cmd, "--sent-filter", d.sent_filter_log2,
             "log2 slots of the filter that drops re-sent duplicate states (0 = off)", 0, 28)
      ->capture_default_str()
      ->group(mpi);
  cmd->add_flag("--compare-serial", d.compare_serial,
                "Rank 0 also solves serially first and reports search overhead and speedup")
      ->group(mpi);
  add_number(cmd, "--simulate-ranks", args->simulate_ranks,
             "Predict the split over these rank counts (e.g. 2,4,...,4096) from one serial "
             "search, instead of running distributed",
             1, 1048576)
      ->delimiter(',')
      ->group(mpi);
  add_number(cmd, "--simulate-coarsen", args->simulate_shifts,
             "Ownership shifts k to predict for (0 = state hash)", 0, 16)
      ->delimiter(',')
      ->capture_default_str()
      ->group(mpi);
  cmd->add_flag("--json", args->json, "Print one JSON object instead of a summary");

  return [args](const Context& context) {
    GridArgs& a = args->grid;
    const int rank = context.comm ? context.comm->rank() : 0;
    const int ranks = context.comm ? context.comm->size() : 1;
    // Only where a checkpoint is written does a signal have somewhere to save the run; without
    // one, the signals keep their default actions.
    const RunControl control = a.options.checkpoint.empty() ? RunControl{} : signal_control();
    prepare_grid_run(a, rank, ranks, control);
    check_field_request(a);

    distributed::DistGridOptions& dist = args->dist;
    dist.scheme = distributed::parse_scheme(args->mode);
    // Fault injection for tests/mpi/test_mpi_failures.sh: HPCPLAN_FAULT_THROW=RANK:EXPANSIONS
    // makes that rank throw mid-search, HPCPLAN_FAULT_KILL=RANK:EXPANSIONS kills it.
    for (const char* name : {"HPCPLAN_FAULT_THROW", "HPCPLAN_FAULT_KILL"}) {
      const char* fault = std::getenv(name);
      if (fault == nullptr) continue;
      unsigned long long after = 0;
      int fault_rank = -1, used = 0;
      if (std::sscanf(fault, "%d:%llu%n", &fault_rank, &after, &used) != 2 || fault[used] != '\0' ||
          fault_rank < 0 || after == 0)
        throw InputError(std::string(name) + " must be RANK:EXPANSIONS (both positive), not '" +
                         fault + "'");
      dist.fault_rank = fault_rank;
      dist.fault_after = after;
      dist.fault_kill = std::string_view(name) == "HPCPLAN_FAULT_KILL";
    }
    distributed::validate(dist, a.problem.extent, ranks, a.problem.dims);
    if (a.problem.cspace) {
      if (dist.slab_width > 0 || !dist.prefix_cuts.empty())
        throw InputError(
            "--owner-slabs and --owner-cuts cut GOG and map lattices; a --world space's states "
            "are owned by their hash (--owner-coarsen k keeps 2^k-wide cells together)");
      if (!a.field_out.empty())
        throw InputError("--field-out writes a GOG or map lattice's field; not a --world space's");
      if (!args->simulate_ranks.empty())
        throw InputError(
            "--simulate-ranks predicts GOG and map lattices; run a --world space "
            "under mpirun instead");
    }

    if (!a.field_out.empty()) {
      if (!args->simulate_ranks.empty())
        throw InputError("--field-out computes a field; it takes no --simulate-ranks");
      DistanceFieldRun run = context.comm ? distributed::distance_field_distributed(
                                                a.problem, a.options, *context.comm)
                                          : distance_field(a.problem, a.options);
      if (!context.is_root()) return kExitOk;
      // A field cut short by a stop is not written: the report says so.
      if (run.field.complete) write_distance_field(a.field_out, run.field);
      const nlohmann::json field =
          field_json(run.field, a.field_out, run.field.complete, run.goal_given);
      const std::string json =
          finish_grid_run(run.report, a, control, {{"distance_field", field}}).dump() + "\n";
      if (args->json) {
        std::fputs(json.c_str(), stdout);
      } else {
        std::string text = to_summary(run.report);
        text += "  field      " +
                (run.field.complete ? a.field_out : "not written (the search was stopped)") + ": " +
                std::string(run.field.hops ? "int32 hops" : "float32 costs") + ", " +
                std::to_string(run.field.reached) + " of " + std::to_string(run.field.cells()) +
                " cells reached" + (run.goal_given ? "" : " (no --goal: start to start)") + "\n";
        std::fputs(text.c_str(), stdout);
      }
      return kExitOk;
    }
    if (!args->simulate_ranks.empty()) {
      if (ranks > 1)
        throw InputError(
            "--simulate-ranks predicts P ranks from one process; run it without "
            "mpirun (or with -np 1)");
      const partition::RankSimulation sim = partition::simulate_ranks(
          a.problem, a.options, args->simulate_ranks, args->simulate_shifts);
      nlohmann::json j = to_json(sim.serial, a.options.keep_path);
      j["rank_simulation"] = to_json(sim);
      const std::string json = j.dump() + "\n";
      if (!a.output.empty()) write_file_atomically(a.output, json);
      if (args->json)
        std::fputs(json.c_str(), stdout);
      else
        std::fputs((to_summary(sim.serial) + to_summary(sim)).c_str(), stdout);
      return kExitOk;
    }
    GridReport report = context.comm ? distributed::solve_grid_distributed(a.problem, a.options,
                                                                           dist, *context.comm)
                                     : solve_grid(a.problem, a.options);
    if (!context.is_root()) return kExitOk;
    const std::string json = finish_grid_run(report, a, control).dump() + "\n";
    std::fputs(args->json ? json.c_str() : to_summary(report).c_str(), stdout);
    return kExitOk;
  };
}

}  // namespace hpcplan::cli
