// `hpcplan grid`: seed-002 grid search on the GOG field.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/interrupt.hpp"
#include "hpcplan/dense/dense_checkpoint.hpp"
#include "hpcplan/distributed/grid_planner_mpi.hpp"
#include "hpcplan/io/grid_report_json.hpp"
#include "hpcplan/io/rank_simulation_json.hpp"
#include "hpcplan/partition/rank_simulation.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "number_options.hpp"

namespace hpcplan::cli {
namespace {

struct GridArgs {
  GridProblem problem;
  GridSearchOptions options;
  std::string algo = "astar";
  std::string heuristic = "lattice";
  std::string connectivity = "seed";
  std::string engine = "auto";
  std::string start, goal, output;
  double weight = 2.0;
  bool json = false;
  distributed::DistGridOptions dist;
  std::string mode = "async";
  bool no_jump_points = false;
  std::vector<int> simulate_ranks;
  std::vector<int> simulate_shifts{0, 1};
};

}  // namespace

Action register_grid_command(CLI::App& app) {
  auto args = std::make_shared<GridArgs>();
  CLI::App* cmd = app.add_subcommand("grid", "Grid BFS/A* on the GOG procedural obstacle field");
  auto& p = args->problem;
  add_number(cmd, "--dims", p.dims, "Dimensions, 1..16", 1, 16)->required();
  cmd->add_option("--algo", args->algo,
                  "Planner (hpcplan planners --world grid): " + planner_names("grid"))
      ->capture_default_str();
  CLI::Option* weight = add_param(cmd, "weight", args->weight)->capture_default_str();
  cmd->add_option("--heuristic", args->heuristic, "lattice (exact free-space cost) | euclidean")
      ->capture_default_str();
  add_number(cmd, "--seed", p.gog.seed, "GOG seed")->capture_default_str();
  add_number(cmd, "--extent", p.extent, "Lattice states per axis, 2..65535", 2, 65535)
      ->capture_default_str();
  cmd->add_option("--start", args->start, "Start state c1,c2,... (default: corner 0, adjusted)");
  cmd->add_option("--goal", args->goal, "Goal state (default: corner extent-1, adjusted)");
  add_param(cmd, "max_states", args->options.max_states)->capture_default_str();
  add_param(cmd, "time_limit", args->options.time_limit_s)->capture_default_str();
  add_param(cmd, "no_jump_points", args->no_jump_points);
  add_param(cmd, "engine", args->engine)->capture_default_str();
  add_param(cmd, "threads", args->options.threads)->capture_default_str();
  add_param(cmd, "memory_budget", args->options.memory_budget)->capture_default_str();
  add_param(cmd, "slab_layers", args->options.slab_layers)->capture_default_str();
  add_param(cmd, "contiguous_slabs", args->options.contiguous_slabs);
  cmd->add_option("--connectivity", args->connectivity, "seed (1 or 2 axes) | full (d <= 4)")
      ->capture_default_str();
  add_number(cmd, "--threshold", p.gog.threshold, "GOG threshold c_v (0 = from --density)", 0, 49)
      ->capture_default_str();
  add_number(cmd, "--density", p.gog.density,
             "Blocked fraction aimed at by the automatic threshold", 0, 1)
      ->capture_default_str();
  add_number(cmd, "--gog-shift-p", p.gog.shift_p, "GOG b_p", 0, 63)->capture_default_str();
  add_number(cmd, "--gog-shift-v", p.gog.shift_v, "GOG b_v", 0, 61)->capture_default_str();
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
  const char* ckpt = "Checkpoints (dense engine: --algo bfs or dijkstra)";
  cmd->add_option("--checkpoint", args->options.checkpoint,
                  "Write the search's state to FILE (FILE.r<rank> per rank under mpirun) at a "
                  "level or bucket boundary: every --checkpoint-every seconds, and on SIGUSR1, "
                  "SIGTERM or Ctrl-C, which then end the run (status interrupted, exit 0)")
      ->group(ckpt);
  add_number(cmd, "--checkpoint-every", args->options.checkpoint_every_s,
             "Seconds between checkpoints (0: only when interrupted)", 0, 1e9)
      ->capture_default_str()
      ->group(ckpt);
  cmd->add_option("--restart", args->options.restart,
                  "Continue from the checkpoint FILE of the same problem, ranks and threads")
      ->group(ckpt);
  cmd->add_flag("--path", args->options.keep_path, "Include the path");
  cmd->add_flag("--json", args->json, "Print one JSON object instead of a summary");
  cmd->add_option("--output", args->output, "Also write the JSON result to this file (atomically)");

  return [args, weight](const Context& context) {
    GridArgs& a = *args;
    a.options.algorithm = parse_grid_algorithm(a.algo);
    a.options.heuristic = parse_heuristic(a.heuristic);
    a.problem.connectivity = parse_connectivity(a.connectivity);
    a.options.engine = parse_engine(a.engine);
    if (weight->count() > 0) a.options.weight = a.weight;
    a.options.jump_points = !a.no_jump_points;
    if (!a.start.empty()) a.problem.start = parse_coordinates(a.start, "--start");
    if (!a.goal.empty()) a.problem.goal = parse_coordinates(a.goal, "--goal");

    a.dist.scheme = distributed::parse_scheme(a.mode);
    // Fault injection for tests/mpi/test_mpi_failures.sh: HPCPLAN_FAULT_THROW=RANK:EXPANSIONS
    // makes that rank throw mid-search, HPCPLAN_FAULT_KILL=RANK:EXPANSIONS kills it.
    for (const char* name : {"HPCPLAN_FAULT_THROW", "HPCPLAN_FAULT_KILL"}) {
      const char* fault = std::getenv(name);
      if (fault == nullptr) continue;
      unsigned long long after = 0;
      int rank = -1, used = 0;
      if (std::sscanf(fault, "%d:%llu%n", &rank, &after, &used) != 2 || fault[used] != '\0' ||
          rank < 0 || after == 0)
        throw InputError(std::string(name) + " must be RANK:EXPANSIONS (both positive), not '" +
                         fault + "'");
      a.dist.fault_rank = rank;
      a.dist.fault_after = after;
      a.dist.fault_kill = std::string_view(name) == "HPCPLAN_FAULT_KILL";
    }
    distributed::validate(a.dist, a.problem.extent, context.comm ? context.comm->size() : 1,
                          a.problem.dims);
    if (!a.output.empty()) require_writable_destination(a.output, "--output");
    const int rank = context.comm ? context.comm->rank() : 0;
    const int ranks = context.comm ? context.comm->size() : 1;
    if (!a.options.checkpoint.empty()) {
      require_writable_destination(dense::rank_file(a.options.checkpoint, rank, ranks),
                                   "--checkpoint");
      // Only where a checkpoint is written does a signal have somewhere to save the run.
      interrupt::install();
      a.options.interrupted = [] { return interrupt::requested() != 0; };
    }

    if (!a.simulate_ranks.empty()) {
      if (context.comm && context.comm->size() > 1)
        throw InputError(
            "--simulate-ranks predicts P ranks from one process; run it without "
            "mpirun (or with -np 1)");
      const partition::RankSimulation sim =
          partition::simulate_ranks(a.problem, a.options, a.simulate_ranks, a.simulate_shifts);
      nlohmann::json j = to_json(sim.serial, a.options.keep_path);
      j["rank_simulation"] = to_json(sim);
      const std::string json = j.dump() + "\n";
      if (!a.output.empty()) write_file_atomically(a.output, json);
      if (a.json)
        std::fputs(json.c_str(), stdout);
      else
        std::fputs((to_summary(sim.serial) + to_summary(sim)).c_str(), stdout);
      return kExitOk;
    }
    GridReport report = context.comm ? distributed::solve_grid_distributed(a.problem, a.options,
                                                                           a.dist, *context.comm)
                                     : solve_grid(a.problem, a.options);
    if (!context.is_root()) return kExitOk;
    report.restarted_from = a.options.restart;
    if (report.result.status == Status::interrupted) {
      report.interrupted_by = interrupt::name(interrupt::requested());
      report.checkpoint = a.options.checkpoint;
    }
    const std::string json = to_json(report, a.options.keep_path).dump() + "\n";
    if (!a.output.empty()) write_file_atomically(a.output, json);
    if (a.json)
      std::fputs(json.c_str(), stdout);
    else
      std::fputs(to_summary(report).c_str(), stdout);
    return kExitOk;
  };
}

}  // namespace hpcplan::cli
