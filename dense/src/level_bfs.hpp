#pragma once
// Level-synchronous BFS on the dense lattice (dense_search.hpp describes the scheme), as the
// superstep driver's algorithm (superstep.hpp): one step is one level.
//
// The store holds three words per tile: the 2-bit level code of its states (0: not reached,
// else level mod 3 + 1; the walk back reads it) and the word of states reached but not yet
// expanded (`pending`). The frontier is an active set: one bit per tile, per thread, for the
// tiles with pending states, in two bitmaps by level parity. A level sweeps the bits of the
// current bitmap in tile order (so neighbouring tiles are read as streams, not at random),
// expands each tile's states of this level (pending, with this level's code: bits a tile
// received earlier in this same level carry the next level's code and stay pending), and
// clears its bit; a target's new states get the next level's code, join its pending word and
// set its bit in the next bitmap. No tile without pending states is touched, and no list of
// entries is kept: the work and the memory traffic of a level are those of its frontier's
// tiles and their neighbours. Targets in a neighbouring block that another thread or
// rank holds go to an outbox, applied by their owner after the driver's barrier.
#include <limits>

#include "engine_common.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/dense/zeroed_words.hpp"
#include "superstep.hpp"

namespace hpcplan::dense::detail {

template <int D, int K, class Kernel>
class LevelBfs final : public SuperstepAlgorithm {
 public:
  LevelBfs(const ObstacleSource& field, const Query& q, SlabTransport& tr, const TileLayout& layout,
           const FreeWindows& windows, const Kernel& kernel, const SlabMap& slabs,
           std::uint64_t free_states)
      : field_(field),
        q_(q),
        tr_(tr),
        layout_(layout),
        windows_(windows),
        kernel_(kernel),
        slabs_(slabs),
        free_states_(free_states) {
    for (int a = 0; a < D; ++a) stride_[a] = layout.stride(a);
    const int T = slabs_.threads;
    store_ = ZeroedWords(kWordsPerTile * slabs_.store_tiles);
    threads_.resize(T);
    for (int t = 0; t < T; ++t) {
      for (ZeroedWords& active : threads_[t].active)
        active = ZeroedWords((slabs_.thread_tiles[t] + 63) / 64);
      threads_[t].size_for(slabs_);
      threads_[t].id = t;
    }
    for (std::size_t j = 0; j < slabs_.blocks.size(); ++j)
      if (slabs_.blocks[j].rank == slabs_.rank)
        threads_[slabs_.blocks[j].thread].blocks.push_back(static_cast<int>(j));
    inbox_.resize(T);
    goal_tile_ = layout_.tile_of(q_.goal);
    goal_bit_ = Word{1} << layout_.bit_of(q_.goal);
    field_run_ = q_.distances != nullptr;
    if (field_run_) distances_.init(field_, layout_, slabs_, *q_.distances, q_.distances->levels);
  }

  // Bytes of the store and the two active bitmaps for `tiles` tiles.
  static std::uint64_t store_bytes(std::uint64_t tiles) {
    return tiles * 8 * kWordsPerTile + 2 * (tiles / 8 + 64);
  }

  Totals start() override {
    const std::uint64_t start_tile = layout_.tile_of(q_.start);
    if (slabs_.of_tile(start_tile).rank == slabs_.rank) {
      const Block& b = slabs_.of_tile(start_tile);
      Word* w = tile_words(b, start_tile);
      w[0] = w[2] = Word{1} << layout_.bit_of(q_.start);  // level 0: code 1, pending
      set_active(threads_[b.thread].active[0], b, start_tile);
    }
    Totals t;
    t.reached = 1;
    t.peak_fresh = 1;
    // The goal's level, once some level reached it (a distance field goes on past it).
    t.goal_seen = q_.start == q_.goal;
    return t;
  }
  // A distance field settles everything reachable whatever the goal.
  bool solved_at_start() const override { return q_.start == q_.goal && !field_run_; }
  std::uint64_t fixed_bytes() const override {
    std::uint64_t bitmaps = 0;
    for (const Thread& t : threads_) bitmaps += t.active[0].bytes() + t.active[1].bytes();
    return store_.bytes() + windows_.bytes() + bitmaps;
  }

  void work(int id, const Superstep& step, ThreadControl& ctl) override {
    Thread& me = threads_[id];
    const Code now = code_of(step.index), next = code_of(step.index + 1);
    ZeroedWords& active = me.active[step.index & 1];
    ZeroedWords& next_active = me.active[(step.index + 1) & 1];
    const auto level = static_cast<std::int32_t>(step.index);
    std::size_t n = 0;
    for (const int j : me.blocks) {
      const Block& b = slabs_.blocks[j];
      Word* const words = block_words(b);
      const std::uint64_t first = b.mark, last = b.mark + (b.hi - b.lo);  // bits in `active`
      if (first == last) continue;
      for (std::uint64_t w = first >> 6; w <= (last - 1) >> 6; ++w) {
        // This block's bits of the word (a word may hold the end of one block and the start
        // of the next, which another pass over the thread's blocks takes).
        Word bits = active[w];
        if (!bits) continue;
        const std::uint64_t lo = w << 6;
        if (lo < first) bits &= ~Word{0} << (first - lo);
        if (last - lo < 64) bits &= (Word{1} << (last - lo)) - 1;
        active[w] &= ~bits;
        for (; bits; bits &= bits - 1) {
          const std::uint64_t tile = b.lo + (lo + std::countr_zero(bits) - first);
          Word* const c = words + kWordsPerTile * tile;
          // This level's states: pending, with this level's code.
          const Word f = c[2] & (c[0] ^ now.not0) & (c[1] ^ now.not1);
          if (!f) continue;
          ++me.active_now;
          c[2] &= ~f;
          if (field_run_) distances_.write(layout_, j, tile, f, level);
          expand(me, b, tile, f, next, next_active);
        }
        if ((++n & 15) == 0 && ctl.poll()) return;
      }
    }
  }
  void receive(int id, const Superstep& step) override {
    Thread& me = threads_[id];
    const Code next = code_of(step.index + 1);
    ZeroedWords& next_active = me.active[(step.index + 1) & 1];
    for (const Thread& t : threads_)
      for (const Entry& e : t.out_local[id])
        apply(me, slabs_.of_tile(e.tile), e.tile, e.bits, next, next_active);
    for (const Entry& e : inbox_[id])
      apply(me, slabs_.of_tile(e.tile), e.tile, e.bits, next, next_active);
  }
  StepReport report(int id) const override {
    const Thread& me = threads_[id];
    StepReport r;
    r.fresh = me.fresh;
    r.pending = me.fresh;  // the next level's states
    r.active = me.active_now;
    r.list_bytes = list_bytes(id);
    r.goal = me.goal_hit;
    return r;
  }
  std::uint64_t list_bytes(int id) const override { return list_bytes(threads_[id]); }
  void next_step(int id) override {
    Thread& me = threads_[id];
    me.clear();
    me.fresh = 0;
    me.active_now = 0;
  }
  void send_halo(std::vector<std::vector<std::byte>>& to) override {
    HaloSwap<Entry>::send(threads_, slabs_.peers.size(), to);
  }
  void receive_halo(const std::vector<std::vector<std::byte>>& from) override {
    halo_.receive(slabs_, from, inbox_);
  }
  double next_key(const Decision&) const override { return 0.0; }
  const char* progress_unit() const override { return "level"; }
  double progress_value(const Totals& t) const override { return static_cast<double>(t.steps); }

  std::uint64_t expanded() const override { return sum_over(threads_, &Thread::expanded); }
  std::uint64_t generated() const override { return sum_over(threads_, &Thread::generated); }
  void finish(Result& res, const Totals& totals, bool solved) override {
    res.counters.peak_states = totals.reached;
    res.counters.peak_open = totals.peak_fresh;
    res.figures.levels = totals.steps;
    res.figures.reached = totals.reached;
    if (solved) {
      res.path = walk_back(field_run_ ? totals.goal_step : totals.steps);
      res.hops = res.path.size() - 1;
      res.cost = path_cost(res.path).value();
    }
  }

  // The state after `totals.steps` levels (dense_checkpoint.hpp): the store (codes and
  // pending words) and each thread's counts and active bitmap for the next level.
  void save(checkpoint::Writer& w, const Totals& totals) const override {
    w.put(totals.steps);
    w.put(totals.reached);
    w.put(totals.peak_fresh);
    w.put(totals.list_peak);
    w.put_array(std::span<const Word>(store_.data(), store_.size()));
    for (const Thread& t : threads_) {
      w.put(t.expanded);
      w.put(t.generated);
      const ZeroedWords& active = t.active[totals.steps & 1];
      w.put_array(std::span<const Word>(active.data(), active.size()));
    }
  }

  // The state saved by save() (InputError if it is refused).
  void restore(checkpoint::Reader& r, Totals& totals) override {
    const std::uint64_t level = r.get<std::uint64_t>();
    const std::uint64_t reached = r.get<std::uint64_t>();
    const std::uint64_t peak = r.get<std::uint64_t>();
    totals.steps = level;
    totals.reached = reached;
    totals.peak_fresh = peak;
    totals.list_peak = r.get<std::uint64_t>();
    // A BFS over N free states has fewer than N levels: a larger count would send the walk
    // back round the lattice for as many steps (found by fuzz_grid_checkpoint).
    if (level >= free_states_ || reached > free_states_ || peak > reached)
      r.fail("holds counts this lattice cannot have (damaged)");
    r.get_array(std::span<Word>(store_.data(), store_.size()));
    for (Thread& t : threads_) {
      t.expanded = r.get<std::uint64_t>();
      t.generated = r.get<std::uint64_t>();
      ZeroedWords& active = t.active[level & 1];
      r.get_array(std::span<Word>(active.data(), active.size()));
      // Bits past the thread's tiles would name tiles it does not hold.
      const std::uint64_t tiles = slabs_.thread_tiles[t.id];
      if (tiles % 64 && active.size() && (active[active.size() - 1] >> (tiles % 64)))
        r.fail("lists a frontier tile this thread does not hold (damaged)");
    }
  }

 private:
  struct alignas(64) Thread
      : Outboxes<Entry> {     // a cache line apart: each thread writes its own counters
    std::vector<int> blocks;  // the blocks it owns, in tile order
    ZeroedWords active[2];    // tiles with pending states, by level parity
    int id = 0;
    std::uint64_t expanded = 0, generated = 0, fresh = 0;
    std::uint64_t active_now = 0;  // tiles swept with states of this level
    bool goal_hit = false;
  };

  // Words per tile in the store: the level code's two bits, and the pending states.
  static constexpr int kWordsPerTile = 3;

  // A level's 2-bit code (level mod 3 + 1) as masks: the words a state's code bits equal, and
  // their complements (c ^ not is all ones where the bit matches).
  struct Code {
    Word c0, c1, not0, not1;
  };
  static Code code_of(std::uint64_t level) {
    const int code = static_cast<int>(level % 3) + 1;
    const Word c0 = code & 1 ? ~Word{0} : 0, c1 = code & 2 ? ~Word{0} : 0;
    return {c0, c1, ~c0, ~c1};
  }

  // The store's words of tile `tile` of block b, and of block b as if indexed by global tile.
  Word* tile_words(const Block& b, std::uint64_t tile) {
    return store_.data() + kWordsPerTile * (b.store + (tile - b.lo));
  }
  const Word* tile_words(const Block& b, std::uint64_t tile) const {
    return store_.data() + kWordsPerTile * (b.store + (tile - b.lo));
  }
  Word* block_words(const Block& b) {
    return store_.data() + kWordsPerTile * b.store - kWordsPerTile * b.lo;
  }
  static void set_active(ZeroedWords& active, const Block& b, std::uint64_t tile) {
    const std::uint64_t i = b.mark + (tile - b.lo);
    active[i >> 6] |= Word{1} << (i & 63);
  }
  static std::uint64_t list_bytes(const Thread& t) { return t.capacity_bytes(); }

  // Bits reaching tile u of block b, which this thread owns.
  [[gnu::always_inline]] inline void apply(Thread& me, const Block& b, std::uint64_t u, Word bits,
                                           const Code& next, ZeroedWords& next_active) {
    apply_at(me, b, block_words(b) + kWordsPerTile * u, u, bits, next, next_active);
  }
  [[gnu::always_inline]] inline void apply_at(Thread& me, const Block& b, Word* c, std::uint64_t u,
                                              Word bits, const Code& next,
                                              ZeroedWords& next_active) {
    const Word fresh = bits & ~(c[0] | c[1]);
    if (!fresh) return;
    c[0] |= fresh & next.c0;
    c[1] |= fresh & next.c1;
    c[2] |= fresh;
    set_active(next_active, b, u);
    me.fresh += static_cast<std::uint64_t>(std::popcount(fresh));
    if (u == goal_tile_ && (fresh & goal_bit_)) me.goal_hit = true;
  }

  [[gnu::always_inline]] inline void expand(Thread& me, const Block& b, std::uint64_t tile, Word f,
                                            const Code& next, ZeroedWords& next_active) {
    int t[kMaxDims];
    layout_.tile_coords(tile, t);
    FreeWindows::At at;
    windows_.locate(t, at);
    me.expanded += static_cast<std::uint64_t>(std::popcount(f));
    Word* const base = block_words(b) + kWordsPerTile * tile;  // the source tile's words
    const std::uint64_t rel = tile - b.lo, span = b.hi - b.lo;
    me.generated += kernel_.template expand<false>(
        f, at, windows_.stride(),
        stride_.data(), [&](std::int64_t delta, Word bits, int) __attribute__((always_inline)) {
          const std::uint64_t u = tile + static_cast<std::uint64_t>(delta);
          if (rel + static_cast<std::uint64_t>(delta) < span)  // inside the block (unsigned)
            return apply_at(me, b, base + kWordsPerTile * delta, u, bits, next, next_active);
          // Another block: a neighbouring section's (slab_plan.hpp).
          const Block& nb = slabs_.of_tile(u);
          if (nb.rank == slabs_.rank && nb.thread == me.id)
            apply(me, nb, u, bits, next, next_active);  // this thread's too: no one else writes it
          else if (nb.rank == slabs_.rank)
            me.out_local[nb.thread].push_back({u, bits});
          else
            me.to_peer(slabs_.peer_slot[nb.rank], {u, bits});
        });
  }

  // The code (0: not reached, else level mod 3 + 1) of a state this rank holds.
  int code_at(const int* c) const {
    const std::uint64_t tile = layout_.tile_of(std::span<const int>(c, D));
    const int bit = layout_.bit_of(std::span<const int>(c, D));
    const Word* w = tile_words(slabs_.of_tile(tile), tile);
    return static_cast<int>((w[0] >> bit) & 1) | static_cast<int>(((w[1] >> bit) & 1) << 1);
  }

  // From the goal (level `level`) back to the start: at each step the first move, in the fixed
  // order, from a state of the level before whose move is legal. Every rank looks among the
  // states it holds; one reduction picks the first.
  std::vector<std::vector<int>> walk_back(std::uint64_t level) {
    const auto offsets = move_offsets(D, q_.connectivity);
    std::vector<std::vector<int>> path{q_.goal};
    int x[kMaxDims];
    std::copy(q_.goal.begin(), q_.goal.end(), x);
    for (std::uint64_t l = level; l > 0; --l) {
      const int want = static_cast<int>((l - 1) % 3) + 1;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < offsets.size() && !slabs_.empty(); ++j) {
        int y[kMaxDims];
        bool inside = true;
        for (int a = 0; a < D; ++a) {
          y[a] = x[a] - offsets[j][a];
          inside = inside && y[a] >= 0 && y[a] < layout_.extent();
        }
        if (!inside || !slabs_.holds_tile(layout_.tile_of(std::span<const int>(y, D)))) continue;
        if (code_at(y) != want || !legal_move(field_, y, offsets[j])) continue;
        best = static_cast<double>(j);
        break;
      }
      tr_.min(std::span<double>(&best, 1));
      if (!std::isfinite(best)) throw RunError("dense BFS: the walk back found no predecessor");
      const auto& o = offsets[static_cast<std::size_t>(best)];
      for (int a = 0; a < D; ++a) x[a] -= o[a];
      path.emplace_back(x, x + D);
    }
    std::reverse(path.begin(), path.end());
    return path;
  }

  ObstacleSource field_;
  const Query& q_;
  SlabTransport& tr_;
  const TileLayout& layout_;
  const FreeWindows& windows_;
  const Kernel& kernel_;
  const SlabMap& slabs_;
  std::uint64_t free_states_ = 0;
  bool field_run_ = false;  // a distance field (Query::distances)
  std::array<std::int64_t, kMaxDims> stride_{};
  ZeroedWords store_;  // kWordsPerTile words per tile of this rank's blocks
  std::vector<Thread> threads_;
  std::vector<std::vector<Entry>> inbox_;  // per thread: what the neighbouring ranks sent it
  HaloSwap<Entry> halo_;
  std::uint64_t goal_tile_ = 0;
  Word goal_bit_ = 0;
  DistanceWriter<std::int32_t> distances_;  // a distance field's part (Query::distances)
};

}  // namespace hpcplan::dense::detail
