#include "hpcplan/cli/scen_options.hpp"

#include <filesystem>

#include "hpcplan/cli/grid_options.hpp"
#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"

namespace hpcplan::cli {

void add_scen_options(CLI::App* cmd, ScenArgs& a) {
  cmd->add_option("scenario", a.scenario,
                  "MovingAI scenario file: .scen (2D, rows: bucket map width height sx sy gx gy "
                  "optimal) or .3dscen (voxel)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--map", a.map,
                  "The map (.map, .3dmap or .npy); default: the one the scenario names, in the "
                  "scenario's folder")
      ->check(CLI::ExistingFile);
  cmd->add_option("--algo", a.algo, "astar | wastar | dijkstra | bfs")->capture_default_str();
  a.weight_option = add_param(cmd, "weight", a.weight)->capture_default_str();
  cmd->add_option("--heuristic", a.heuristic, "lattice (octile in 2D) | euclidean")
      ->capture_default_str();
  cmd->add_option("--connectivity", a.connectivity,
                  "seed | full (default: the format's own: seed for .scen, full for .3dscen)");
  add_param(cmd, "engine", a.engine)->capture_default_str();
  add_param(cmd, "threads", a.options.threads)->capture_default_str();
  add_param(cmd, "memory_budget", a.options.memory_budget)->capture_default_str();
  add_param(cmd, "max_states", a.options.max_states)->capture_default_str();
  add_param(cmd, "time_limit", a.options.time_limit_s)->capture_default_str();
  add_param(cmd, "no_jump_points", a.no_jump_points);
  cmd->add_option("--buckets", a.buckets, "Only these buckets: A-B or A");
  add_number(cmd, "--rows", a.rows, "At most this many rows (after --buckets; 0: all)");
  cmd->add_option("--csv", a.csv, "Write one CSV row per problem to this file (atomically)");
  cmd->add_option("--output", a.output, "Also write the JSON summary to this file (atomically)");
}

PreparedScen prepare_scen_run(ScenArgs& a, const RunControl& control) {
  Stopwatch load;
  GridSearchOptions& o = a.options;
  o.algorithm = parse_grid_algorithm(a.algo);
  o.heuristic = parse_heuristic(a.heuristic);
  o.engine = parse_engine(a.engine);
  if (a.weight_option != nullptr && a.weight_option->count() > 0) o.weight = a.weight;
  o.jump_points = !a.no_jump_points;
  o.keep_path = a.keep_paths;
  o.cancel = control.cancel;
  if (!a.csv.empty()) require_writable_destination(a.csv, "--csv");
  if (!a.output.empty()) require_writable_destination(a.output, "--output");
  ScenarioSelection selection;
  if (!a.buckets.empty()) parse_bucket_range(a.buckets, selection);
  selection.max_rows = a.rows;

  PreparedScen run;
  run.scenario = env::load_scenario(a.scenario);
  if (run.scenario.rows.empty()) throw InputError("scenario '" + a.scenario + "' has no problems");
  run.map_path = a.map;
  if (run.map_path.empty()) {
    const std::string named =
        run.scenario.map.empty() ? run.scenario.rows.front().map : run.scenario.map;
    const std::filesystem::path beside =
        std::filesystem::path(a.scenario).parent_path() / std::filesystem::path(named).filename();
    if (!std::filesystem::is_regular_file(beside))
      throw InputError("scenario '" + a.scenario + "' names the map '" + named +
                       "', which is not beside it; give --map FILE");
    run.map_path = beside.string();
  }
  const Connectivity fallback = run.scenario.voxel ? Connectivity::full : Connectivity::seed_pairs;
  LoadedMap m = load_map(run.map_path, std::nullopt, fallback);
  run.grid = std::move(m.grid);
  run.connectivity = a.connectivity.empty() ? m.connectivity : parse_connectivity(a.connectivity);
  run.rows = select_rows(run.scenario, selection);
  if (run.rows.empty()) throw InputError("no scenario rows in --buckets " + a.buckets);
  check_scenario_rows(*run.grid, run.scenario, run.rows);
  GridProblem probe = occupancy_problem(run.grid, run.connectivity);
  validate(probe, o);

  ScenarioRunInfo& info = run.info;
  info.scenario = std::filesystem::path(a.scenario).filename().string();
  info.map = run.grid->name;
  info.format = run.grid->format;
  info.shape = run.grid->shape();
  info.algorithm = a.algo;
  info.weight = o.algorithm == GridAlgorithm::wastar ? o.weight.value_or(2.0) : 1.0;
  info.engine = a.engine;
  info.connectivity = std::string(to_string(run.connectivity));
  info.file_rows = run.scenario.rows.size();
  info.load_ms = load.milliseconds();
  return run;
}

ScenarioSummary finish_scen_run(const ScenArgs& a, const PreparedScen& run,
                                const std::vector<ScenarioRowResult>& rows) {
  ScenarioSummary summary = summarize(rows);
  if (!a.csv.empty()) write_file_atomically(a.csv, scenario_csv(rows, run.grid->dims()));
  if (!a.output.empty()) write_file_atomically(a.output, to_json(run.info, summary).dump() + "\n");
  return summary;
}

}  // namespace hpcplan::cli
