#include "hpcplan/plan/scenario_run.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/memory.hpp"
#include "hpcplan/core/stopwatch.hpp"

namespace hpcplan {
namespace {

int parse_bucket(std::string_view text, const std::string& whole) {
  int v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || ptr != text.data() + text.size() || v < 0)
    throw InputError("--buckets must be A-B or A (bucket numbers >= 0), not '" + whole + "'");
  return v;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  // Nearest rank: the smallest value with at least q of the values at or below it.
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, k == 0 ? 0 : k - 1)];
}

}  // namespace

void parse_bucket_range(const std::string& text, ScenarioSelection& s) {
  const std::size_t dash = text.find('-');
  if (dash == std::string::npos) {
    s.first_bucket = s.last_bucket = parse_bucket(text, text);
    return;
  }
  s.first_bucket = parse_bucket(std::string_view(text).substr(0, dash), text);
  s.last_bucket = parse_bucket(std::string_view(text).substr(dash + 1), text);
  if (s.last_bucket < s.first_bucket)
    throw InputError("--buckets " + text + " is empty (the first bucket is above the last)");
}

std::vector<std::size_t> select_rows(const env::Scenario& scenario, const ScenarioSelection& s) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < scenario.rows.size(); ++i) {
    const int b = scenario.rows[i].bucket;
    if (b < s.first_bucket || b > s.last_bucket) continue;
    if (s.max_rows != 0 && rows.size() >= s.max_rows) break;
    rows.push_back(i);
  }
  return rows;
}

void check_scenario_rows(const OccupancyGrid& grid, const env::Scenario& scenario,
                         const std::vector<std::size_t>& rows) {
  auto size_text = [](const std::vector<int>& sides) {
    std::string t;
    for (std::size_t a = 0; a < sides.size(); ++a)
      t.append(a ? " x " : "").append(std::to_string(sides[a]));
    return t;
  };
  const std::string& first_map = scenario.rows.empty() ? std::string() : scenario.rows[0].map;
  for (std::size_t i : rows) {
    const env::ScenarioRow& row = scenario.rows.at(i);
    const std::string where = "scenario row " + std::to_string(i) + ": ";
    if (!scenario.voxel && row.map != first_map)
      throw InputError(where + "names the map '" + row.map + "', not '" + first_map +
                       "' as the file's first row does; run each map's rows on their own");
    if (!row.map_size.empty() && row.map_size != grid.shape())
      throw InputError(where + "is for a " + size_text(row.map_size) + " map; the map '" +
                       grid.name + "' is " + size_text(grid.shape()));
    for (const auto* end : {&row.start, &row.goal}) {
      const char* what = end == &row.start ? "start" : "goal";
      if (end->size() != static_cast<std::size_t>(grid.dims()))
        throw InputError(where + "has " + std::to_string(end->size()) + " coordinates; the map '" +
                         grid.name + "' has " + std::to_string(grid.dims()) + " dimensions");
      if (!grid.inside(*end))
        throw InputError(where + "its " + what + " is outside the map '" + grid.name + "' (" +
                         size_text(grid.shape()) + ")");
      if (!grid.is_free(*end))
        throw InputError(where + "its " + what + " is blocked on the map '" + grid.name +
                         "': is this the map the scenario was made for?");
    }
  }
}

bool is_mismatch(const ScenarioRowResult& r, GridAlgorithm algorithm, double weight) {
  if (r.status != Status::solved) return true;
  const double tol = kScenarioTolerance * std::max(1.0, r.optimal);
  switch (algorithm) {
    case GridAlgorithm::astar:
    case GridAlgorithm::dijkstra:
      return std::abs(r.cost - r.optimal) > tol;
    case GridAlgorithm::wastar:
      return r.cost < r.optimal - tol || r.cost > weight * r.optimal + tol;
    case GridAlgorithm::bfs:
      return r.cost < r.optimal - tol;
  }
  return true;
}

std::vector<ScenarioRowResult> run_scenario_rows(
    std::shared_ptr<const OccupancyGrid> grid, Connectivity connectivity,
    const env::Scenario& scenario, const std::vector<std::size_t>& rows, GridSearchOptions options,
    const ScenarioSolver& solve, const std::function<void(const ScenarioRowResult&)>& each,
    const std::function<bool()>& stop_between_rows) {
  check_scenario_rows(*grid, scenario, rows);
  // The budget once for the run (reading the kernel's memory figure per query would cost more
  // than many of the searches).
  if (options.max_states == 0) {
    const std::uint64_t avail = available_memory_bytes();
    options.max_states = avail ? avail / 2 / bytes_per_state(1) : 100'000'000;
  }
  const double weight =
      options.algorithm == GridAlgorithm::wastar ? options.weight.value_or(2.0) : 1.0;
  GridProblem problem = occupancy_problem(grid, connectivity);
  std::vector<ScenarioRowResult> out;
  out.reserve(rows.size());
  for (std::size_t i : rows) {
    const env::ScenarioRow& row = scenario.rows[i];
    problem.start = row.start;
    problem.goal = row.goal;
    ScenarioRowResult r;
    r.row = i;
    r.bucket = row.bucket;
    r.start = row.start;
    r.goal = row.goal;
    r.optimal = row.optimal;
    try {
      Stopwatch clock;
      GridReport report = solve ? solve(problem, options) : solve_grid(*grid, problem, options);
      r.time_us = clock.milliseconds() * 1000.0;
      r.status = report.result.status;
      r.cost = r.status == Status::solved ? report.result.cost : 0.0;
      r.hops = report.result.hops;
      r.expanded = report.result.counters.expanded;
      r.path = std::move(report.result.path);
    } catch (const InputError& e) {
      // A published problem whose end is blocked or outside the map: the map is not the one
      // the scenario was made for.
      throw InputError("scenario row " + std::to_string(i) + ": " + e.what());
    }
    r.mismatch = is_mismatch(r, options.algorithm, weight);
    if (each) each(r);
    out.push_back(std::move(r));
    if (options.cancel.stop_requested() || (stop_between_rows && stop_between_rows())) break;
  }
  return out;
}

ScenarioSummary summarize(const std::vector<ScenarioRowResult>& rows) {
  ScenarioSummary s;
  std::map<int, std::vector<const ScenarioRowResult*>> by_bucket;
  std::vector<double> all;
  for (const ScenarioRowResult& r : rows) {
    ++s.rows;
    s.solved += r.status == Status::solved;
    if (r.mismatch) s.mismatch_rows.push_back(r.row);
    s.total_us += r.time_us;
    s.expanded += r.expanded;
    all.push_back(r.time_us);
    by_bucket[r.bucket].push_back(&r);
  }
  std::sort(s.mismatch_rows.begin(), s.mismatch_rows.end());
  s.mismatches = s.mismatch_rows.size();
  s.p50_us = quantile(all, 0.50);
  s.p95_us = quantile(all, 0.95);
  s.max_us = all.empty() ? 0.0 : *std::max_element(all.begin(), all.end());
  s.states_per_second = s.total_us > 0 ? static_cast<double>(s.expanded) / (s.total_us * 1e-6) : 0;
  for (const auto& [bucket, members] : by_bucket) {
    BucketTimes b;
    b.bucket = bucket;
    std::vector<double> t;
    double expanded = 0;
    for (const ScenarioRowResult* r : members) {
      ++b.rows;
      b.mismatches += r->mismatch;
      t.push_back(r->time_us);
      expanded += static_cast<double>(r->expanded);
    }
    b.p50_us = quantile(t, 0.50);
    b.p95_us = quantile(t, 0.95);
    b.max_us = *std::max_element(t.begin(), t.end());
    b.mean_expanded = expanded / static_cast<double>(b.rows);
    s.buckets.push_back(b);
  }
  return s;
}

}  // namespace hpcplan
