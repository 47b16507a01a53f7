#include "hpcplan/distributed/grid_planner_mpi.hpp"

#include "hpcplan/distributed/mpi_slab_transport.hpp"

#include <algorithm>
#include <optional>
#include <thread>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/graph/lattice_heuristic.hpp"
#include "hpcplan/partition/ownership.hpp"
#include "hpcplan/plan/grid_planner_impl.hpp"
#include "hpcplan/search/stamped_dense_map.hpp"

namespace hpcplan::distributed {

Scheme parse_scheme(std::string_view name) {
  if (name == "async") return Scheme::async;
  if (name == "bulk" || name == "bulk_sync") return Scheme::bulk_sync;
  throw InputError("unknown --mode '" + std::string(name) + "' (expected async or bulk)");
}

std::string_view to_string(Scheme s) {
  switch (s) {
    case Scheme::async:
      return "async";
    case Scheme::bulk_sync:
      return "bulk_sync";
    case Scheme::level_sync:
      return "level_sync";
  }
  return "unknown";
}

void validate(const DistGridOptions& o, int extent, int ranks, int dims) {
  if (o.coarsen_shift < 0 || o.coarsen_shift > 16)
    throw InputError("--owner-coarsen must be in 0..16, got " + std::to_string(o.coarsen_shift));
  if (o.slab_width < 0)
    throw InputError("--owner-slabs must be 0 (hash) or a width, got " +
                     std::to_string(o.slab_width));
  if (o.slab_width > 0 && o.coarsen_shift > 0)
    throw InputError("--owner-slabs and --owner-coarsen choose different ownerships: give one");
  if (extent > 0 && o.slab_width > extent)
    throw InputError("--owner-slabs " + std::to_string(o.slab_width) +
                     " is wider than the extent " + std::to_string(extent));
  if (!o.prefix_cuts.empty()) {
    if (o.slab_width > 0 || o.coarsen_shift > 0)
      throw InputError("--owner-cuts replaces --owner-slabs and --owner-coarsen: give one");
    const std::uint64_t positions = extent > 0 ? partition::prefix_positions(dims, extent) : ~0ULL;
    if (const std::size_t j = partition::first_misplaced_cut(o.prefix_cuts, positions);
        j != o.prefix_cuts.size())
      throw InputError("--owner-cuts must ascend strictly within 1.." +
                       (extent > 0 ? std::to_string(positions - 1) : std::string("extent^2 - 1")) +
                       ", got " + std::to_string(o.prefix_cuts[j]) + " at position " +
                       std::to_string(j + 1));
    if (ranks > 0 && o.prefix_cuts.size() != static_cast<std::size_t>(ranks - 1))
      throw InputError("--owner-cuts needs P - 1 positions for P ranks: " + std::to_string(ranks) +
                       " need " + std::to_string(ranks - 1) + ", got " +
                       std::to_string(o.prefix_cuts.size()));
  }
  if (o.batch < 1 || o.batch > (1u << 20))
    throw InputError("--batch must be in 1..1048576 records, got " + std::to_string(o.batch));
  if (!(o.batch_age_ms >= 0.0) || o.batch_age_ms > 1000.0)
    throw InputError("--batch-age-ms must be in 0..1000");
  if (o.sync_every < 1) throw InputError("--sync-every must be at least 1");
  if (o.sent_filter_log2 < 0 || o.sent_filter_log2 > 28)
    throw InputError("--sent-filter must be in 0..28 (log2 of its slots)");
}

std::uint64_t per_rank_budget(const GridSearchOptions& options, GridReport& report, int ranks) {
  const auto p = static_cast<std::uint64_t>(ranks);
  if (options.max_states != 0) return (options.max_states + p - 1) / p;
  const std::uint64_t per_rank = report.options.max_states;
  report.options.max_states = per_rank * p;
  return per_rank;
}

DistOptions rank_options(GridAlgorithm algorithm, const DistGridOptions& dist,
                         const mpi::Communicator& comm) {
  DistOptions d;
  d.scheme = algorithm == GridAlgorithm::bfs ? Scheme::level_sync : dist.scheme;
  d.batch = dist.batch;
  d.batch_age_ms = dist.batch_age_ms;
  d.sync_every = dist.sync_every;
  d.sent_filter_log2 = dist.sent_filter_log2;
  d.yield_when_idle = comm.ranks_on_node() > static_cast<int>(std::thread::hardware_concurrency());
  if (comm.rank() == dist.fault_rank) {
    d.fail_after_expansions = dist.fault_after;
    d.fault_kill = dist.fault_kill;
  }
  return d;
}

namespace {

template <int W>
void run_distributed(const ObstacleSource& field, const GridProblem& problem,
                     const GridSearchOptions& o, const DistGridOptions& dist,
                     const mpi::Communicator& comm, GridReport& report) {
  LatticeGraph<W> graph(field, problem.connectivity);
  const auto start = graph.pack(report.problem.start);
  const auto goal = graph.pack(report.problem.goal);
  const int p = comm.size();
  const std::uint64_t per_rank = per_rank_budget(o, report, p);
  auto eo = hpcplan::detail::engine_options(o, report.options.weight, per_rank);
  // The serial engine's rule: small one-word lattices keep their states in the dense store
  // (each rank faults in only the pages its own states fall on).
  const bool dense = W == 1 && dense_visited_fits(problem.dims, problem.extent);
  if (dense) eo.dense_keys = graph.layout().dense_index_bound();
  report.options.visited_map =
      dense ? search::StampedDensePolicy::name : search::DefaultVisitedMap::name;

  const DistOptions d = rank_options(o.algorithm, dist, comm);
  const partition::Ownership<W> owner(graph.layout(), p, dist.coarsen_shift, dist.slab_width,
                                      problem.extent, dist.prefix_cuts);

  auto search = [&](const auto& h) {
    using H = std::remove_cvref_t<decltype(h)>;
    auto with = [&]<class Map>(Map) {
      DistributedSearch<Map, LatticeGraph<W>, H, partition::Ownership<W>> engine(graph, h, owner,
                                                                                 comm, eo, d);
      return engine.run(start, goal);
    };
    if constexpr (W == 1)
      if (dense) return with(search::StampedDensePolicy{});
    return with(search::DefaultVisitedMap{});
  };
  const auto r =
      hpcplan::detail::with_heuristic<W>(o, problem, graph.layout(), report.problem.goal, search);
  GridResult& out = report.result;
  out.status = r.result.status;
  out.cost = r.result.cost;
  out.hops = r.result.hops;
  out.counters = r.result.counters;
  report.distribution.per_rank = std::move(r.per_rank);
  // One rank runs the serial engine (DistributedSearch::run), and says so.
  report.distribution.scheme = p == 1 ? "serial" : std::string(to_string(d.scheme));
  if (o.keep_path)
    for (const auto& s : r.result.path) out.path.push_back(graph.unpack(s));
}

}  // namespace

GridReport solve_grid_distributed(const GridProblem& problem, const GridSearchOptions& options,
                                  const DistGridOptions& dist, const mpi::Communicator& comm) {
  if (problem.cspace) return solve_cspace_distributed(problem, options, dist, comm);
  hpcplan::validate(problem, options);
  validate(dist, problem.extent, comm.size(), problem.dims);
  Stopwatch setup;
  std::optional<GogField> gog;
  const ObstacleSource field = obstacles_of(problem, gog);
  GridReport report = prepare_grid_report(problem, options, field, comm.ranks_on_node());
  report.result.setup_ms = setup.milliseconds();
  GridDistribution& dr = report.distribution;
  dr.ranks = comm.size();
  dr.coarsen_shift = dist.coarsen_shift;
  dr.slab_width = dist.slab_width;
  dr.prefix_cuts = dist.prefix_cuts;
  dr.batch = dist.batch;
  dr.batch_age_ms = dist.batch_age_ms;
  dr.sync_every = dist.sync_every;

  // The engine, its threads and its memory budget must be the same on every rank, but each
  // rank derives its defaults from its own node (free memory, cores, ranks sharing them): all
  // take the smallest.
  GridSearchOptions agreed = options;
  {
    double v[2] = {static_cast<double>(dense_memory_budget(options, report)),
                   static_cast<double>(dense_threads(field, options, comm.ranks_sharing_cpus()))};
    comm.allreduce_min(v);
    agreed.memory_budget = static_cast<std::uint64_t>(std::min(v[0], 1.8e19));
    agreed.threads = static_cast<int>(v[1]);
  }
  const bool dense = uses_dense_engine(field, problem, agreed, report, comm.size());
  require_dense_for_checkpoints(options, problem.dims, dense);

  if (dist.compare_serial) {
    if (comm.rank() == 0) {
      // Before the distributed run, while the other ranks sleep at the barrier below, so the
      // two never compete for cores. The ranks expand every lattice state, so the reference
      // does too (no jump points at 2D): search overhead compares like with like.
      // One process on one core, with the budget a plain run would have (not a rank's share).
      GridSearchOptions serial_options = options;
      serial_options.jump_points = false;
      serial_options.threads = 1;
      serial_options.checkpoint.clear();  // the reference neither writes nor reads them
      serial_options.restart.clear();
      serial_options.checkpoint_every_s = 0.0;
      // The dense engine's serial reference holds the whole lattice in one process: where
      // that is over the budget there is no reference (rather than rank 0 failing alone, or
      // a reference from the other engine).
      const GridReport serial_plan = prepare_grid_report(problem, serial_options, field, 1);
      if (!dense || dense_fits(field, problem, serial_options, serial_plan, 1)) {
        const GridReport serial = solve_grid(field, problem, serial_options);
        report.serial =
            SerialReference{serial.result.status, serial.result.cost, serial.result.hops,
                            serial.result.counters.expanded, serial.result.counters.time_ms};
      }
    }
    comm.quiet_barrier();
  }

  if (dense) {
    // Slabs of the dense lattice, one per rank; one rank is the serial dense engine.
    MpiSlabTransport transport(comm);
    dr.scheme = comm.size() == 1 ? "serial" : "dense_slabs";
    run_dense(field, problem, agreed, transport, comm.ranks_sharing_cpus(), report);
    const dense::Figures& f = *report.dense;
    dr.per_rank.assign(f.rank_expanded.size(), {});
    for (std::size_t r = 0; r < dr.per_rank.size(); ++r) {
      dr.per_rank[r].expanded = f.rank_expanded[r];
      dr.per_rank[r].search_ms = f.rank_search_ms[r];
    }
    finish_grid_report(report);
    return report;
  }

  switch (report.options.key_words) {
    case 1:
      run_distributed<1>(field, problem, options, dist, comm, report);
      break;
    case 2:
      run_distributed<2>(field, problem, options, dist, comm, report);
      break;
    default:
      run_distributed<4>(field, problem, options, dist, comm, report);
      break;
  }
  finish_grid_report(report);
  return report;
}

DistanceFieldRun distance_field_distributed(const GridProblem& asked,
                                            const GridSearchOptions& options,
                                            const mpi::Communicator& comm) {
  hpcplan::validate(asked, options);
  validate_distance_field(asked, options);
  std::optional<GogField> gog;
  const ObstacleSource field = obstacles_of(asked, gog);
  const GridProblem problem = distance_field_problem(field, asked);
  // The threads and budget every rank can afford (as solve_grid_distributed).
  const GridReport plan = prepare_grid_report(problem, options, field, comm.ranks_on_node());
  GridSearchOptions agreed = options;
  double v[2] = {
      static_cast<double>(dense_memory_budget(options, plan)),
      static_cast<double>(distance_field_threads(field, options, comm.ranks_sharing_cpus()))};
  comm.allreduce_min(v);
  agreed.memory_budget = static_cast<std::uint64_t>(std::min(v[0], 1.8e19));
  agreed.threads = static_cast<int>(v[1]);
  MpiSlabTransport transport(comm);
  DistanceFieldRun run = distance_field(field, problem, agreed, transport, comm.ranks_on_node());
  run.goal_given = asked.goal.has_value();
  GridDistribution& dr = run.report.distribution;
  dr.ranks = comm.size();
  dr.scheme = comm.size() == 1 ? "serial" : "dense_slabs";
  const dense::Figures& f = *run.report.dense;
  dr.per_rank.assign(f.rank_expanded.size(), {});
  for (std::size_t r = 0; r < dr.per_rank.size(); ++r) {
    dr.per_rank[r].expanded = f.rank_expanded[r];
    dr.per_rank[r].search_ms = f.rank_search_ms[r];
  }
  finish_grid_report(run.report);
  return run;
}

}  // namespace hpcplan::distributed
