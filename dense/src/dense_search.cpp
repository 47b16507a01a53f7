#include "hpcplan/dense/dense_search.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "engine_dims.hpp"
#include "hpcplan/core/cpu_set.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/format.hpp"

namespace hpcplan::dense {
namespace {

// The dimensions compiled: all (16) unless a build asks for fewer (HPCPLAN_DENSE_DIMS): each
// has its translation unit (engine_dims.hpp), generated for these dimensions only. The grid
// checkpoint's fuzz target (tests/fuzz) runs a 3D lattice only and compiles the first three.
#ifndef HPCPLAN_DENSE_COMPILED_DIMS
#define HPCPLAN_DENSE_COMPILED_DIMS 16
#endif
constexpr int kCompiledDims = HPCPLAN_DENSE_COMPILED_DIMS;

// 8 x 8 tiles unless their window table would pass this; rows of 64 then (1D always).
constexpr std::uint64_t kMaxSquareTable = std::uint64_t{32} << 20;

using detail::max_word_steps;

int in_tile_axes(const ObstacleSource& field, const Query& q) {
  const int dims = field.dims();
  if (dims == 1) return 1;
  // An occupancy table is 9 words per tile either way: 8 x 8 tiles, the better shape.
  if (field.is_occupancy()) return 2;
  // Rows only where they are compiled for (wide 2D and 3D lattices); from 4D a lattice wide
  // enough to need them does not fit any budget anyway.
  if (dims > 3) return 2;
  const TileLayout square(dims, field.extent(), 2);
  return FreeWindows::table_bytes(field, square, max_word_steps(q, dims)) <= kMaxSquareTable ? 2
                                                                                             : 1;
}

}  // namespace

namespace {

// A rank's bytes before its lists grow, for `tiles` tiles of the query's store.
std::uint64_t rank_bytes(const Query& q, std::uint64_t table_bytes, std::uint64_t tiles,
                         std::uint64_t section_tiles) {
  std::uint64_t bytes = table_bytes;
  if (q.algorithm == Algorithm::bfs) {
    bytes += detail::LevelBfs<2, 2, detail::SeedKernel<2, 2>>::store_bytes(tiles);
  } else {
    bytes +=
        detail::CostClassDijkstra<2, 2, detail::SeedKernel<2, 2>>::store_bytes(tiles, q.keep_path);
  }
  // A distance field's part: a 4-byte value per state of the rank's slab.
  if (q.distances) bytes += tiles * 64 * 4;
  // A first frontier: one section's tiles as entries.
  bytes += section_tiles * sizeof(detail::Entry);
  return bytes;
}

}  // namespace

Decomposition describe_decomposition(const ObstacleSource& field, const Query& q, int ranks) {
  const int dims = field.dims();
  ranks = std::max(1, ranks);
  if (!TileLayout::fits(dims, field.extent(), in_tile_axes(field, q)))
    throw InputError("the lattice has more than 2^50 tiles: the dense engine cannot hold it");
  const TileLayout layout(dims, field.extent(), in_tile_axes(field, q));
  const std::uint64_t table = FreeWindows::table_bytes(field, layout, max_word_steps(q, dims));
  Decomposition d;
  double free = 0.0;
  for (const double w : free_states_per_layer(field, layout)) free += w;
  d.free_states = static_cast<std::uint64_t>(free + 0.5);
  for (int r = 0; r < ranks; ++r) {
    const detail::SlabMap plan =
        detail::plan_slabs(field, layout, r, ranks, std::max(1, q.threads), q.block_sections);
    d.cut_axis = plan.cut_axis;
    d.section_tiles = plan.section_tiles;
    d.block_sections = plan.block_sections;
    d.blocks = static_cast<int>(plan.blocks.size());
    RankPlan p;
    p.tiles = plan.store_tiles;
    p.sections = plan.rank_sections[r];
    p.peers = static_cast<int>(plan.peers.size());
    p.ghost_tiles = plan.ghost_sections * plan.section_tiles;
    p.planned_bytes = table == std::numeric_limits<std::uint64_t>::max()
                          ? table
                          : rank_bytes(q, table, plan.store_tiles, plan.section_tiles);
    d.ranks.push_back(p);
  }
  return d;
}

std::uint64_t planned_bytes(const ObstacleSource& field, const Query& q, int ranks) {
  const int dims = field.dims();
  if (!TileLayout::fits(dims, field.extent(), in_tile_axes(field, q)))
    return std::numeric_limits<std::uint64_t>::max();
  const TileLayout layout(dims, field.extent(), in_tile_axes(field, q));
  // The rank holding the most tiles under the plan the run will use.
  std::uint64_t tiles = 0, section_tiles = 0;
  for (int r = 0; r < std::max(1, ranks); ++r) {
    const detail::SlabMap plan = detail::plan_slabs(field, layout, r, std::max(1, ranks),
                                                    std::max(1, q.threads), q.block_sections);
    tiles = std::max(tiles, plan.store_tiles);
    section_tiles = plan.section_tiles;
  }
  const std::uint64_t table = FreeWindows::table_bytes(field, layout, max_word_steps(q, dims));
  if (table == std::numeric_limits<std::uint64_t>::max()) return table;
  return rank_bytes(q, table, tiles, section_tiles);
}

int usable_cpus() {
  const int places = omp_get_num_places();
  if (places <= 0) return CpuSet::of_this_process().count();
  std::vector<int> ids;
  for (int p = 0; p < places; ++p) {
    std::vector<int> in(static_cast<std::size_t>(omp_get_place_num_procs(p)));
    omp_get_place_proc_ids(p, in.data());
    ids.insert(ids.end(), in.begin(), in.end());
  }
  std::sort(ids.begin(), ids.end());
  return std::max(1, static_cast<int>(std::unique(ids.begin(), ids.end()) - ids.begin()));
}

int compiled_dims() {
  return kCompiledDims;
}

void require_compiled(int dims) {
  if (dims > kCompiledDims)
    throw InputError("this build compiles the dense engine for 1 to " +
                     std::to_string(kCompiledDims) + " dimensions (HPCPLAN_DENSE_DIMS), not " +
                     std::to_string(dims) + "; use --engine sparse");
}

Result search(const ObstacleSource& field, const Query& asked, SlabTransport& tr) {
  // A build configured with -DHPCPLAN_DENSE_DIMS=N < 16: every rank runs the same build, so
  // all refuse together.
  require_compiled(field.dims());
  // Every rank must deal the same blocks to the same number of threads and refuse or accept
  // together, while each knows only its own limits: all take the smallest thread count any
  // rank can start (its OpenMP thread limit; one thread when called inside another parallel
  // region without nesting) and the smallest budget.
  Query q = asked;
  int threads = std::min(std::max(1, q.threads), omp_get_thread_limit());
  if (omp_in_parallel() && omp_get_active_level() >= omp_get_max_active_levels()) threads = 1;
  double agreed[2] = {static_cast<double>(threads), q.memory_budget > 0
                                                        ? static_cast<double>(q.memory_budget)
                                                        : std::numeric_limits<double>::infinity()};
  tr.min(agreed);
  q.threads = static_cast<int>(agreed[0]);
  q.memory_budget =
      std::isfinite(agreed[1]) ? static_cast<std::uint64_t>(std::min(agreed[1], 1.8e19)) : 0;
  if (q.start.size() != static_cast<std::size_t>(field.dims()) ||
      q.goal.size() != static_cast<std::size_t>(field.dims()))
    throw std::logic_error("dense::search: start and goal need one coordinate per axis");
  if (!field.is_free(q.start) || !field.is_free(q.goal))
    throw std::logic_error("dense::search: start and goal must be free");
  if (q.distances && (!q.checkpointing.path.empty() || !q.checkpointing.restart.empty()))
    throw std::logic_error("dense::search: a distance field takes no checkpoints");
  if (q.connectivity == Connectivity::full && field.dims() > kMaxFullConnectivityDims)
    throw std::logic_error("dense::search: full connectivity is limited to d <= 4");
  const std::uint64_t needed = planned_bytes(field, q, tr.ranks());
  if (needed == std::numeric_limits<std::uint64_t>::max())
    throw InputError(field.is_occupancy()
                         ? std::string("the array's bounding hypercube is too large for the dense "
                                       "engine's window table (over 2^31 / 9 padded tiles); use "
                                       "--engine sparse")
                         : std::string("the lattice is too large for the dense engine (over 2^50 "
                                       "tiles of 64 states); use --engine sparse"));
  if (q.memory_budget > 0 && needed > q.memory_budget)
    throw InputError("the dense engine needs " + format_bytes(needed) + " per rank (" +
                     std::to_string(needed) + " bytes) for this lattice, over the budget of " +
                     format_bytes(q.memory_budget) + " (" + std::to_string(q.memory_budget) +
                     " bytes); raise --memory-budget, use more ranks, or --engine sparse");
  const int k = in_tile_axes(field, q);
  switch (field.dims()) {
#define HPCPLAN_DENSE_DIMS(d)                                                      \
  case d:                                                                          \
    if constexpr (d <= kCompiledDims) return detail::run_dims<d>(field, q, tr, k); \
    break;
    HPCPLAN_DENSE_DIMS(1)
    HPCPLAN_DENSE_DIMS(2)
    HPCPLAN_DENSE_DIMS(3)
    HPCPLAN_DENSE_DIMS(4)
    HPCPLAN_DENSE_DIMS(5)
    HPCPLAN_DENSE_DIMS(6)
    HPCPLAN_DENSE_DIMS(7)
    HPCPLAN_DENSE_DIMS(8)
    HPCPLAN_DENSE_DIMS(9)
    HPCPLAN_DENSE_DIMS(10)
    HPCPLAN_DENSE_DIMS(11)
    HPCPLAN_DENSE_DIMS(12)
    HPCPLAN_DENSE_DIMS(13)
    HPCPLAN_DENSE_DIMS(14)
    HPCPLAN_DENSE_DIMS(15)
    HPCPLAN_DENSE_DIMS(16)
#undef HPCPLAN_DENSE_DIMS
  }
  throw std::logic_error("dense::search: dims out of range");
}

}  // namespace hpcplan::dense
