#pragma once
// hpcplan scen's options that every front end shares (the executable; the Python module's
// hpcplan.scen.run): the scenario file, its map, the planner and the rows, read into a prepared
// run with the checks that go with them. The executable adds MPI, --json and printing
// (src/scen_command.cpp).
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "hpcplan/cli/run_control.hpp"
#include "hpcplan/env/occupancy_io.hpp"
#include "hpcplan/io/scenario_report.hpp"
#include "hpcplan/plan/scenario_run.hpp"

namespace hpcplan::cli {

struct ScenArgs {
  std::string scenario;  // .scen or .3dscen
  std::string map;       // default: the map the scenario names, beside it
  std::string algo = "astar";
  std::string heuristic = "lattice";
  std::string connectivity;  // default: the format's own
  std::string engine = "auto";
  std::string buckets;
  std::uint64_t rows = 0;
  double weight = 2.0;
  bool no_jump_points = false;
  bool keep_paths = false;
  std::string csv, output;
  GridSearchOptions options;
  const CLI::Option* weight_option = nullptr;
};

void add_scen_options(CLI::App* command, ScenArgs& args);

// The scenario and its map read, the rows chosen, the options checked (InputError for a bad
// one), --csv and --output checked writable.
struct PreparedScen {
  env::Scenario scenario;
  std::shared_ptr<const OccupancyGrid> grid;
  Connectivity connectivity = Connectivity::seed_pairs;
  std::vector<std::size_t> rows;
  std::string map_path;
  ScenarioRunInfo info;  // filled but for ranks, split and wall time
};
PreparedScen prepare_scen_run(ScenArgs& args, const RunControl& control);

// The summary and the files (--csv, --output), written atomically.
ScenarioSummary finish_scen_run(const ScenArgs& args, const PreparedScen& run,
                                const std::vector<ScenarioRowResult>& rows);

}  // namespace hpcplan::cli
