// `hpcplan ompl`: the grid planner against OMPL's sampling planners on one problem (the GOG
// field, or OMPL's own kinematic-chain and hypercube benchmarks as configuration spaces), with
// an OMPL benchmark log, a per-run CSV and a summary table of medians.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "commands.hpp"
#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/io/ompl_bench_csv.hpp"
#include "hpcplan/plan/ompl_benchmark.hpp"

namespace hpcplan::cli {
namespace {

struct OmplArgs {
  plan::OmplBenchOptions options;
  std::string log, csv;
  bool no_shortcut = false;
  bool verbose = false;
};

// Median of the values that exist (negative = not available); -1 when none does.
double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return x < 0; }), v.end());
  if (v.empty()) return -1.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string cell(double v, const char* format) {
  if (v < 0) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void print_summary(const plan::OmplBenchOptions& o, const plan::OmplBenchResult& r) {
  if (plan::is_cspace_world(o.world))
    std::printf(
        "hpcplan ompl: world %s, %s %d, %d cells per axis, %d run(s) of %.3g s per planner, "
        "seed %llu\n",
        o.world.c_str(), o.world == "chain" ? "links" : "dims", o.dims, r.cells, o.runs, o.time_s,
        static_cast<unsigned long long>(o.seed));
  else
    std::printf(
        "hpcplan ompl: world gog, %dD, extent %d, %d run(s) of %.3g s per planner, seed %llu\n",
        o.dims, o.extent, o.runs, o.time_s, static_cast<unsigned long long>(o.seed));
  std::printf("  straight line %.4f; reference quality (best final of any run) %s\n",
              r.straight_line, cell(r.reference_quality, "%.4f").c_str());
  std::printf("  %-16s %7s %12s %9s %12s %9s %9s %14s %6s %9s\n", "planner", "success",
              "t_first ms", "q_first", "t_best ms", "q_best", "q_final", "coll. checks", "valid",
              "smooth x");
  for (const auto& name : o.planners) {
    // smooth x: the smoothed answer's time over the lattice answer's in the same run
    // (t_first over t_first less the smoothing), immune to the machine's drift between runs.
    std::vector<double> tf, qf, tb, qb, qz, cc, sx;
    int solved = 0, runs = 0, valid = 0;
    for (const auto& row : r.rows) {
      if (row.planner != name) continue;
      ++runs;
      if (row.solved) ++solved;
      if (row.path_valid) ++valid;
      tf.push_back(row.solved ? row.time_first_s * 1e3 : -1);
      qf.push_back(row.quality_first);
      tb.push_back(row.time_best_s < 0 ? -1 : row.time_best_s * 1e3);
      qb.push_back(row.quality_best);
      qz.push_back(row.quality_final);
      cc.push_back(static_cast<double>(row.collision_checks));
      if (row.solved && row.smoothing_s > 0 && row.time_first_s > row.smoothing_s)
        sx.push_back(row.time_first_s / (row.time_first_s - row.smoothing_s));
    }
    std::printf("  %-16s %3d/%-3d %12s %9s %12s %9s %9s %14s %3d/%-3d %8s\n", name.c_str(), solved,
                runs, cell(median(tf), "%.3f").c_str(), cell(median(qf), "%.4f").c_str(),
                cell(median(tb), "%.3f").c_str(), cell(median(qb), "%.4f").c_str(),
                cell(median(qz), "%.4f").c_str(), cell(median(cc), "%.0f").c_str(), valid, runs,
                cell(median(sx), "%.2f").c_str());
  }
  std::printf(
      "  (medians over runs; times of solved runs; '-' = none reached; smooth x: grid planner's "
      "answer time over its lattice answer's, same run)\n");
}

}  // namespace

std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// The options that describe the GOG field, refused with a configuration-space world rather
// than silently ignored.
const char* const kGogOnly[] = {"--extent", "--density", "--motion", "--resolution"};

Action register_ompl_command(CLI::App& app) {
  auto args = std::make_shared<OmplArgs>();
  CLI::App* cmd = app.add_subcommand(
      "ompl",
      "Grid A* vs OMPL sampling planners on the GOG field or OMPL's chain and hypercube "
      "benchmarks (OMPL benchmark log + CSV)");
  auto& o = args->options;
  cmd->add_option("--world", o.world,
                  "gog (seed 002's field) | chain (OMPL's kinematic chain, --dims links) | "
                  "hypercube (OMPL's hypercube corridor)")
      ->capture_default_str();
  // The range depends on the world: validate() says which.
  add_number(cmd, "--dims", o.dims, "Dimensions (chain: links): gog 2..10, chain/hypercube 2..16",
             2, 16)
      ->required();
  add_number(cmd, "--cells", o.cells,
             "chain/hypercube: the grid planner's cells per axis (0: the benchmark's default)", 0,
             65535)
      ->capture_default_str();
  add_number(cmd, "--resolution-fraction", o.resolution_fraction,
             "chain/hypercube: motion-check step as a fraction of the bounds' diagonal (0: the "
             "benchmark's: chain 0.01, hypercube 0.001)",
             0, 1)
      ->capture_default_str();
  cmd->add_option(
         "--planners", o.planners,
         "Comma-separated (hpcplan planners --world ompl): " + planner_names("ompl") +
             "; with --world chain|hypercube also: " + join_names(plan::cspace_only_planners()))
      ->delimiter(',')
      ->capture_default_str();
  add_number(cmd, "--time", o.time_s, "Seconds per run", 1e-6, 3600)->capture_default_str();
  add_number(cmd, "--runs", o.runs, "Runs per planner", 1, 10000)->capture_default_str();
  add_number(cmd, "--warmup", o.warmup,
             "Untimed solves of each planner first (at most 1 s each), not recorded", 0, 100)
      ->capture_default_str();
  add_number(cmd, "--seed", o.seed, "GOG field and OMPL random seed")->capture_default_str();
  add_number(cmd, "--extent", o.extent, "Cells per axis; bounds are [0, extent]", 2, 1000)
      ->capture_default_str();
  add_number(cmd, "--density", o.gog.density, "Blocked fraction aimed at", 0, 1)
      ->capture_default_str();
  cmd->add_option("--motion", o.motion,
                  "exact (every touched cell free) | discrete (OMPL's sampled validator)")
      ->capture_default_str();
  add_number(cmd, "--resolution", o.resolution_cells,
             "Discrete motion checks: spacing in cell widths, (0, 1]", 1e-9, 1)
      ->capture_default_str();
  add_param(cmd, "grid_weight", o.grid_weight)->capture_default_str();
  add_param(cmd, "no_shortcut", args->no_shortcut);
  add_param(cmd, "smoothing_budget", o.smoothing_budget)->capture_default_str();
  cmd->add_option("--log", args->log, "OMPL benchmark log (for ompl_benchmark_statistics)");
  cmd->add_option("--csv", args->csv, "One row per planner run");
  cmd->add_flag("--verbose", args->verbose, "Keep OMPL's informational messages");
  return [args, cmd](const Context& context) {
    if (context.comm != nullptr && context.comm->size() > 1)
      throw InputError(
          "hpcplan ompl runs in one process; the distributed grid planner is "
          "`mpirun -np P hpcplan grid`");
    if (!args->verbose) ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    args->options.shortcut = !args->no_shortcut;
    if (plan::is_cspace_world(args->options.world))
      for (const char* gog_only : kGogOnly)
        if (cmd->count(gog_only) > 0)
          throw InputError(std::string(gog_only) + " describes the GOG field; --world " +
                           args->options.world + " takes --cells and --resolution-fraction");
    plan::validate(args->options);
    if (!args->log.empty()) require_writable_destination(args->log, "--log");
    if (!args->csv.empty()) require_writable_destination(args->csv, "--csv");
    const auto result = plan::run_ompl_benchmark(args->options);
    if (!args->log.empty()) write_file_atomically(args->log, result.ompl_log);
    if (!args->csv.empty()) write_file_atomically(args->csv, io::ompl_bench_csv(result));
    print_summary(args->options, result);
    for (const auto& row : result.rows)
      if (!row.path_valid)
        throw RunError(row.planner + " run " + std::to_string(row.run) +
                       " returned a path that fails re-validation");
    return 0;
  };
}

}  // namespace hpcplan::cli
