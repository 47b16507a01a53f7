#pragma once
// The grid planner across MPI ranks: the same problem, options and report as solve_grid(),
// searched by the distributed engine. Collective: every rank calls it with the same
// arguments; the report is complete on rank 0 (other ranks hold their own share).
#include "hpcplan/distributed/distributed_search.hpp"
#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/plan/distance_field.hpp"
#include "hpcplan/plan/grid_planner.hpp"

namespace hpcplan::distributed {

struct DistGridOptions {
  // async or bulk_sync for A*, weighted A* and Dijkstra; BFS is always level_sync.
  Scheme scheme = Scheme::async;
  int coarsen_shift = 0;  // ownership hashes coordinates >> k (0 = the state itself)
  int slab_width = 0;     // > 0: ownership by slabs of this width along the last axis instead
  // Non-empty: ownership by prefix cuts instead (partition/ownership.hpp), ranks - 1 positions.
  std::vector<std::uint32_t> prefix_cuts;
  std::size_t batch = 512;
  double batch_age_ms = 0.5;
  std::uint64_t sync_every = 4096;
  int sent_filter_log2 = 16;    // duplicate filter on outgoing records (0 = off)
  bool compare_serial = false;  // rank 0 also solves serially first, for overhead and speedup
  // Fault injection for the failure tests (DistOptions::fail_after_expansions): rank
  // `fault_rank` throws (or, with fault_kill, is killed) after `fault_after` expansions;
  // 0 expansions: never.
  int fault_rank = -1;
  std::uint64_t fault_after = 0;
  bool fault_kill = false;
};

Scheme parse_scheme(std::string_view name);  // InputError if unknown
std::string_view to_string(Scheme s);

// InputError for impossible distributed options; with the lattice's extent, also for slabs
// wider than it and prefix cuts outside it; with the rank count, also for cuts that do not
// number one fewer.
void validate(const DistGridOptions& options, int extent = 0, int ranks = 0, int dims = 2);

GridReport solve_grid_distributed(const GridProblem& problem, const GridSearchOptions& options,
                                  const DistGridOptions& dist, const mpi::Communicator& comm);

// The steps both distributed planners (the lattices', the configuration spaces') share: the
// state budget per rank (a user's --max-states is the job's total, split; a derived one is
// already per rank, and the report then shows the job's), and the engine's options for this rank
// (BFS always level-synchronous; the fault injection on its rank; yielding when oversubscribed).
std::uint64_t per_rank_budget(const GridSearchOptions& options, GridReport& report, int ranks);
DistOptions rank_options(GridAlgorithm algorithm, const DistGridOptions& dist,
                         const mpi::Communicator& comm);

// The same on a configuration space (GridProblem::cspace, plan/cspace_planner.hpp): hashed
// ownership only; solve_grid_distributed hands such a problem here.
GridReport solve_cspace_distributed(const GridProblem& problem, const GridSearchOptions& options,
                                    const DistGridOptions& dist, const mpi::Communicator& comm);

// The distance field (plan/distance_field.hpp) over the ranks' slabs of the dense engine: every
// rank fills its slab's cells, rank 0 gathers them; threads and memory budget agreed as above.
// Collective; the field is whole on rank 0 only.
DistanceFieldRun distance_field_distributed(const GridProblem& problem,
                                            const GridSearchOptions& options,
                                            const mpi::Communicator& comm);

}  // namespace hpcplan::distributed
