// Strong-scaling driver for the distributed grid search; run it under mpirun -np P. With
// --engine sparse (the default) it sweeps the best-first engine's schedules and ownerships;
// with --engine dense it times the dense engine's slabs (one configuration) the same way.
// For one problem it times, in `--repeats` rounds, each round
//   - the serial engine on rank 0 alone (the other ranks sleep in a barrier), unless
//     --no-serial, then
//   - the distributed engine once for every combination of --modes, --batches, --slabs,
//     --coarsen and --sent-filters (a slab ownership, width > 0, runs with no coarsening),
//     and with --balanced-cuts once more per mode, batch and filter with prefix cuts placed
//     where a serial run's expansions split evenly (found before the rounds, on rank 0, by the
//     rank simulation's census: calibration, not counted in any time), and once with the
//     prefix cuts of --cuts; given only cuts (no --slabs, no --coarsen), no hash runs;
//   - with --ceiling, the serial search on every rank at once (scheme "ceiling": the speedup
//     the machine itself allows P copies of this memory-bound work).
// Interleaving matters on a noisy machine: the speed of a shared VM drifts by 10-25% over a
// minute, so each round's serial run is the reference for that round's distributed runs, and
// the reported speedup is the median of the per-round ratios (medians of the times are
// reported too). Rounds alternate which side runs first, since the second finds warm memory. One
// CSV row per configuration (rank 0; appended to --csv, or stdout).
// The spread: the lowest and highest per-round speedups. With --ceiling, each round also
// yields the ceiling of that round and the distributed speedup as a fraction of it; the row
// reports that fraction's median, quartiles, lowest and highest, so a drifting machine shows
// as spread instead of moving the median unseen. That fraction is the crowded time over P
// times the distributed time (the solo serial run cancels out), so the crowded run sits next
// to the distributed ones: last in rounds that start with the serial run, first in the others.
// serial_min_ms and serial_max_ms show how far the machine's own speed moved within the job.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/progress.hpp"
#include "hpcplan/distributed/grid_planner_mpi.hpp"
#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/partition/rank_simulation.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace {

using namespace hpcplan;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
double lowest(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
}
double highest(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}
// The q-quantile by the nearest rank (q = 0.25, 0.75: the quartiles).
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(std::lround(q * static_cast<double>(v.size() - 1)));
  return v[i];
}

}  // namespace

int main(int argc, char** argv) {
  mpi::Session session(argc, argv);
  const mpi::Communicator comm;
  CLI::App app{"hpcplan strong scaling: serial vs distributed medians as CSV"};
  GridProblem p;
  GridSearchOptions o;
  // The ranks expand every lattice state; so does the serial reference (no 2D jump points),
  // as with `hpcplan grid --compare-serial`.
  o.jump_points = false;
  std::string algo = "dijkstra", label;
  std::vector<std::string> modes{"async"};
  std::vector<std::size_t> batches{512};
  std::vector<int> coarsen{0};
  std::vector<int> slabs{0};
  std::vector<int> filters{distributed::DistGridOptions{}.sent_filter_log2};
  int repeats = 3;
  bool no_serial = false;
  bool ceiling = false;
  bool balanced_cuts = false;
  std::vector<std::uint32_t> fixed_cuts;
  std::string csv;
  std::string engine = "sparse";
  app.add_option("--engine", engine,
                 "sparse: the best-first engine, swept over --modes and ownerships; dense: the "
                 "bit-parallel engine's slabs (one configuration; --threads per rank)")
      ->check(CLI::IsMember({"sparse", "dense"}));
  app.add_option("--threads", o.threads, "Dense engine: OpenMP threads per rank (default 1)");
  app.add_option("--dims", p.dims)->required();
  app.add_option("--extent", p.extent);
  app.add_option("--density", p.gog.density);
  app.add_option("--seed", p.gog.seed);
  app.add_option("--algo", algo);
  app.add_option("--max-states", o.max_states);
  app.add_option("--modes", modes)->delimiter(',');
  app.add_option("--batches", batches)->delimiter(',');
  app.add_option("--coarsen", coarsen)->delimiter(',');
  app.add_option("--slabs", slabs,
                 "Slab widths along the last axis (0 = hash ownership); each runs with "
                 "coarsening 0")
      ->delimiter(',');
  app.add_option("--sent-filters", filters, "log2 slots of the sent-duplicate filter")
      ->delimiter(',');
  app.add_option("--repeats", repeats)->check(CLI::Range(1, 100));
  app.add_option("--label", label, "Free text copied into every row");
  app.add_flag("--no-serial", no_serial);
  app.add_flag("--ceiling", ceiling,
               "Also time the serial search on every rank at once (the machine's ceiling)");
  app.add_flag("--balanced-cuts", balanced_cuts,
               "Also run prefix-cut ownership balanced on a serial run's expansions (calibration "
               "before the rounds, untimed)");
  app.add_option(
         "--cuts", fixed_cuts,
         "Also run prefix-cut ownership with these P - 1 positions (c_d * extent + c_(d-1))")
      ->delimiter(',');
  app.add_option("--csv", csv, "Append rows to this CSV file (header when new)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return comm.rank() == 0 ? app.exit(e) : 2;
  }
  const bool root = comm.rank() == 0;
  try {
    o.algorithm = parse_grid_algorithm(algo);
    o.engine = engine == "dense" ? GridEngine::dense : GridEngine::sparse;
    if (o.engine == GridEngine::dense && o.threads == 0) o.threads = 1;
    // The ownerships to time: each slab width with no coarsening, each coarsening with the
    // hash, the cuts given and the balanced cuts.
    struct Owner {
      int slabs = 0, coarsen = 0;
      std::vector<std::uint32_t> cuts;
    };
    std::vector<Owner> owners;
    const bool cuts_only = (balanced_cuts || !fixed_cuts.empty()) && app.count("--slabs") == 0 &&
                           app.count("--coarsen") == 0;
    for (int w : slabs)
      for (int k : coarsen)
        if ((w == 0 || k == 0) && !cuts_only)
          owners.push_back({w, k, {}});  // slabs replace the hash
    if (!fixed_cuts.empty()) owners.push_back({0, 0, fixed_cuts});
    if (balanced_cuts && comm.size() > 1) {
      std::vector<std::uint32_t> cuts(static_cast<std::size_t>(comm.size() - 1));
      if (root) {
        const auto sim = partition::simulate_ranks(p, o, {comm.size()}, {0});
        cuts = partition::balanced_prefix_cuts(sim, comm.size());
      }
      comm.broadcast(cuts.data(), static_cast<int>(cuts.size() * sizeof(std::uint32_t)), 0);
      owners.push_back({0, 0, cuts});
    }
    std::vector<distributed::DistGridOptions> configs;
    // The dense engine has one distribution (slabs balanced by free states): one configuration.
    if (o.engine == GridEngine::dense) {
      modes = {"async"};
      batches = {batches.front()};
      owners = {Owner{}};
      filters = {filters.front()};
    }
    for (const auto& mode : modes)
      for (std::size_t batch : batches)
        for (const Owner& owner : owners)
          for (int f : filters) {
            distributed::DistGridOptions d;
            d.scheme = distributed::parse_scheme(mode);
            d.batch = batch;
            d.coarsen_shift = owner.coarsen;
            d.slab_width = owner.slabs;
            d.prefix_cuts = owner.cuts;
            d.sent_filter_log2 = f;
            distributed::validate(d, p.extent, comm.size(), p.dims);
            configs.push_back(d);
          }
    std::vector<double> serial_t;
    std::vector<std::vector<double>> dist_t(configs.size()), ratio(configs.size()),
        of_ceiling(configs.size());
    std::vector<GridReport> last(configs.size());
    std::uint64_t serial_expanded = 0;
    double serial_cost = 0.0;
    auto time_serial = [&] {
      if (no_serial) return;
      if (root) {
        const GridReport s = solve_grid(p, o);
        serial_t.push_back(s.result.counters.time_ms);
        serial_expanded = s.result.counters.expanded;
        serial_cost = s.result.cost;
      }
      comm.quiet_barrier();  // waiting ranks sleep: spinning would slow the serial run
    };
    // The machine's own ceiling for P ranks: every rank runs the whole serial search at
    // the same time. P times the solo time over this time is the best any distribution of
    // this memory-bound work could reach here (shared caches, memory bandwidth, a VM's
    // neighbours), before any communication.
    std::vector<double> crowd_t;
    auto time_crowded = [&] {
      if (no_serial || !ceiling) return;
      comm.quiet_barrier();
      const double t = solve_grid(p, o).result.counters.time_ms;
      const double slowest = comm.allreduce_max(t);
      if (root) crowd_t.push_back(slowest);
    };
    std::vector<double> crowd_ratio;
    std::optional<Progress> progress;
    if (root) progress.emplace("hpcplan_mpi_scaling", static_cast<std::size_t>(repeats));
    for (int r = 0; r < repeats; ++r) {
      // Alternate the order: whichever runs second finds the allocator and caches warmed.
      // The crowded run stays next to the distributed ones (see the top).
      const bool serial_first = r % 2 == 0;
      if (serial_first) time_serial();
      if (!serial_first) time_crowded();
      for (std::size_t c = 0; c < configs.size(); ++c) {
        last[c] = distributed::solve_grid_distributed(p, o, configs[c], comm);
        dist_t[c].push_back(last[c].result.counters.time_ms);
      }
      if (serial_first) time_crowded();
      if (!serial_first) time_serial();
      if (root && !crowd_t.empty())
        crowd_ratio.push_back(comm.size() * serial_t.back() / crowd_t.back());
      if (!no_serial && root)
        for (std::size_t c = 0; c < configs.size(); ++c) {
          ratio[c].push_back(serial_t.back() / dist_t[c].back());
          if (!crowd_ratio.empty()) of_ceiling[c].push_back(ratio[c].back() / crowd_ratio.back());
        }
      if (progress) progress->step("round " + std::to_string(r + 1));
    }
    const double serial_ms = no_serial || !root ? 0.0 : median(serial_t);
    std::ostringstream rows;
    for (std::size_t c = 0; c < configs.size() && root; ++c) {
      const GridReport& g = last[c];
      if (!no_serial && std::abs(g.result.cost - serial_cost) > 1e-6 * (1 + serial_cost) &&
          o.algorithm != GridAlgorithm::bfs && o.algorithm != GridAlgorithm::wastar)
        throw RunError("distributed cost differs from serial");
      std::uint64_t messages = 0, bytes = 0;
      for (const auto& k2 : g.distribution.per_rank) {
        messages += k2.messages_sent;
        bytes += k2.bytes_sent;
      }
      const double med = median(dist_t[c]);
      const double ex = static_cast<double>(std::max<std::uint64_t>(1, g.result.counters.expanded));
      const double speedup = no_serial ? 0.0 : median(ratio[c]);
      std::string cuts;  // positions joined by ';' (the CSV's own separator is ',')
      for (auto x : configs[c].prefix_cuts) {
        if (!cuts.empty()) cuts += ';';
        cuts += std::to_string(x);
      }
      char line[2048];
      std::snprintf(line, sizeof line,
                    "%s,%d,%d,%d,%.2f,%s,%s,%zu,%d,%d,%d,%s,%.6f,%llu,%llu,%.3f,%.3f,%.3f,%.3f,"
                    "%.3f,%.5f,%.2f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%d,%s,%.3f,%.3f,%.3f,%.3f,"
                    "%s,%d\n",
                    label.c_str(), comm.size(), p.dims, p.extent, p.gog.density, algo.c_str(),
                    g.distribution.scheme.c_str(), configs[c].batch, configs[c].coarsen_shift,
                    configs[c].sent_filter_log2, repeats,
                    std::string(search::to_string(g.result.status)).c_str(), g.result.cost,
                    static_cast<unsigned long long>(g.result.counters.expanded),
                    static_cast<unsigned long long>(serial_expanded), serial_ms, med,
                    no_serial ? 0.0 : serial_ms / med, speedup, speedup / comm.size(),
                    messages / ex, bytes / ex, workload_deviation_percent(g.distribution.per_rank),
                    serial_expanded ? ex / static_cast<double>(serial_expanded) : 0.0,
                    lowest(ratio[c]), highest(ratio[c]), median(of_ceiling[c]),
                    lowest(of_ceiling[c]), highest(of_ceiling[c]), configs[c].slab_width,
                    cuts.c_str(), quantile(of_ceiling[c], 0.25), quantile(of_ceiling[c], 0.75),
                    lowest(serial_t), highest(serial_t), g.options.engine.c_str(),
                    g.dense ? g.dense->threads : 1);
      rows << line;
      std::fputs(line, stderr);
    }
    if (root && !crowd_ratio.empty()) {
      char line[512];
      std::snprintf(line, sizeof line,
                    "%s,%d,%d,%d,%.2f,%s,ceiling,0,0,0,%d,solved,%.6f,%llu,%llu,%.3f,%.3f,%.3f,"
                    "%.3f,%.3f,0,0,0,1,%.3f,%.3f,1,1,1,0,,1,1,%.3f,%.3f,%s,%d\n",
                    label.c_str(), comm.size(), p.dims, p.extent, p.gog.density, algo.c_str(),
                    repeats, serial_cost, static_cast<unsigned long long>(serial_expanded),
                    static_cast<unsigned long long>(serial_expanded), serial_ms,
                    serial_ms * comm.size() / median(crowd_ratio), median(crowd_ratio),
                    median(crowd_ratio), median(crowd_ratio) / comm.size(), lowest(crowd_ratio),
                    highest(crowd_ratio), lowest(serial_t), highest(serial_t), engine.c_str(),
                    o.engine == GridEngine::dense ? o.threads : 1);
      rows << line;
      std::fputs(line, stderr);
    }
    if (root) {
      const char* header =
          "label,ranks,dims,extent,density,algo,scheme,batch,coarsen,sent_filter,repeats,status,"
          "cost,expanded,serial_expanded,serial_median_ms,median_ms,ratio_of_medians,"
          "speedup_vs_serial,efficiency,"
          "messages_per_expansion,bytes_per_expansion,workload_deviation_percent,"
          "search_overhead,speedup_min,speedup_max,of_ceiling,of_ceiling_min,of_ceiling_max,"
          "slabs,cuts,of_ceiling_q1,of_ceiling_q3,serial_min_ms,serial_max_ms,engine,threads\n";
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
    const int code = dynamic_cast<const InputError*>(&e) != nullptr ? 2 : 1;
    if (comm.size() > 1) comm.abort(code);
    return code;
  }
  return 0;
}
