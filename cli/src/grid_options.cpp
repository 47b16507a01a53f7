#include "hpcplan/cli/grid_options.hpp"

#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/dense/dense_checkpoint.hpp"
#include "hpcplan/io/grid_report_json.hpp"

namespace hpcplan::cli {

void add_grid_options(CLI::App* cmd, GridArgs& a) {
  auto& p = a.problem;
  add_number(cmd, "--dims", p.dims, "Dimensions, 1..16", 1, 16)->required();
  cmd->add_option("--algo", a.algo,
                  "Planner (hpcplan planners --world grid): " + planner_names("grid"))
      ->capture_default_str();
  a.weight_option = add_param(cmd, "weight", a.weight)->capture_default_str();
  cmd->add_option("--heuristic", a.heuristic, "lattice (exact free-space cost) | euclidean")
      ->capture_default_str();
  add_number(cmd, "--seed", p.gog.seed, "GOG seed")->capture_default_str();
  add_number(cmd, "--extent", p.extent, "Lattice states per axis, 2..65535", 2, 65535)
      ->capture_default_str();
  cmd->add_option("--start", a.start, "Start state c1,c2,... (default: corner 0, adjusted)");
  cmd->add_option("--goal", a.goal, "Goal state (default: corner extent-1, adjusted)");
  add_param(cmd, "max_states", a.options.max_states)->capture_default_str();
  add_param(cmd, "time_limit", a.options.time_limit_s)->capture_default_str();
  add_param(cmd, "no_jump_points", a.no_jump_points);
  add_param(cmd, "engine", a.engine)->capture_default_str();
  add_param(cmd, "threads", a.options.threads)->capture_default_str();
  add_param(cmd, "memory_budget", a.options.memory_budget)->capture_default_str();
  add_param(cmd, "slab_layers", a.options.slab_layers)->capture_default_str();
  add_param(cmd, "contiguous_slabs", a.options.contiguous_slabs);
  cmd->add_option("--connectivity", a.connectivity, "seed (1 or 2 axes) | full (d <= 4)")
      ->capture_default_str();
  add_number(cmd, "--threshold", p.gog.threshold, "GOG threshold c_v (0 = from --density)", 0, 49)
      ->capture_default_str();
  add_number(cmd, "--density", p.gog.density,
             "Blocked fraction aimed at by the automatic threshold", 0, 1)
      ->capture_default_str();
  add_number(cmd, "--gog-shift-p", p.gog.shift_p, "GOG b_p", 0, 63)->capture_default_str();
  add_number(cmd, "--gog-shift-v", p.gog.shift_v, "GOG b_v", 0, 61)->capture_default_str();
  const char* ckpt = "Checkpoints (dense engine: --algo bfs or dijkstra)";
  cmd->add_option("--checkpoint", a.options.checkpoint,
                  "Write the search's state to FILE (FILE.r<rank> per rank under mpirun) at a "
                  "level or bucket boundary: every --checkpoint-every seconds, and on SIGUSR1, "
                  "SIGTERM or Ctrl-C, which then end the run (status interrupted, exit 0)")
      ->group(ckpt);
  add_number(cmd, "--checkpoint-every", a.options.checkpoint_every_s,
             "Seconds between checkpoints (0: only when interrupted)", 0, 1e9)
      ->capture_default_str()
      ->group(ckpt);
  cmd->add_option("--restart", a.options.restart,
                  "Continue from the checkpoint FILE of the same problem, ranks and threads")
      ->group(ckpt);
  cmd->add_flag("--path", a.options.keep_path, "Include the path");
  cmd->add_option("--output", a.output, "Also write the JSON result to this file (atomically)");
}

void prepare_grid_run(GridArgs& a, int rank, int ranks, const RunControl& control) {
  a.options.algorithm = parse_grid_algorithm(a.algo);
  a.options.heuristic = parse_heuristic(a.heuristic);
  a.problem.connectivity = parse_connectivity(a.connectivity);
  a.options.engine = parse_engine(a.engine);
  if (a.weight_option != nullptr && a.weight_option->count() > 0) a.options.weight = a.weight;
  a.options.jump_points = !a.no_jump_points;
  if (!a.start.empty()) a.problem.start = parse_coordinates(a.start, "--start");
  if (!a.goal.empty()) a.problem.goal = parse_coordinates(a.goal, "--goal");
  if (!a.output.empty()) require_writable_destination(a.output, "--output");
  a.options.cancel = control.cancel;
  if (!a.options.checkpoint.empty()) {
    require_writable_destination(dense::rank_file(a.options.checkpoint, rank, ranks),
                                 "--checkpoint");
    a.options.interrupted = [control] { return control.interrupted(); };
  }
}

nlohmann::json finish_grid_run(GridReport& report, const GridArgs& a, const RunControl& control) {
  report.restarted_from = a.options.restart;
  if (report.result.status == Status::interrupted) {
    report.interrupted_by = control.stopped_by();
    report.checkpoint = a.options.checkpoint;
  }
  nlohmann::json json = to_json(report, a.options.keep_path);
  if (!a.output.empty()) write_file_atomically(a.output, json.dump() + "\n");
  return json;
}

}  // namespace hpcplan::cli
