// `hpcplan grid`: seed-002 grid search on the GOG field.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/dist/grid_planner_mpi.hpp"
#include "hpcplan/io/atomic_file.hpp"
#include "hpcplan/io/grid_report_json.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan::cli {
namespace {

struct GridArgs {
  GridProblem problem;
  GridSearchOptions options;
  std::string algo = "astar";
  std::string heuristic = "lattice";
  std::string connectivity = "seed";
  std::string start, goal, output;
  double weight = 2.0;
  bool json = false;
  dist::DistGridOptions dist;
  std::string mode = "async";
};

}  // namespace

Action register_grid_command(CLI::App& app) {
  auto args = std::make_shared<GridArgs>();
  CLI::App* cmd = app.add_subcommand("grid", "Grid BFS/A* on the GOG procedural obstacle field");
  auto& p = args->problem;
  cmd->add_option("--dims", p.dims, "Dimensions, 1..16")->required();
  cmd->add_option("--algo", args->algo, "astar | wastar | dijkstra | bfs")->capture_default_str();
  CLI::Option* weight =
      cmd->add_option("--weight", args->weight, "Weighted A* weight w >= 1 (f = g + w h)")
          ->capture_default_str();
  cmd->add_option("--heuristic", args->heuristic, "lattice (exact free-space cost) | euclidean")
      ->capture_default_str();
  cmd->add_option("--seed", p.gog.seed, "GOG seed")->capture_default_str();
  cmd->add_option("--extent", p.extent, "Lattice states per axis, 2..65535")->capture_default_str();
  cmd->add_option("--start", args->start, "Start state c1,c2,... (default: corner 0, adjusted)");
  cmd->add_option("--goal", args->goal, "Goal state (default: corner extent-1, adjusted)");
  cmd->add_option("--max-states", args->options.max_states,
                  "Stored-state budget (0 = half of available memory)")
      ->capture_default_str();
  cmd->add_option("--time-limit", args->options.time_limit_s, "Seconds (0 = none)")
      ->capture_default_str();
  cmd->add_option("--connectivity", args->connectivity, "seed (1 or 2 axes) | full (d <= 4)")
      ->capture_default_str();
  cmd->add_option("--threshold", p.gog.threshold, "GOG threshold c_v (0 = from --density)")
      ->capture_default_str();
  cmd->add_option("--density", p.gog.density,
                  "Blocked fraction aimed at by the automatic threshold")
      ->capture_default_str();
  cmd->add_option("--gog-shift-p", p.gog.shift_p, "GOG b_p")->capture_default_str();
  cmd->add_option("--gog-shift-v", p.gog.shift_v, "GOG b_v")->capture_default_str();
  auto& d = args->dist;
  const char* mpi = "Distributed (under mpirun/srun)";
  cmd->add_option("--mode", args->mode,
                  "Distributed A*/Dijkstra schedule: async (HDA*) | bulk (seed 002 Alg. 6-7); "
                  "BFS is always level-synchronous")
      ->capture_default_str()
      ->group(mpi);
  cmd->add_option("--owner-coarsen", d.coarsen_shift,
                  "Ownership hashes each coordinate >> k, keeping 2^k-wide cells on one rank")
      ->capture_default_str()
      ->group(mpi);
  cmd->add_option("--batch", d.batch, "Async: records per message")
      ->capture_default_str()
      ->group(mpi);
  cmd->add_option("--batch-age-ms", d.batch_age_ms, "Async: longest a record waits to be sent")
      ->capture_default_str()
      ->group(mpi);
  cmd->add_option("--sync-every", d.sync_every, "Bulk: expansions between exchanges")
      ->capture_default_str()
      ->group(mpi);
  cmd->add_option("--sent-filter", d.sent_filter_log2,
                  "log2 slots of the filter that drops re-sent duplicate states (0 = off)")
      ->capture_default_str()
      ->group(mpi);
  cmd->add_flag("--compare-serial", d.compare_serial,
                "Rank 0 also solves serially first and reports search overhead and speedup")
      ->group(mpi);
  cmd->add_flag("--path", args->options.keep_path, "Include the path");
  cmd->add_flag("--json", args->json, "Print one JSON object instead of a summary");
  cmd->add_option("--output", args->output, "Also write the JSON result to this file (atomically)");

  return [args, weight](const Context& context) {
    GridArgs& a = *args;
    a.options.algorithm = parse_grid_algorithm(a.algo);
    a.options.heuristic = parse_heuristic(a.heuristic);
    a.problem.connectivity = parse_connectivity(a.connectivity);
    if (weight->count() > 0) a.options.weight = a.weight;
    if (!a.start.empty()) a.problem.start = parse_coordinates(a.start, "--start");
    if (!a.goal.empty()) a.problem.goal = parse_coordinates(a.goal, "--goal");

    a.dist.scheme = dist::parse_scheme(a.mode);
    dist::validate(a.dist);

    const GridReport report =
        context.comm ? dist::solve_grid_distributed(a.problem, a.options, a.dist, *context.comm)
                     : solve_grid(a.problem, a.options);
    if (!context.is_root()) return kExitOk;
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
