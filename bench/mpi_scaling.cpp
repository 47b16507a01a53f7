// Strong-scaling driver for the distributed grid search; run it under mpirun -np P.
// For one problem it times, with `--repeats` repetitions each and medians reported:
//   - the serial engine on rank 0 alone (the other ranks wait), unless --no-serial;
//   - the distributed engine for every combination of --modes, --batches and --coarsen.
// One CSV row per configuration (rank 0; appended to --csv, or stdout), with speedup against
// the serial median measured in the same run, efficiency, messages and bytes per expansion,
// workload deviation and search overhead.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "hpcplan/core/error.hpp"
#include "hpcplan/dist/grid_planner_mpi.hpp"
#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace {

using namespace hpcplan;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  mpi::Session session(argc, argv);
  const mpi::Communicator comm;
  CLI::App app{"hpcplan strong scaling: serial vs distributed medians as CSV"};
  GridProblem p;
  GridSearchOptions o;
  std::string algo = "dijkstra", label;
  std::vector<std::string> modes{"async"};
  std::vector<std::size_t> batches{512};
  std::vector<int> coarsen{0};
  int repeats = 3;
  bool no_serial = false;
  std::string csv;
  app.add_option("--dims", p.dims)->required();
  app.add_option("--extent", p.extent);
  app.add_option("--density", p.gog.density);
  app.add_option("--seed", p.gog.seed);
  app.add_option("--algo", algo);
  app.add_option("--max-states", o.max_states);
  app.add_option("--modes", modes)->delimiter(',');
  app.add_option("--batches", batches)->delimiter(',');
  app.add_option("--coarsen", coarsen)->delimiter(',');
  app.add_option("--repeats", repeats)->check(CLI::Range(1, 100));
  app.add_option("--label", label, "Free text copied into every row");
  app.add_flag("--no-serial", no_serial);
  app.add_option("--csv", csv, "Append rows to this CSV file (header when new)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return comm.rank() == 0 ? app.exit(e) : 2;
  }
  const bool root = comm.rank() == 0;
  try {
    o.algorithm = parse_grid_algorithm(algo);
    double serial_ms = 0.0;
    std::uint64_t serial_expanded = 0;
    double serial_cost = 0.0;
    if (!no_serial) {
      std::vector<double> t;
      for (int r = 0; r < repeats; ++r) {
        if (root) {
          const GridReport s = solve_grid(p, o);
          t.push_back(s.counters.time_ms);
          serial_expanded = s.counters.expanded;
          serial_cost = s.cost;
        }
        comm.quiet_barrier();  // waiting ranks sleep: spinning would slow the serial run
      }
      if (root) serial_ms = median(t);
    }
    std::ostringstream rows;
    for (const auto& mode : modes)
      for (std::size_t batch : batches)
        for (int k : coarsen) {
          dist::DistGridOptions d;
          d.scheme = dist::parse_scheme(mode);
          d.batch = batch;
          d.coarsen_shift = k;
          std::vector<double> t;
          GridReport last;
          for (int r = 0; r < repeats; ++r) {
            last = dist::solve_grid_distributed(p, o, d, comm);
            t.push_back(last.counters.time_ms);
          }
          if (!root) continue;
          if (!no_serial && std::abs(last.cost - serial_cost) > 1e-6 * (1 + serial_cost) &&
              o.algorithm != GridAlgorithm::bfs && o.algorithm != GridAlgorithm::wastar)
            throw RunError("distributed cost differs from serial");
          std::uint64_t messages = 0, bytes = 0;
          for (const auto& k2 : last.per_rank) {
            messages += k2.messages_sent;
            bytes += k2.bytes_sent;
          }
          const double med = median(t);
          const double ex = static_cast<double>(std::max<std::uint64_t>(1, last.counters.expanded));
          const double speedup = serial_ms > 0 ? serial_ms / med : 0.0;
          char line[1024];
          std::snprintf(line, sizeof line,
                        "%s,%d,%d,%d,%.2f,%s,%s,%zu,%d,%d,%s,%.6f,%llu,%llu,%.3f,%.3f,%.3f,%.3f,"
                        "%.5f,%.2f,%.3f,%.3f\n",
                        label.c_str(), comm.size(), p.dims, p.extent, p.gog.density, algo.c_str(),
                        last.scheme.c_str(), batch, k, repeats,
                        std::string(search::to_string(last.status)).c_str(), last.cost,
                        static_cast<unsigned long long>(last.counters.expanded),
                        static_cast<unsigned long long>(serial_expanded), serial_ms, med, speedup,
                        speedup / comm.size(), messages / ex, bytes / ex,
                        workload_deviation_percent(last.per_rank),
                        serial_expanded ? ex / static_cast<double>(serial_expanded) : 0.0);
          rows << line;
          std::fputs(line, stderr);
        }
    if (root) {
      const char* header =
          "label,ranks,dims,extent,density,algo,scheme,batch,coarsen,repeats,status,cost,"
          "expanded,serial_expanded,serial_median_ms,median_ms,speedup_vs_serial,efficiency,"
          "messages_per_expansion,bytes_per_expansion,workload_deviation_percent,"
          "search_overhead\n";
      if (csv.empty()) {
        std::fputs(header, stdout);
        std::fputs(rows.str().c_str(), stdout);
      } else {
        std::ifstream probe(csv);
        const bool fresh = !probe.good() || probe.peek() == std::ifstream::traits_type::eof();
        std::ofstream f(csv, std::ios::app);
        if (fresh) f << header;
        f << rows.str();
        if (!f) throw RunError("cannot write " + csv);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hpcplan_mpi_scaling: error: %s\n", e.what());
    if (comm.size() > 1) comm.abort(1);
    return 1;
  }
  return 0;
}
