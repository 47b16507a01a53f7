// The configuration-space planner over MPI ranks: the lattice of graph/cspace_graph.hpp searched
// by the distributed engine with hashed ownership. Each rank tests the successors of the states
// it expands (their ends and edges, in batches) before routing them to their owners, so the
// collision checks, which dominate on a mechanism's space, are spread over the ranks.
#include <algorithm>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/distributed/grid_planner_mpi.hpp"
#include "hpcplan/partition/ownership.hpp"
#include "hpcplan/plan/cspace_planner.hpp"
#include "hpcplan/plan/grid_planner_impl.hpp"

namespace hpcplan::distributed {

GridReport solve_cspace_distributed(const GridProblem& problem, const GridSearchOptions& options,
                                    const DistGridOptions& dist, const mpi::Communicator& comm) {
  validate_cspace(problem, options);
  validate(dist, 0, comm.size(), problem.dims);
  if (dist.slab_width > 0 || !dist.prefix_cuts.empty())
    throw InputError(
        "--owner-slabs and --owner-cuts cut GOG and map lattices; a configuration space's states "
        "are owned by their hash (--owner-coarsen k keeps 2^k-wide cells together)");
  Stopwatch setup;
  CSpaceGraph graph(*problem.cspace->space, problem.extent, problem.cspace->moves);
  graph.set_batch_checks(problem.cspace->batch_checks);
  CSpaceRun run;
  const bool joined = begin_cspace_run(problem, options, graph, comm.ranks_on_node(), run);
  GridReport& report = run.report;
  report.result.setup_ms = setup.milliseconds();
  GridDistribution& dr = report.distribution;
  const int p = comm.size();
  dr.ranks = p;
  dr.coarsen_shift = dist.coarsen_shift;
  dr.batch = dist.batch;
  dr.batch_age_ms = dist.batch_age_ms;
  dr.sync_every = dist.sync_every;
  // Every rank joined the ends the same way (the same deterministic tests): all return here.
  if (!joined) {
    finish_grid_report(report);
    return report;
  }

  if (dist.compare_serial) {
    if (comm.rank() == 0) {
      const GridReport serial = solve_cspace(problem, options);
      report.serial =
          SerialReference{serial.result.status, serial.result.cost, serial.result.hops,
                          serial.result.counters.expanded, serial.result.counters.time_ms};
    }
    comm.quiet_barrier();
  }

  const std::uint64_t per_rank = per_rank_budget(options, report, p);
  const auto eo = hpcplan::detail::engine_options(options, report.options.weight, per_rank);
  const DistOptions d = rank_options(options.algorithm, dist, comm);
  using Owner = partition::Ownership<CSpaceGraph::kWords>;
  const Owner owner(graph.layout(), p, dist.coarsen_shift);

  auto search = [&](const auto& h) {
    using H = std::remove_cvref_t<decltype(h)>;
    DistributedSearch<search::DefaultVisitedMap, CSpaceGraph, H, Owner> engine(graph, h, owner,
                                                                               comm, eo, d);
    return engine.run(run.start, run.goal);
  };
  auto r = options.algorithm == GridAlgorithm::dijkstra || options.algorithm == GridAlgorithm::bfs
               ? search(search::ZeroHeuristic{})
               : search(CSpaceHeuristic(graph, run.goal));
  dr.per_rank = std::move(r.per_rank);
  dr.scheme = p == 1 ? "serial" : std::string(to_string(d.scheme));
  if (comm.rank() == 0) {
    finish_cspace_run(r.result, graph, run);
  } else {
    report.result.status = r.result.status;
    report.result.counters = r.result.counters;
    finish_grid_report(report);
  }
  return report;
}

}  // namespace hpcplan::distributed
