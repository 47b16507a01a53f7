// `hpcplan scen`: every problem of a MovingAI scenario file solved on its map and checked
// against the published optimal lengths; serial, or under mpirun with the rows dealt round the
// ranks (--split rows, the default: the ranks pay by answering different queries) or every rank
// on each row (--split search: the distributed planner, for checking it).
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "hpcplan/cli/scen_options.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/distributed/grid_planner_mpi.hpp"
#include "hpcplan/io/scenario_report.hpp"

namespace hpcplan::cli {
namespace {

struct ScenCommandArgs {
  ScenArgs scen;
  std::string split = "rows";
  bool json = false;
};

// What a rank sends rank 0 about one row (the rest rank 0 reads from the scenario itself).
struct RowRecord {
  std::uint64_t row, expanded, hops;
  double cost, time_us;
  std::int32_t status, mismatch;
};

std::vector<ScenarioRowResult> gather_rows(const mpi::Communicator& comm,
                                           const std::vector<ScenarioRowResult>& mine,
                                           const env::Scenario& scenario) {
  std::vector<RowRecord> records;
  for (const ScenarioRowResult& r : mine)
    records.push_back({r.row, r.expanded, r.hops, r.cost, r.time_us,
                       static_cast<std::int32_t>(r.status), r.mismatch ? 1 : 0});
  const auto bytes = comm.allgather(std::span<const std::byte>(
      reinterpret_cast<const std::byte*>(records.data()), records.size() * sizeof(RowRecord)));
  std::vector<ScenarioRowResult> all(bytes.size() / sizeof(RowRecord));
  for (std::size_t i = 0; i < all.size(); ++i) {
    RowRecord rec;
    std::memcpy(&rec, bytes.data() + i * sizeof(RowRecord), sizeof rec);
    ScenarioRowResult& r = all[i];
    const env::ScenarioRow& row = scenario.rows.at(rec.row);
    r.row = rec.row;
    r.bucket = row.bucket;
    r.start = row.start;
    r.goal = row.goal;
    r.optimal = row.optimal;
    r.cost = rec.cost;
    r.status = static_cast<Status>(rec.status);
    r.expanded = rec.expanded;
    r.hops = rec.hops;
    r.time_us = rec.time_us;
    r.mismatch = rec.mismatch != 0;
  }
  std::sort(all.begin(), all.end(),
            [](const ScenarioRowResult& a, const ScenarioRowResult& b) { return a.row < b.row; });
  return all;
}

}  // namespace

Action register_scen_command(CLI::App& app) {
  auto args = std::make_shared<ScenCommandArgs>();
  CLI::App* cmd = app.add_subcommand(
      "scen", "Solve a MovingAI scenario (.scen/.3dscen) and check every row's optimal length");
  add_scen_options(cmd, args->scen);
  cmd->add_option("--split", args->split,
                  "Under mpirun: rows (dealt round the ranks) | search (every rank on each row, "
                  "the distributed planner)")
      ->check(CLI::IsMember({"rows", "search"}))
      ->capture_default_str()
      ->group("Distributed (under mpirun/srun)");
  cmd->add_flag("--json", args->json, "Print the JSON summary instead of the table");

  return [args](const Context& context) {
    ScenArgs& a = args->scen;
    const RunControl control = signal_control();
    PreparedScen run = prepare_scen_run(a, control);
    const int ranks = context.comm ? context.comm->size() : 1;
    const int rank = context.comm ? context.comm->rank() : 0;
    run.info.ranks = ranks;
    run.info.split = ranks > 1 ? args->split : "serial";
    Stopwatch wall;
    std::vector<ScenarioRowResult> rows;
    // SIGTERM (SLURM's time limit), SIGUSR1 or Ctrl-C end the run between rows; the rows done
    // are written and summarised, and the run exits 1 (it did not check every row).
    const auto interrupted = [&control] { return control.interrupted(); };
    if (ranks > 1 && args->split == "search") {
      // Every rank must take the same decision to stop, or one would wait in the next row's
      // collectives: only a signal every rank received (mpirun forwards it to all) is read.
      const distributed::DistGridOptions dist;
      const mpi::Communicator& comm = *context.comm;
      rows = run_scenario_rows(
          run.grid, run.connectivity, run.scenario, run.rows, a.options,
          [&](const GridProblem& p, const GridSearchOptions& o) {
            return distributed::solve_grid_distributed(p, o, dist, comm);
          },
          {}, [&] { return comm.allreduce_max(interrupted() ? 1.0 : 0.0) > 0.0; });
    } else {
      std::vector<std::size_t> mine;
      for (std::size_t k = static_cast<std::size_t>(rank); k < run.rows.size();
           k += static_cast<std::size_t>(ranks))
        mine.push_back(run.rows[k]);
      rows = run_scenario_rows(run.grid, run.connectivity, run.scenario, mine, a.options, {}, {},
                               interrupted);
      if (ranks > 1) rows = gather_rows(*context.comm, rows, run.scenario);
    }
    run.info.wall_ms = wall.milliseconds();
    if (control.interrupted()) run.info.interrupted_by = control.stopped_by();
    if (ranks > 1) {
      // Any rank's interruption marks the whole run.
      const bool any = context.comm->allreduce_max(control.interrupted() ? 1.0 : 0.0) > 0.0;
      if (any && run.info.interrupted_by.empty())
        run.info.interrupted_by = "a signal on another rank";
    }
    if (!context.is_root()) return run.info.interrupted_by.empty() ? kExitOk : kExitRunFailure;
    const ScenarioSummary summary = finish_scen_run(a, run, rows);
    const std::string out =
        args->json ? to_json(run.info, summary).dump() + "\n" : to_summary(run.info, summary);
    std::fputs(out.c_str(), stdout);
    std::fflush(stdout);
    if (!run.info.interrupted_by.empty()) {
      std::fprintf(stderr, "hpcplan: scen interrupted by %s after %llu of %zu rows\n",
                   run.info.interrupted_by.c_str(), static_cast<unsigned long long>(summary.rows),
                   run.rows.size());
      return kExitRunFailure;
    }
    if (summary.mismatches > 0) {
      std::fprintf(stderr,
                   "hpcplan: %llu of %llu rows differ from the published optimum (first: row "
                   "%llu)\n",
                   static_cast<unsigned long long>(summary.mismatches),
                   static_cast<unsigned long long>(summary.rows),
                   static_cast<unsigned long long>(summary.mismatch_rows.front()));
      return kExitRunFailure;
    }
    return kExitOk;
  };
}

}  // namespace hpcplan::cli
