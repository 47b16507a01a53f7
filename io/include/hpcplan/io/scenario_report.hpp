#pragma once
// A scenario run's outputs: the per-problem CSV (`hpcplan scen --csv`), the JSON summary
// (`--json`, `--output`) and the terminal summary.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hpcplan/plan/scenario_run.hpp"

namespace hpcplan {

// What the run was, for the summary's header.
struct ScenarioRunInfo {
  std::string scenario, map, format, algorithm, engine, connectivity;
  std::vector<int> shape;
  double weight = 1.0;
  int ranks = 1;
  std::string split = "rows";  // rows (dealt round the ranks) | search (every rank per row)
  double load_ms = 0.0;        // reading the map and the scenario
  double wall_ms = 0.0;        // the rows, start to end
  std::uint64_t file_rows = 0;
  std::string interrupted_by;  // the signal that ended the run between rows ("" if none)
};

// One line per row: row, bucket, start_x, start_y[, start_z], goal_x, ..., optimal, cost,
// status, expanded, hops, time_us, mismatch (optimal and cost with 8 decimals, as published).
std::string scenario_csv(const std::vector<ScenarioRowResult>& rows, int dims);
nlohmann::json to_json(const ScenarioRunInfo& info, const ScenarioSummary& summary);
std::string to_summary(const ScenarioRunInfo& info, const ScenarioSummary& summary);

}  // namespace hpcplan
