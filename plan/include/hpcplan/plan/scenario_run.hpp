#pragma once
// A scenario run: every problem of a MovingAI .scen (or voxel .3dscen) file solved on its map
// by the grid planner, each answer checked against the published optimal length. What
// `hpcplan scen`, the Python module's hpcplan.scen.run, the test suite and the per-map
// benchmarks all run.
//
// A row is a mismatch when its answer breaks what the algorithm promises against the published
// optimum L (tolerance 1e-6 relative): A* and Dijkstra |cost - L| <= tol; weighted A* with
// weight w, L - tol <= cost <= w L + tol; BFS (fewest moves, not shortest length), cost >= L -
// tol; and every algorithm solves every row whose L is finite (a MovingAI row always has a
// path). A run with a mismatch is a wrong answer: the command exits 1.
//
// Threads: run_scenario_rows() uses the calling thread (the dense engine its own OpenMP team).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "hpcplan/core/status.hpp"
#include "hpcplan/env/occupancy_io.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan {

inline constexpr double kScenarioTolerance = 1e-6;

// Which rows of a file to run: buckets [first_bucket, last_bucket] (all by default), then at
// most max_rows of them (0: all), in file order.
struct ScenarioSelection {
  int first_bucket = 0;
  int last_bucket = 1 << 30;
  std::uint64_t max_rows = 0;
};
// "A-B" or "A" -> buckets; InputError on anything else.
void parse_bucket_range(const std::string& text, ScenarioSelection& selection);
// The indices (0-based among the file's problems) the selection keeps.
std::vector<std::size_t> select_rows(const env::Scenario& scenario, const ScenarioSelection& s);

struct ScenarioRowResult {
  std::size_t row = 0;  // 0-based index among the file's problems
  int bucket = 0;
  std::vector<int> start, goal;
  double optimal = 0.0;  // published
  double cost = 0.0;     // ours (0 unless solved)
  Status status = Status::no_path;
  std::uint64_t expanded = 0;
  std::uint64_t hops = 0;
  double time_us = 0.0;  // the whole call: report, search, path check
  bool mismatch = false;
  std::vector<std::vector<int>> path;  // with GridSearchOptions::keep_path
};

// InputError (one line, naming the row) unless every row of `rows` fits the grid: the map size it
// names, its coordinates' count and range, free ends, the same map name as the file's first
// row. Every rank calls it on all the rows before any is dealt out, so a bad row ends every
// rank the same way instead of one rank leaving the others in a collective.
void check_scenario_rows(const OccupancyGrid& grid, const env::Scenario& scenario,
                         const std::vector<std::size_t>& rows);

// Checks a row's answer against its published optimum (the rule above).
bool is_mismatch(const ScenarioRowResult& r, GridAlgorithm algorithm, double weight);

// The rows of the map `grid` named by `rows` (indices into scenario.rows): each a GridProblem
// on the grid with the row's start and goal, solved with `options` (the state budget derived
// once for the whole run when it is 0). `solve` runs one problem (default: solve_grid on the
// grid; the command line passes the distributed planner under mpirun). `each` sees every row
// as it finishes (progress, early exit by cancelling options.cancel's source);
// `stop_between_rows` ends the run before the next row when true (a signal's interruption).
using ScenarioSolver = std::function<GridReport(const GridProblem&, const GridSearchOptions&)>;
std::vector<ScenarioRowResult> run_scenario_rows(
    std::shared_ptr<const OccupancyGrid> grid, Connectivity connectivity,
    const env::Scenario& scenario, const std::vector<std::size_t>& rows, GridSearchOptions options,
    const ScenarioSolver& solve = {},
    const std::function<void(const ScenarioRowResult&)>& each = {},
    const std::function<bool()>& stop_between_rows = {});

// Times per bucket and the run's totals, from the rows (in any order).
struct BucketTimes {
  int bucket = 0;
  std::uint64_t rows = 0, mismatches = 0;
  double p50_us = 0, p95_us = 0, max_us = 0, mean_expanded = 0;
};
struct ScenarioSummary {
  std::uint64_t rows = 0, solved = 0, mismatches = 0;
  std::vector<std::size_t> mismatch_rows;  // file indices, ascending
  std::vector<BucketTimes> buckets;        // ascending bucket
  double total_us = 0, p50_us = 0, p95_us = 0, max_us = 0;
  std::uint64_t expanded = 0;
  double states_per_second = 0;  // expanded states over the summed query time
};
ScenarioSummary summarize(const std::vector<ScenarioRowResult>& rows);

}  // namespace hpcplan
