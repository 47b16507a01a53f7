// Sweep driver: runs `hpcplan grid` problems over dimensions, algorithms and heuristics,
// repeats each, and writes one CSV row per configuration with medians (written atomically).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace {

using namespace hpcplan;

template <class T>
T median(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hpcplan grid sweep: medians of repeated runs as CSV"};
  std::vector<int> dims{2, 4, 6, 8, 10};
  std::vector<std::string> algos{"astar"}, heuristics{"lattice"};
  int repeats = 5;
  double density = 0.40;
  std::uint64_t max_states = 0, seed = 1;
  std::string csv;
  app.add_option("--dims", dims)->delimiter(',');
  app.add_option("--algos", algos)->delimiter(',');
  app.add_option("--heuristics", heuristics)->delimiter(',');
  app.add_option("--repeats", repeats)->check(CLI::Range(1, 1000));
  app.add_option("--density", density);
  app.add_option("--seed", seed);
  app.add_option("--max-states", max_states);
  app.add_option("--csv", csv, "CSV output file (stdout if omitted)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  std::ostringstream out;
  out << "dims,algo,heuristic,density,seed,repeats,status,cost,quality,expanded,generated,"
         "collision_checks,peak_states,median_time_ms,min_time_ms,generated_per_s\n";
  try {
    for (int d : dims)
      for (const auto& a : algos)
        for (const auto& h : heuristics) {
          GridProblem p;
          p.dims = d;
          p.gog.density = density;
          p.gog.seed = seed;
          GridSearchOptions o;
          o.algorithm = parse_grid_algorithm(a);
          o.heuristic = parse_heuristic(h);
          o.max_states = max_states;
          std::vector<double> times;
          GridReport r;
          for (int i = 0; i < repeats; ++i) {
            r = solve_grid(p, o);
            times.push_back(r.result.counters.time_ms);
          }
          const double med = median(times);
          char row[512];
          std::snprintf(row, sizeof row,
                        "%d,%s,%s,%.3f,%llu,%d,%s,%.6f,%.6f,%llu,%llu,%llu,%llu,%.4f,%.4f,%.0f\n",
                        d, a.c_str(), r.options.heuristic.c_str(), density,
                        static_cast<unsigned long long>(seed), repeats,
                        std::string(search::to_string(r.result.status)).c_str(), r.result.cost,
                        r.result.quality,
                        static_cast<unsigned long long>(r.result.counters.expanded),
                        static_cast<unsigned long long>(r.result.counters.generated),
                        static_cast<unsigned long long>(r.result.counters.collision_checks),
                        static_cast<unsigned long long>(r.result.counters.peak_states), med,
                        *std::min_element(times.begin(), times.end()),
                        r.result.counters.generated / (med / 1e3));
          out << row;
          std::fputs(row, stderr);
        }
    if (csv.empty())
      std::fputs(out.str().c_str(), stdout);
    else
      write_file_atomically(csv, out.str());
  } catch (const InputError& e) {
    std::fprintf(stderr, "hpcplan_grid_sweep: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hpcplan_grid_sweep: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
