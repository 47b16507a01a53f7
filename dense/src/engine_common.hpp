#pragma once
// Pieces both dense searches share: the slab this rank and its threads own, frontier entries,
// outboxes to neighbours, the walk back from the goal, and the moves in one fixed order.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/progress.hpp"
#include "hpcplan/core/stop.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/dense/free_windows.hpp"
#include "hpcplan/dense/slab_plan.hpp"
#include "hpcplan/dense/tile_layout.hpp"
#include "hpcplan/dense/tile_moves.hpp"
#include "hpcplan/graph/lattice_cost.hpp"

namespace hpcplan::dense::detail {

// One tile of a frontier or an outbox: its index and a word of states.
struct Entry {
  std::uint64_t tile;
  Word bits;
};

template <class T>
std::span<const std::byte> as_bytes_of(const std::vector<T>& v) {
  return std::as_bytes(std::span<const T>(v.data(), v.size()));
}
template <class T>
void append_bytes(const std::vector<T>& v, std::vector<std::byte>& out) {
  const std::size_t at = out.size();
  out.resize(at + v.size() * sizeof(T));
  if (!v.empty()) std::memcpy(out.data() + at, v.data(), v.size() * sizeof(T));
}
template <class T>
void from_bytes(const std::vector<std::byte>& b, std::vector<T>& out) {
  out.resize(b.size() / sizeof(T));
  if (!b.empty()) std::memcpy(out.data(), b.data(), out.size() * sizeof(T));
}

// Who holds which tiles. The lattice is cut into sections (slab_plan.hpp: the tiles sharing
// their coordinates on the cut axis and every axis above it), and runs of sections into blocks,
// each owned by one thread of one rank, so every block is one run of tile indices:
//   dealt (block_sections > 0): blocks of that many sections dealt round the ranks (block j to
//   rank j mod P), and each rank's blocks round its threads. A BFS wavefront moves through the
//   lattice layer by layer, so one contiguous slab per worker leaves most workers idle in most
//   levels (measured: two threads on contiguous slabs did 73% of their work in parallel, 4D
//   extent 100); dealt blocks give every worker a share of every level.
//   contiguous (block_sections == 0): one slab per rank, balanced by free states, cut into one
//   sub-slab per thread the same way (the seed's layout, for comparison).
// The cut is the last axis while it has layers enough for every worker (kSectionsPerWorker
// each); past that it moves down one axis at a time, so that blocks are pieces of layers
// (pencils: a run of rows of one layer) and the ranks can outnumber the extent of any one
// axis. A move changes each tile coordinate by at most one, so a target lies in a section next
// to its source's on the axes of the cut: the ranks holding those are this rank's peers, the
// only ones it trades halos with (two for a cut along the last axis, up to 3^k - 1 for a cut
// over k axes).
struct Block {
  int s0 = 0, s1 = 0;            // sections
  int rank = 0, thread = 0;      // owner
  std::uint64_t lo = 0, hi = 0;  // tiles
  std::uint64_t store = 0;       // on its rank: offset of tile lo in the rank's store
  std::uint64_t mark = 0;        // on its thread: offset of tile lo in the thread's marks
};

struct SlabMap {
  int rank = 0, ranks = 1;
  int threads = 1;         // this rank's threads (at most one per block it holds)
  int cut_axis = 0;        // the cut: sections share their tile coordinates from this axis up
  int block_sections = 0;  // 0: contiguous slabs
  std::uint64_t section_tiles = 1;
  double section_inverse = 1.0;  // 1 / section_tiles (section_of)
  std::vector<Block> blocks;
  std::vector<int> section_block;           // section -> block
  std::uint64_t store_tiles = 0;            // tiles this rank holds
  std::vector<std::uint64_t> thread_tiles;  // tiles each thread holds
  std::vector<int> rank_sections;           // sections each rank holds
  std::vector<int> peers;                   // the ranks this one trades halos with, ascending
  std::vector<int> peer_slot;               // per rank: its index in peers, or -1
  // Other ranks' sections next to this rank's own: the targets of its outgoing halo (at most
  // one entry per tile of them per step, once merged).
  std::uint64_t ghost_sections = 0;

  // The section of a tile (asked for every target outside its source's block and every entry
  // received): by a double reciprocal and one correction, as TileLayout::tile_coords divides,
  // not by a 64-bit division. Exact: tile indices stay far below 2^53 (TileLayout::kMaxTiles).
  int section_of(std::uint64_t tile) const {
    auto q = static_cast<std::uint64_t>(static_cast<double>(tile) * section_inverse);
    if (q * section_tiles > tile)
      --q;
    else if ((q + 1) * section_tiles <= tile)
      ++q;
    return static_cast<int>(q);
  }
  int block_index_of_tile(std::uint64_t tile) const { return section_block[section_of(tile)]; }
  const Block& of_tile(std::uint64_t tile) const { return blocks[block_index_of_tile(tile)]; }
  bool holds_tile(std::uint64_t tile) const { return of_tile(tile).rank == rank; }
  bool empty() const { return store_tiles == 0; }
};

// A halo entry's target, for merging: entries with equal keys become one (their bits or'ed).
inline std::uint64_t halo_key(const Entry& e) {
  return e.tile;
}
inline std::uint64_t halo_hash(const Entry& e) {
  return e.tile;
}

// A thread's outboxes: the targets it found in blocks it does not own, for each peer rank and
// for each other thread of its rank. Written by their thread during a step's work, read by the
// others (and the master's halo swap) after the barrier that ends it, emptied by their thread
// in the step's next_step().
//
// Targets for a peer are merged as they are found: a ghost tile is reached in one step from
// several of its neighbours (measured before merging: 11 entries per visit of a face tile), so
// a direct-mapped window of recent targets ors a repeat into the entry already listed. It is
// the ghost layer's effect at the cost of a cache-resident table, in each thread (an exact
// sort on the master thread cost more than the BFS's own work on a two-rank 5D run).
template <class Item>
struct Outboxes {
  std::vector<std::vector<Item>> out_peer;  // per peer (SlabMap::peers)
  std::vector<std::vector<Item>> out_local;

  void size_for(const SlabMap& slabs) {
    out_peer.resize(slabs.peers.size());
    out_local.resize(slabs.threads);
    if (!slabs.peers.empty()) window_.assign(std::size_t{1} << kWindowBits, {});
  }
  // Lists e for peer p, or ors it into the entry for the same target listed this step.
  void to_peer(int p, const Item& e) {
    std::vector<Item>& box = out_peer[p];
    Slot& s = window_[(halo_hash(e) * 0x9E3779B97F4A7C15ULL) >> (64 - kWindowBits)];
    if (s.epoch == epoch_ && s.peer == p && halo_key(box[s.index]) == halo_key(e)) {
      box[s.index].bits |= e.bits;
      return;
    }
    s = {static_cast<std::uint32_t>(box.size()), p, epoch_};
    box.push_back(e);
  }
  void clear() {
    for (auto& box : out_peer) box.clear();
    for (auto& box : out_local) box.clear();
    // A new step: the window's slots are stale. After 2^32 steps the epoch wraps, and a slot
    // of the step 2^32 ago would look current, so the window is emptied then.
    if (++epoch_ == 0) {
      std::fill(window_.begin(), window_.end(), Slot{});
      epoch_ = 1;
    }
  }
  std::uint64_t capacity_bytes() const {
    std::size_t n = 0;
    for (const auto& box : out_peer) n += box.capacity();
    for (const auto& box : out_local) n += box.capacity();
    return n * sizeof(Item) + window_.size() * sizeof(Slot);
  }

 private:
  static constexpr int kWindowBits = 12;
  struct Slot {
    std::uint32_t index = 0;
    int peer = -1;
    std::uint32_t epoch = 0;
  };
  std::vector<Slot> window_;
  std::uint32_t epoch_ = 1;
};

// One rank's halo swap, by the master thread between the driver's barriers: the threads'
// outboxes for each peer, as bytes for the transport's exchange; and what arrived, sorted into
// the inboxes of the threads that own its tiles (read by those threads after the next
// barrier).
template <class Item>
struct HaloSwap {
  std::vector<Item> received;

  template <class Threads>
  static void send(const Threads& threads, std::size_t peers,
                   std::vector<std::vector<std::byte>>& to) {
    to.resize(peers);
    for (std::size_t p = 0; p < peers; ++p) {
      to[p].clear();
      for (const Outboxes<Item>& t : threads) append_bytes(t.out_peer[p], to[p]);
    }
  }
  void receive(const SlabMap& slabs, const std::vector<std::vector<std::byte>>& from,
               std::vector<std::vector<Item>>& inbox) {
    for (auto& box : inbox) box.clear();
    for (const std::vector<std::byte>& bytes : from) {
      from_bytes(bytes, received);
      for (const Item& e : received) inbox[slabs.of_tile(e.tile).thread].push_back(e);
    }
  }
};

// The sum of one counter over an algorithm's threads (`field`: a pointer to the member).
template <class Threads, class Field>
std::uint64_t sum_over(const Threads& threads, Field field) {
  std::uint64_t n = 0;
  for (const auto& t : threads) n += t.*field;
  return n;
}

// Every rank's value of v, in rank order (collective).
template <class T>
std::vector<T> gather_ranks(SlabTransport& tr, T v) {
  std::vector<T> out;
  from_bytes(tr.allgather(std::as_bytes(std::span<const T>(&v, 1))), out);
  return out;
}

// Writes a distance-field run's values (Query::distances) for this rank's blocks: each block is
// one run of grid-order cells (its sections' cells inside the field's shape), so a settled state's
// value goes to its run's offset plus its grid index less the run's first. Only the thread that
// owns a block writes its cells (the states it settles), so no two threads share a run.
template <class V>
class DistanceWriter {
 public:
  void init(const ObstacleSource& field, const TileLayout& layout, const SlabMap& slabs,
            Distances& out, std::vector<V>& values) {
    dims_ = layout.dims();
    in_tile_ = layout.in_tile_axes();
    std::int64_t stride = 1;
    for (int a = 0; a < dims_; ++a) {
      side_[a] = layout.side(a);
      stride_[a] = stride;
      stride *= field.size(a);
    }
    const int last = dims_ - 1;
    const std::int64_t rows = field.size(last);
    out.runs.clear();
    base_.assign(slabs.blocks.size(), 0);
    std::int64_t at = 0;
    for (std::size_t j = 0; j < slabs.blocks.size(); ++j) {
      const Block& b = slabs.blocks[j];
      if (b.rank != slabs.rank) continue;
      std::uint64_t first = 0, count = 0;
      if (slabs.cut_axis == last) {
        const std::int64_t lo = std::min(rows, b.s0 * side_[last]);
        const std::int64_t hi = std::min(rows, b.s1 * side_[last]);
        first = static_cast<std::uint64_t>(lo * stride_[last]);
        count = static_cast<std::uint64_t>((hi - lo) * stride_[last]);
      } else {
        // Sections of one cell per axis: those inside the grid's shape are consecutive runs of
        // the axes below the cut, in the grid's order too.
        bool any = false;
        for (int s = b.s0; s < b.s1; ++s) {
          std::uint64_t rest = static_cast<std::uint64_t>(s), cell = 0;  // its first cell
          bool inside = true;
          for (int a = slabs.cut_axis; a < dims_; ++a) {
            const auto c = static_cast<std::int64_t>(rest % layout.tiles(a));
            rest /= layout.tiles(a);
            inside = inside && c < field.size(a);
            cell += static_cast<std::uint64_t>(c * stride_[a]);
          }
          if (!inside) continue;
          if (!any) first = cell;
          any = true;
          count += static_cast<std::uint64_t>(stride_[slabs.cut_axis]);
        }
      }
      base_[j] = at - static_cast<std::int64_t>(first);
      if (count) out.runs.push_back({first, count});
      at += static_cast<std::int64_t>(count);
    }
    values.assign(static_cast<std::size_t>(at), V(-1));
    values_ = values.data();
  }
  // The states `bits` of `tile` (in block j of this rank) have the value v.
  void write(const TileLayout& layout, int j, std::uint64_t tile, Word bits, V v) const {
    int t[kMaxDims];
    layout.tile_coords(tile, t);
    std::int64_t i = base_[j];
    for (int a = 0; a < dims_; ++a) i += static_cast<std::int64_t>(t[a]) * side_[a] * stride_[a];
    V* const out = values_ + i;
    if (in_tile_ == 1) {
      for (Word w = bits; w; w &= w - 1) out[std::countr_zero(w)] = v;
    } else {
      const std::int64_t row = stride_[1];
      for (Word w = bits; w; w &= w - 1) {
        const int bit = std::countr_zero(w);
        out[(bit & 7) + (bit >> 3) * row] = v;
      }
    }
  }

 private:
  int dims_ = 1, in_tile_ = 1;
  std::array<std::int64_t, kMaxDims> side_{}, stride_{};
  std::vector<std::int64_t> base_;  // per block: its run's offset less its first grid index
  V* values_ = nullptr;
};

// Blocks of about this many per worker when block_sections is left to the engine (< 0).
inline constexpr int kBlocksPerWorker = 4;
// The cut moves below the last axis while it has fewer sections than this per worker.
inline constexpr int kSectionsPerWorker = 4 * kBlocksPerWorker;

// The cut spans at most this many axes (the last ones).
inline constexpr int kMaxCutAxes = 6;

// The cut axis for `workers` ranks x threads: the last axis, or the highest one below it (of
// one cell per tile, within the last kMaxCutAxes) whose sections number at least
// kSectionsPerWorker per worker, or the lowest it may take.
int cut_axis_for(const TileLayout& layout, int workers);

SlabMap plan_slabs(const ObstacleSource& field, const TileLayout& layout, int rank, int ranks,
                   int threads, int block_sections);

// The lattice moves as coordinate offsets, in one fixed order (the walk back picks the first
// legal predecessor in it, so paths do not depend on ranks or threads): one-axis steps, then
// two-axis steps (the seed rule), or every offset in {-1,0,1}^d but 0 (full connectivity).
std::vector<std::array<int, kMaxDims>> move_offsets(int dims, Connectivity c);

// Whether from -> from + offset is a legal move, from the field formula alone (every corner of
// the spanned unit cube free, inside the box); its axis count, or 0.
int legal_move(const ObstacleSource& field, const int* from, const std::array<int, kMaxDims>& o);

// Progress on stderr for runs over 2 s: the level or class, states reached of the lattice's
// free states, the rate and the time left at that rate.
class DenseProgress {
 public:
  DenseProgress(std::string label, double after_s, std::uint64_t free_states)
      : label_(std::move(label)), after_s_(after_s), free_(free_states) {}
  void update(const char* unit, double at, std::uint64_t reached);

 private:
  std::string label_;
  double after_s_;
  std::uint64_t free_;
  double last_ = -1.0;
  Stopwatch clock_;
  ProgressLine line_;
};

// The exact cost of a lattice path of unit cubes' diagonals.
LatticeCost path_cost(const std::vector<std::vector<int>>& path);

}  // namespace hpcplan::dense::detail
