#pragma once
// Level-synchronous BFS on the dense lattice (dense_search.hpp describes the scheme), as the
// superstep driver's algorithm (superstep.hpp): one step is one level.
//
// Per level, every thread expands its frontier entries (tiles of its blocks with bits of the
// current level): targets in the entry's own block are applied at once (bits not yet reached
// get the next level's code; the first new bits of a tile put it on the next frontier, with the
// tile's reached bits before the level, so the next level's frontier word is "reached now, not
// then"), targets in the next block either side go to an outbox for its owner. After the
// driver's barrier (and halo swap) each thread applies what the other threads and ranks sent
// it. The level's report: states reached, next frontier entries, the goal reached.
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
    codes_ = ZeroedWords(2 * slabs_.store_tiles);
    threads_.resize(T);
    for (int t = 0; t < T; ++t) {
      threads_[t].marks = ZeroedWords((slabs_.thread_tiles[t] + 63) / 64);
      threads_[t].out_local.resize(T);
      threads_[t].id = t;
    }
    inbox_.resize(T);
    goal_tile_ = layout_.tile_of(q_.goal);
    goal_bit_ = Word{1} << layout_.bit_of(q_.goal);
    field_run_ = q_.distances != nullptr;
    if (field_run_) distances_.init(field_, layout_, slabs_, *q_.distances, q_.distances->levels);
  }

  // Bytes of the store and marks for `tiles` tiles.
  static std::uint64_t store_bytes(std::uint64_t tiles) { return tiles * 16 + tiles / 8 + 64; }

  Totals start() override {
    const std::uint64_t start_tile = layout_.tile_of(q_.start);
    if (slabs_.of_tile(start_tile).rank == slabs_.rank) {
      const Block& b = slabs_.of_tile(start_tile);
      *code_words(b, start_tile) |= Word{1} << layout_.bit_of(q_.start);  // level 0: code 1
      Thread& th = threads_[b.thread];
      mark(th, b, start_tile);
      th.cur.push_back({start_tile, 0});
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
    return codes_.bytes() + windows_.bytes() + marks_bytes();
  }

  void work(int id, const Superstep& step, ThreadControl& ctl) override {
    Thread& me = threads_[id];
    const Code next = next_code(step);
    // The frontier's words: reached now, not before the level that reached them.
    for (Entry& e : me.cur) {
      const Block& b = slabs_.of_tile(e.tile);
      const Word* c = code_words(b, e.tile);
      e.bits = (c[0] | c[1]) & ~e.bits;
      unmark(me, b, e.tile);
      // These are the states of this level: their distance.
      if (field_run_)
        distances_.write(layout_, slabs_.block_index_of_tile(e.tile), e.tile, e.bits,
                         static_cast<std::int32_t>(step.index));
    }
    std::size_t n = 0;
    for (const Entry& e : me.cur) {
      if ((++n & 1023) == 0 && ctl.poll()) break;
      expand(me, e, next.c0, next.c1);
    }
  }
  void receive(int id, const Superstep& step) override {
    Thread& me = threads_[id];
    const Code next = next_code(step);
    for (const Thread& t : threads_)
      for (const Entry& e : t.out_local[id])
        apply(me, slabs_.of_tile(e.tile), e.tile, e.bits, next.c0, next.c1);
    for (const Entry& e : inbox_[id])
      apply(me, slabs_.of_tile(e.tile), e.tile, e.bits, next.c0, next.c1);
  }
  StepReport report(int id) override {
    const Thread& me = threads_[id];
    StepReport r;
    r.fresh = me.fresh;
    r.pending = me.next.size();
    r.list_bytes = list_bytes(id);
    r.goal = me.goal_hit;
    return r;
  }
  std::uint64_t list_bytes(int id) const override { return list_bytes(threads_[id]); }
  void next_step(int id) override {
    Thread& me = threads_[id];
    me.out_down.clear();
    me.out_up.clear();
    for (auto& box : me.out_local) box.clear();
    me.fresh = 0;
    std::swap(me.cur, me.next);
    me.next.clear();
  }
  void send_halo(std::vector<std::byte>& down, std::vector<std::byte>& up) override {
    halo_.send(threads_, down, up);
  }
  void receive_halo(const std::vector<std::byte>& from_below,
                    const std::vector<std::byte>& from_above) override {
    halo_.receive(slabs_, from_below, from_above, inbox_);
  }
  double next_key(const Decision&) const override { return 0.0; }
  const char* progress_unit() const override { return "level"; }
  double progress_value(const Totals& t) const override { return static_cast<double>(t.steps); }

  std::uint64_t expanded() const override {
    std::uint64_t n = 0;
    for (const Thread& t : threads_) n += t.expanded;
    return n;
  }
  std::uint64_t generated() const override {
    std::uint64_t n = 0;
    for (const Thread& t : threads_) n += t.generated;
    return n;
  }
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

  // The state after `totals.steps` levels (dense_checkpoint.hpp).
  void save(checkpoint::Writer& w, const Totals& totals) const override {
    w.put(totals.steps);
    w.put(totals.reached);
    w.put(totals.peak_fresh);
    w.put(totals.list_peak);
    w.put_array(std::span<const Word>(codes_.data(), codes_.size()));
    for (const Thread& t : threads_) {
      w.put(t.expanded);
      w.put(t.generated);
      w.put_array(t.cur);  // the next level's frontier, with the bits before this level
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
    r.get_array(std::span<Word>(codes_.data(), codes_.size()));
    for (Thread& t : threads_) {
      t.expanded = r.get<std::uint64_t>();
      t.generated = r.get<std::uint64_t>();
      r.get_array(t.cur);
      for (const Entry& e : t.cur) {
        if (e.tile >= layout_.tile_count() || slabs_.of_tile(e.tile).rank != slabs_.rank ||
            slabs_.of_tile(e.tile).thread != t.id)
          r.fail("lists a frontier tile this thread does not hold (damaged)");
      }
      // (The frontier's marks need no restoring: every level starts by clearing them.)
    }
  }

 private:
  struct alignas(64) Thread {  // a cache line apart: each thread writes its own counters
    std::vector<Entry> cur, next;
    std::vector<Entry> out_down, out_up;        // to the ranks below and above
    std::vector<std::vector<Entry>> out_local;  // to this rank's threads
    ZeroedWords marks;
    int id = 0;
    std::uint64_t expanded = 0, generated = 0, fresh = 0;
    bool goal_hit = false;
  };

  // The 2-bit code of the level a step reaches (the step's index + 1, mod 3, + 1), as masks.
  struct Code {
    Word c0, c1;
  };
  static Code next_code(const Superstep& step) {
    const int code = static_cast<int>((step.index + 1) % 3) + 1;
    return {code & 1 ? ~Word{0} : 0, code & 2 ? ~Word{0} : 0};
  }

  Word* code_words(const Block& b, std::uint64_t tile) {
    return codes_.data() + 2 * (b.store + (tile - b.lo));
  }
  // The store's words of block b as if indexed by global tile (2 words a tile).
  Word* block_codes(const Block& b) { return codes_.data() + 2 * b.store - 2 * b.lo; }
  const Word* code_words(const Block& b, std::uint64_t tile) const {
    return codes_.data() + 2 * (b.store + (tile - b.lo));
  }
  static void mark(Thread& t, const Block& b, std::uint64_t tile) {
    const std::uint64_t i = b.mark + (tile - b.lo);
    t.marks[i >> 6] |= Word{1} << (i & 63);
  }
  static void unmark(Thread& t, const Block& b, std::uint64_t tile) {
    const std::uint64_t i = b.mark + (tile - b.lo);
    t.marks[i >> 6] &= ~(Word{1} << (i & 63));
  }
  std::uint64_t marks_bytes() const {
    std::uint64_t b = 0;
    for (const Thread& t : threads_) b += t.marks.bytes();
    return b;
  }
  static std::uint64_t list_bytes(const Thread& t) {
    std::size_t n =
        t.cur.capacity() + t.next.capacity() + t.out_down.capacity() + t.out_up.capacity();
    for (const auto& box : t.out_local) n += box.capacity();
    return n * sizeof(Entry);
  }

  // Bits reaching tile u of block b, which this thread owns.
  [[gnu::always_inline]] inline void apply(Thread& me, const Block& b, std::uint64_t u, Word bits,
                                           Word c0, Word c1) {
    apply_at(me, b, block_codes(b) + 2 * u, u, bits, c0, c1);
  }
  [[gnu::always_inline]] inline void apply_at(Thread& me, const Block& b, Word* c, std::uint64_t u,
                                              Word bits, Word c0, Word c1) {
    const Word old = c[0] | c[1];
    const Word fresh = bits & ~old;
    if (!fresh) return;
    const std::uint64_t i = b.mark + (u - b.lo);
    Word& mk = me.marks[i >> 6];
    const Word mb = Word{1} << (i & 63);
    if (!(mk & mb)) {
      mk |= mb;
      me.next.push_back({u, old});
    }
    c[0] |= fresh & c0;
    c[1] |= fresh & c1;
    me.fresh += static_cast<std::uint64_t>(std::popcount(fresh));
    if (u == goal_tile_ && (fresh & goal_bit_)) me.goal_hit = true;
  }

  [[gnu::always_inline]] inline void expand(Thread& me, const Entry& e, Word c0, Word c1) {
    int t[kMaxDims];
    layout_.tile_coords(e.tile, t);
    FreeWindows::At at;
    windows_.locate(t, at);
    me.expanded += static_cast<std::uint64_t>(std::popcount(e.bits));
    const int j = slabs_.layer_block[t[D - 1]];
    const Block& b = slabs_.blocks[j];
    Word* const base = block_codes(b) + 2 * e.tile;  // the source tile's words
    const std::uint64_t rel = e.tile - b.lo, span = b.hi - b.lo;
    me.generated += kernel_.template expand<false>(
        e.bits, at, windows_.stride(),
        stride_.data(), [&](std::int64_t delta, Word bits, int) __attribute__((always_inline)) {
          const std::uint64_t u = e.tile + static_cast<std::uint64_t>(delta);
          if (rel + static_cast<std::uint64_t>(delta) < span)  // inside the block (unsigned)
            return apply_at(me, b, base + 2 * delta, u, bits, c0, c1);
          // The next block down or up (a move crosses one layer at most).
          const int to = u < b.lo ? j - 1 : j + 1;
          const Block& nb = slabs_.blocks[to];
          if (nb.rank == slabs_.rank && nb.thread == me.id)
            apply(me, nb, u, bits, c0, c1);  // this thread's too: no one else writes it
          else if (nb.rank == slabs_.rank)
            me.out_local[nb.thread].push_back({u, bits});
          else
            (to < j ? me.out_down : me.out_up).push_back({u, bits});
        });
  }

  // The code (0: not reached, else level mod 3 + 1) of a state this rank holds.
  int code_at(const int* c) const {
    const std::uint64_t tile = layout_.tile_of(std::span<const int>(c, D));
    const int bit = layout_.bit_of(std::span<const int>(c, D));
    const Word* w = code_words(slabs_.of_tile(tile), tile);
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
        if (!inside || !slabs_.holds_layer(layout_.layer_of(std::span<const int>(y, D)))) continue;
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
  ZeroedWords codes_;
  std::vector<Thread> threads_;
  std::vector<std::vector<Entry>> inbox_;  // per thread: what the neighbouring ranks sent it
  HaloSwap<Entry> halo_;
  std::uint64_t goal_tile_ = 0;
  Word goal_bit_ = 0;
  DistanceWriter<std::int32_t> distances_;  // a distance field's part (Query::distances)
};

}  // namespace hpcplan::dense::detail
