#pragma once
// The dense engine for one lattice dimension D: the move kernel picked for the rule, the
// engine (level BFS or cost-class Dijkstra) run over the slab, and the figures filled in.
// run_dims<D> is instantiated once per dimension, each in a translation unit of its own that
// dense/CMakeLists.txt generates (engine_d<D>.cpp, for the dimensions the build compiles):
// one file holding every dimension was the project's longest compile (over half an hour of one
// core with clang under ASan), and 16 small ones spread over the build's cores. Every other
// file sees the extern declarations at the end and links those instantiations.
#include <algorithm>
#include <cstdint>
#include <span>

#include "cost_class_dijkstra.hpp"
#include "engine_common.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "level_bfs.hpp"

namespace hpcplan::dense::detail {

// The unrolled seed-rule kernel up to this many dimensions; the move table beyond.
inline constexpr int kMaxSeedKernelDims = 8;

// How many axes one move may change: all with full connectivity, two under the seed rule.
inline int max_word_steps(const Query& q, int dims) {
  return q.connectivity == Connectivity::full ? dims : 2;
}

template <int D, int K>
struct SeedKernel {
  template <bool kSplit, class Out>
  [[gnu::always_inline]] std::uint64_t expand(Word f, const FreeWindows::At& at, int stride,
                                              const std::int64_t* W, Out&& out) const {
    return SeedMoves<D, K>::template expand<kSplit>(f, at, stride, W, out);
  }
};

template <int K>
struct TableKernel {
  const TableMoves& table;
  template <bool kSplit, class Out>
  std::uint64_t expand(Word f, const FreeWindows::At& at, int stride, const std::int64_t* W,
                       Out&& out) const {
    return table.template expand<K, kSplit>(f, at, stride, W, out);
  }
};

template <int D, int K, class Kernel>
Result run_engine(const ObstacleSource& field, const Query& q, SlabTransport& tr,
                  const TileLayout& layout, const FreeWindows& windows, const Kernel& kernel,
                  const SlabMap& slabs, std::uint64_t free_states) {
  if (q.algorithm == Algorithm::bfs) {
    LevelBfs<D, K, Kernel> bfs(field, q, tr, layout, windows, kernel, slabs, free_states);
    return run_supersteps(bfs, field, q, tr, slabs, free_states);
  }
  CostClassDijkstra<D, K, Kernel> dijkstra(field, q, tr, layout, windows, kernel, slabs,
                                           free_states);
  return run_supersteps(dijkstra, field, q, tr, slabs, free_states);
}

template <int D, int K>
Result run_shape(const ObstacleSource& field, const Query& q, SlabTransport& tr) {
  const TileLayout layout(D, field.extent(), K);
  const FreeWindows windows(field, layout, max_word_steps(q, D));
  const SlabMap slabs =
      plan_slabs(field, layout, tr.rank(), tr.ranks(), std::max(1, q.threads), q.block_sections);
  double free = 0.0;
  for (double w : free_states_per_layer(field, layout)) free += w;
  const auto free_states = static_cast<std::uint64_t>(free + 0.5);
  Result r;
  if constexpr (D > kMaxSeedKernelDims) {
    // Beyond 8D the seed rule runs from the move table: the unrolled kernel's code grows with
    // d^2 and its compile time faster (8D: 19 s for one translation unit; 16D would be minutes),
    // for lattices that are rarely wide enough to be worth it.
    const TableMoves table(layout, 2);
    r = run_engine<D, K>(field, q, tr, layout, windows, TableKernel<K>{table}, slabs, free_states);
  } else {
    if constexpr (D <= kMaxFullConnectivityDims) {
      if (q.connectivity == Connectivity::full) {
        const TableMoves table(layout, D);
        r = run_engine<D, K>(field, q, tr, layout, windows, TableKernel<K>{table}, slabs,
                             free_states);
      }
    }
    if (q.connectivity != Connectivity::full)
      r = run_engine<D, K>(field, q, tr, layout, windows, SeedKernel<D, K>{}, slabs, free_states);
  }
  Figures& f = r.figures;
  f.in_tile_axes = K;
  f.tiles = layout.tile_count();
  f.threads = slabs.threads;
  f.ranks = tr.ranks();
  f.cut_axis = slabs.cut_axis;
  f.rank_sections = slabs.rank_sections;
  f.block_sections = slabs.block_sections;
  f.rank_peers = gather_ranks(tr, static_cast<int>(slabs.peers.size()));
  f.blocks = static_cast<int>(slabs.blocks.size());
  f.table_bytes = windows.bytes();
  // Every window mask of the table answers 64 validity questions of the field, once.
  r.counters.collision_checks = windows.bytes() / sizeof(Word) * 64;
  f.free_states = free_states;
  std::uint64_t halo[2] = {tr.messages_sent, tr.bytes_sent};
  tr.sum(halo);
  f.halo_messages = halo[0];
  f.halo_bytes = halo[1];
  double ex = tr.exchange_ms;
  double neg = -ex;
  tr.min(std::span<double>(&neg, 1));
  f.exchange_ms = -neg;
  return r;
}

// The engine for D-dimensional lattices with k axes inside a tile (1 or 2; 2 from 4D on).
template <int D>
Result run_dims(const ObstacleSource& field, const Query& q, SlabTransport& tr, int k) {
  if constexpr (D == 1) {
    return run_shape<1, 1>(field, q, tr);
  } else if constexpr (D <= 3) {
    return k == 1 ? run_shape<D, 1>(field, q, tr) : run_shape<D, 2>(field, q, tr);
  } else {
    return run_shape<D, 2>(field, q, tr);
  }
}

#define HPCPLAN_DENSE_EXTERN_DIMS(d) \
  extern template Result run_dims<d>(const ObstacleSource&, const Query&, SlabTransport&, int);
HPCPLAN_DENSE_EXTERN_DIMS(1)
HPCPLAN_DENSE_EXTERN_DIMS(2)
HPCPLAN_DENSE_EXTERN_DIMS(3)
HPCPLAN_DENSE_EXTERN_DIMS(4)
HPCPLAN_DENSE_EXTERN_DIMS(5)
HPCPLAN_DENSE_EXTERN_DIMS(6)
HPCPLAN_DENSE_EXTERN_DIMS(7)
HPCPLAN_DENSE_EXTERN_DIMS(8)
HPCPLAN_DENSE_EXTERN_DIMS(9)
HPCPLAN_DENSE_EXTERN_DIMS(10)
HPCPLAN_DENSE_EXTERN_DIMS(11)
HPCPLAN_DENSE_EXTERN_DIMS(12)
HPCPLAN_DENSE_EXTERN_DIMS(13)
HPCPLAN_DENSE_EXTERN_DIMS(14)
HPCPLAN_DENSE_EXTERN_DIMS(15)
HPCPLAN_DENSE_EXTERN_DIMS(16)
#undef HPCPLAN_DENSE_EXTERN_DIMS

}  // namespace hpcplan::dense::detail
