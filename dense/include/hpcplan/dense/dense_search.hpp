#pragma once
// The dense lattice engine: exhaustive searches of the whole GOG lattice at one bit per state,
// whole 64-bit tiles per operation (tile_moves.hpp).
//
//   BFS: level-synchronous. A state's 2-bit code is 0 (not reached) or its level mod 3 + 1, so
//   the path is walked back from the goal (a predecessor of a level-L state has level L - 1,
//   and neighbours' levels differ by at most one, so level mod 3 tells it apart). Frontiers are
//   lists of (tile, bits) entries, deduplicated by one mark bit per tile.
//
//   Dijkstra: every move costs sqrt k for k axes, so a path cost is a + b sqrt2 + c sqrt3 with
//   integers (graph/lattice_cost.hpp): equal costs are equal exactly, and the states of one cost
//   value form one "class". Classes are processed in increasing value; a state settles in the
//   first class that holds it, which is its cost, because every class still pending is at least
//   as large (a processed class only creates classes larger by a move's cost, >= 1). Classes are
//   processed in buckets [k, k + 1): no state of a bucket can reach another state of the same
//   bucket (every move costs at least 1), so the states of a bucket settle in one pass, and the
//   ranks and threads exchange once per bucket. Memory: a settled bit per state, the pending
//   classes' lists, and, with a path, the settling class of every state (8 bytes).
//
// Slabs along the last axis: each rank holds the layers of one slab (slab_plan.hpp) and sends
// the targets that fall in a neighbour's slab to it once per level or bucket
// (slab_transport.hpp); within a rank, each OpenMP thread owns a sub-slab, and targets in
// another thread's sub-slab go through the same kind of outbox, applied by their owner after a
// barrier, so no word is written by two threads and no atomics are used. Results (status,
// cost, hops, path, counters) do not depend on the number of ranks or threads.
//
// Threads: search() uses `threads` OpenMP threads inside; the field may be shared read-only.
#include <cstdint>
#include <string>
#include <vector>

#include "hpcplan/core/result.hpp"
#include "hpcplan/core/stop.hpp"
#include "hpcplan/dense/dense_checkpoint.hpp"
#include "hpcplan/dense/slab_transport.hpp"
#include "hpcplan/env/obstacle_source.hpp"
#include "hpcplan/graph/lattice_graph.hpp"

namespace hpcplan::dense {

enum class Algorithm { bfs, dijkstra };

// A distance field's part on one rank (Query::distances): the value of every cell whose last
// coordinate lies in the layers this rank holds, in grid order (axis 0 fastest, over the
// field's own shape, ObstacleSource::size), -1 where no state was reached or settled (blocked,
// unreachable). The rank's cells are runs of consecutive grid-order indices (one per block of
// layers, in block order), their values concatenated in `levels` or `costs`.
struct Distances {
  struct Run {
    std::uint64_t first = 0, count = 0;
  };
  std::vector<Run> runs;
  std::vector<std::int32_t> levels;  // BFS: the state's level (hop count)
  std::vector<float> costs;          // Dijkstra: its exact cost (LatticeCost), as float
  std::uint64_t cells() const {
    std::uint64_t n = 0;
    for (const Run& r : runs) n += r.count;
    return n;
  }
};

struct Query {
  std::vector<int> start, goal;  // free lattice states
  Algorithm algorithm = Algorithm::bfs;
  Connectivity connectivity = Connectivity::seed_pairs;
  int threads = 1;  // OpenMP threads of this rank (>= 1)
  // Sections per block dealt round the ranks and threads (a section is a layer along the last
  // axis while there are enough of them for every worker, else a piece of a layer: see
  // Figures::cut_axis); 0: one contiguous slab per rank and thread, balanced by free states;
  // < 0: about 4 blocks per thread, at least 4 sections each (the default).
  int block_sections = -1;
  bool keep_path = false;           // Dijkstra: record classes and walk the path back
                                    // (BFS always walks it, for its cost, and returns it)
  std::uint64_t memory_budget = 0;  // bytes this rank may use; 0 = no limit
  Stop stop;                        // polled between chunks of a level or class
  std::string progress_label;       // non-empty: progress lines (HPCPLAN_PROGRESS=1 or
  double progress_after_s = 2.0;    // a terminal) once the run passes this many seconds
  Checkpointing checkpointing;      // writing checkpoints, restarting from one
  // Set: a distance-field run. The search does not stop at the goal: it settles every state
  // the start reaches and writes each one's value into this rank's part (filled by search()),
  // per level or class, for the states it settles (no extra pass). The goal is still reported
  // (solved, with its cost and hops, if reached). No checkpoints with it.
  Distances* distances = nullptr;
};

// What the engine did beyond the counters.
struct Figures {
  int in_tile_axes = 2;              // 2: 8 x 8 tiles on axes 0 and 1; 1: rows of 64 on axis 0
  std::uint64_t tiles = 0;           // tiles of the whole lattice
  std::uint64_t free_states = 0;     // free states of the whole lattice (exact)
  std::uint64_t reached = 0;         // states reached (BFS) or settled (Dijkstra)
  std::uint64_t bytes_per_rank = 0;  // the most any rank allocated (its slab's store, marks,
                                     // window table, frontier lists at their peak)
  std::uint64_t bytes_total = 0;     // summed over ranks
  std::uint64_t bytes_needed = 0;    // this rank's planned bytes before the run (the check)
  std::uint64_t table_bytes = 0;     // of which the window table (every rank holds one)
  std::uint64_t levels = 0;          // BFS levels, or the Dijkstra cost classes processed
  std::uint64_t buckets = 0;         // Dijkstra buckets (exchanges)
  // The active set: tiles worked on in each step (BFS level: tiles swept with states of the
  // level; Dijkstra bucket: class entries taken), over every rank, and their sum. A BFS tile
  // moves 3 words of store (its level code and pending states) in and out per visit: the
  // engine's traffic floor is about active_tiles x 48 bytes (bench/dense_floor.py).
  std::vector<std::uint64_t> step_active_tiles;
  std::uint64_t active_tiles = 0;
  int threads = 1;
  int ranks = 1;
  // The decomposition: blocks are runs of sections, the tiles sharing their coordinates on
  // the cut axis and every axis above it (a layer when the cut is the last axis; a row of a
  // layer when it is the one below).
  int cut_axis = 0;
  int block_sections = 0;           // sections per dealt block; 0: contiguous slabs
  int blocks = 1;                   // blocks of sections
  std::vector<int> rank_sections;   // sections each rank holds
  std::vector<int> rank_peers;      // the ranks each rank trades halos with
  std::uint64_t halo_messages = 0;  // summed over ranks
  std::uint64_t halo_bytes = 0;
  double exchange_ms = 0.0;            // the slowest rank's time in exchanges and reductions
  std::vector<double> rank_search_ms;  // per rank
  std::vector<std::uint64_t> rank_expanded;
};

struct Result : hpcplan::Result<std::vector<int>> {
  Figures figures;
};

// The bytes a rank of `ranks` will allocate for this query before its lists grow (the store,
// marks, window table and a first frontier reserve); the largest uint64 when the lattice has
// more tiles than TileLayout::kMaxTiles.
std::uint64_t planned_bytes(const ObstacleSource& field, const Query& query, int ranks);

// The decomposition a run of this query on `ranks` ranks (of query.threads threads each) would
// use, rank by rank, computed without allocating the lattice: for sizing a job (memory per
// rank, halo per level) before submitting it, and for the scaling model
// (bench/dense_blocks.py).
struct RankPlan {
  std::uint64_t tiles = 0;          // tiles it holds
  int sections = 0;                 // sections it holds
  int peers = 0;                    // ranks it trades halos with
  std::uint64_t ghost_tiles = 0;    // tiles of other ranks next to its own: a step sends at
                                    // most one 16-byte entry (BFS) per tile of them
  std::uint64_t planned_bytes = 0;  // what planned_bytes() counts, for this rank
};
struct Decomposition {
  int cut_axis = 0;
  std::uint64_t section_tiles = 0;
  int block_sections = 0;
  int blocks = 0;
  std::uint64_t free_states = 0;  // of the whole lattice
  std::vector<RankPlan> ranks;
};
Decomposition describe_decomposition(const ObstacleSource& field, const Query& query, int ranks);

// The largest lattice dimension this build compiled the engine for: 16 unless it was configured
// with -DHPCPLAN_DENSE_DIMS=N (search() refuses a higher one; --engine auto picks sparse there).
int compiled_dims();

// The CPUs this process may run the engine's threads on: its affinity mask (core/cpu_set.hpp),
// or, when OpenMP binds its threads (OMP_PROC_BIND, OMP_PLACES: the runtime then pins the
// calling thread to the first place before main runs, so its mask shows one CPU), every CPU
// of its places. At least 1.
int usable_cpus();

// InputError naming the build option when `dims` is over compiled_dims(). Callers that run on
// several ranks call it before any rank communicates, so that all refuse together.
void require_compiled(int dims);

// Runs the query on this rank's slab; collective over the transport's ranks. InputError if the
// lattice's dimension is not compiled (require_compiled), if the planned bytes exceed the
// budget (one line naming both), before anything large is allocated, or if a rank's restart
// checkpoint is refused (every rank throws it, with that rank's
// message). RunError if a checkpoint cannot be written.
Result search(const ObstacleSource& field, const Query& query, SlabTransport& transport);

}  // namespace hpcplan::dense
