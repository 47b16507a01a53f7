#pragma once
// Solves a GridProblem with the serial engine and reports everything a user or a later
// analysis needs: the problem as actually solved (adjusted start/goal, threshold, density),
// the options, the result and its counters.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/plan/grid_problem.hpp"
#include "hpcplan/search/search_result.hpp"

namespace hpcplan {

// What a grid run reports, in four parts: the problem as solved (adjusted start and goal,
// threshold, density), the options as run, how the work was spread over ranks, and the one
// Result (path of lattice states, cost, hops, counters). A distributed run with
// --compare-serial adds the serial engine's figures for the same problem.

// The problem as solved.
struct GridProblemReport {
  // What was planned on: "gog" (then seed, threshold and shifts describe it), or an occupancy
  // grid's format ("movingai", "voxel", "npy", "array") with its name, shape and checksum.
  std::string obstacles = "gog";
  std::string map;
  std::vector<int> shape;
  std::uint64_t map_checksum = 0;
  int dims = 0;
  int extent = 0;
  std::uint64_t seed = 0;
  int threshold = 0;
  double blocked_fraction = 0.0;
  int shift_p = 0;
  int shift_v = 0;
  std::string connectivity;
  std::vector<int> start, goal;
  bool start_adjusted = false, goal_adjusted = false;
  double straight_line = 0.0;  // |goal - start|, the denominator of quality
};

// The search as run.
struct GridOptionsReport {
  std::string algorithm;
  double weight = 1.0;
  std::string heuristic;
  std::uint64_t max_states = 0;
  std::string engine = "sparse";  // sparse (best-first) | dense (bit-parallel lattice)
  int key_words = 1;              // 64-bit words per packed state
  std::string visited_map;        // the state store used
  std::string pruning = "none";   // none | jump_points (2D A*; its path is still unit moves)
};

// How the work was spread over ranks and exchanged.
struct GridDistribution {
  int ranks = 1;
  std::string scheme = "serial";  // serial | async | bulk_sync | level_sync
  int coarsen_shift = 0;
  int slab_width = 0;  // > 0: ownership by slabs of this width along the last axis
  std::vector<std::uint32_t> prefix_cuts;  // non-empty: ownership by prefix cuts
  std::uint64_t batch = 0;
  double batch_age_ms = 0.0;
  std::uint64_t sync_every = 0;
  std::vector<search::RankCounters> per_rank;
};

// The serial engine on the same problem, run first by rank 0 (--compare-serial).
struct SerialReference {
  search::Status status = search::Status::no_path;
  double cost = 0.0;
  std::uint64_t hops = 0;
  std::uint64_t expanded = 0;
  double time_ms = 0.0;
};

// The one Result, plus what is derived from it.
struct GridResult : Result<std::vector<int>> {
  double quality = 0.0;  // cost / straight_line (seed 002 eq. 2)
  double setup_ms = 0.0;
};

// The report's part about the space (GridReport::cspace).
struct CSpaceReport {
  std::string world;  // the space's name ("chain", "hypercube", a user's)
  int cells = 0;
  std::string moves;
  double resolution = 0.0;
  std::vector<bool> periodic;
  std::vector<double> start, goal;                       // as asked, in the space's coordinates
  std::vector<double> start_vertex, goal_vertex;         // where they joined the lattice
  double start_connection = 0.0, goal_connection = 0.0;  // those motions' lengths
  std::string unconnected;                // "start" or "goal" when one joined nothing
  std::vector<std::vector<double>> path;  // keep_path: start, vertices, goal
  bool path_rechecked = false;
  std::uint64_t batches = 0;  // batches of states tested (this rank's, or the sum)
};

struct GridReport {
  GridProblemReport problem;
  GridOptionsReport options;
  GridDistribution distribution;
  GridResult result;
  std::optional<SerialReference> serial;
  std::optional<dense::Figures> dense;  // the dense engine's own figures, when it ran
  std::optional<CSpaceReport> cspace;   // the configuration space's part, when it planned on one
  // Checkpoints (set by the command line): the files continued from and written (the user's
  // FILE; one per rank), and the signal that interrupted the run ("SIGUSR1", ...).
  std::string restarted_from, checkpoint, interrupted_by;
};

// The serial search. Its visited map is chosen by the lattice's size: where the packed keys fit
// kDenseVisitedBits bits (2^26 states: 2D up to extent 8192, 3D up to 256), flat arrays
// indexed by the key, reused across runs (search/stamped_dense_map.hpp); else a hash map.
// The report's visited_map names the one used.
inline constexpr int kDenseVisitedBits = 26;
bool dense_visited_fits(int dims, int extent);
GridReport solve_grid(const GridProblem& problem, const GridSearchOptions& options);
// What a problem plans on: its occupancy grid, or its GOG field, built into `gog`.
ObstacleSource obstacles_of(const GridProblem& problem, std::optional<GogField>& gog);
// The same on a field already built (problem.gog must be its parameters, or problem.occupancy
// the grid): a planner solving many queries on one field (the OMPL adapter, a scenario run)
// builds it once.
GridReport solve_grid(const ObstacleSource& field, const GridProblem& problem,
                      const GridSearchOptions& options);

// The parts of solving every engine shares (serial and distributed): describes the problem
// and options in a report, resolves start and goal (InputError if blocked), and sets the
// state budget. The derived budget (half of available memory) is split among
// `ranks_sharing_memory` processes.
GridReport prepare_grid_report(const GridProblem& problem, const GridSearchOptions& options,
                               const ObstacleSource& field, int ranks_sharing_memory);
// The dense engine: its memory budget per process (--memory-budget, else what max_states buys
// the sparse engine), its OpenMP threads per process (--threads, else the process's share of
// the CPUs it may run on: its CPU set's count (core/cpu_set.hpp) over `ranks_sharing_cpus`,
// the ranks of its node whose sets overlap its own, mpi::Communicator::ranks_sharing_cpus; 1
// for a serial run), whether `ranks` slabs fit the budget, whether it runs this query (--engine
// dense, or auto for BFS and Dijkstra when they fit and the dimension is compiled: see
// dense::compiled_dims), and a run on this process's slab,
// collective over the transport, filling the report (its path re-validated move by move with
// the lattice graph).
std::uint64_t dense_memory_budget(const GridSearchOptions& options, const GridReport& report);
int dense_threads(const GridSearchOptions& options, int ranks_sharing_cpus);
// The threads a dense run on `field` uses: --threads when given; else one per
// kDenseStatesPerThreadLevel states of the average level (the free states over the extent: a
// wavefront crosses the lattice in about `extent` levels), at least one and at most
// dense_threads(). Each level or cost bucket ends at two to four barriers; a 2D map's level is a
// few hundred states (microseconds of work), so extra threads only wait there, and where the
// cores are shared with other processes a waiting thread that spins holds up the one doing the
// work (measured on a busy 2-core VM: 64room_005's Dijkstra field 34 ms on one thread, 5.0 s on
// two). Large lattices (3D and up, GOG's high dimensions) keep every core.
inline constexpr double kDenseStatesPerThreadLevel = 32768;
int dense_threads(const ObstacleSource& field, const GridSearchOptions& options,
                  int ranks_sharing_cpus);
// The dense engine's query for a prepared report (its resolved start and goal), built in this
// one place for every dense run (point queries, distance fields, the budget check): the
// checkpoint files are the job's, which the engine names per rank.
dense::Query dense_query(const ObstacleSource& field, const GridProblem& problem,
                         const GridSearchOptions& options, const GridReport& report,
                         int ranks_sharing_cpus);
bool dense_fits(const ObstacleSource& field, const GridProblem& problem,
                const GridSearchOptions& options, const GridReport& report, int ranks);
bool uses_dense_engine(const ObstacleSource& field, const GridProblem& problem,
                       const GridSearchOptions& options, const GridReport& report, int ranks);
void run_dense(const ObstacleSource& field, const GridProblem& problem,
               const GridSearchOptions& options, dense::SlabTransport& transport,
               int ranks_sharing_cpus, GridReport& report);

// Derives quality from cost once the search has filled the result.
void finish_grid_report(GridReport& report);
// Workload deviation of seed 002 Table IV: max - min of the ranks' shares of expansions, in
// percent (0 for one rank or no expansions).
double workload_deviation_percent(const std::vector<search::RankCounters>& per_rank);

}  // namespace hpcplan
