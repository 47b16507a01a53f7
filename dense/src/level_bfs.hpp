#pragma once
// Level-synchronous BFS on the dense lattice (dense_search.hpp describes the scheme).
//
// Per level, every thread expands its frontier entries (tiles of its blocks with bits of the
// current level): targets in the entry's own block are applied at once (bits not yet reached
// get the next level's code; the first new bits of a tile put it on the next frontier, with the
// tile's reached bits before the level, so the next level's frontier word is "reached now, not
// then"), targets in the next block either side go to an outbox for its owner. After a barrier
// (and, with other ranks, the master thread's swap of the rank's outboxes with the neighbouring
// ranks and another barrier) each thread applies what the other threads and ranks sent it and
// publishes its level's counts. One decision per level: goal reached, nothing left (no_path),
// or a stop; taken by every thread from the published counts after one more barrier on one
// rank, by one reduction over the ranks otherwise. The same decision says when to write a
// checkpoint (dense_checkpoint.hpp), after the level's lists are swapped.
#include <limits>

#include "engine_checkpoint.hpp"
#include "engine_common.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/dense/zeroed_words.hpp"

namespace hpcplan::dense::detail {

template <int D, int K, class Kernel>
class LevelBfs {
 public:
  LevelBfs(const ObstacleSource& field, const Query& q, SlabTransport& tr, const TileLayout& layout,
           const FreeWindows& windows, const Kernel& kernel, const SlabMap& slabs)
      : field_(field),
        q_(q),
        tr_(tr),
        layout_(layout),
        windows_(windows),
        kernel_(kernel),
        slabs_(slabs) {
    for (int a = 0; a < D; ++a) stride_[a] = layout.stride(a);
    double free = 0.0;
    for (double w : free_states_per_layer(field, layout)) free += w;
    free_states_ = static_cast<std::uint64_t>(free + 0.5);
  }

  // Bytes of the store and marks for `tiles` tiles.
  static std::uint64_t store_bytes(std::uint64_t tiles) { return tiles * 16 + tiles / 8 + 64; }

  Result run() {
    Result res;
    Stopwatch clock;
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
    const std::uint64_t start_tile = layout_.tile_of(q_.start);
    // A distance field settles everything reachable whatever the goal.
    const bool field_run = q_.distances != nullptr;
    const bool trivial = q_.start == q_.goal && !field_run;
    // The goal's level, once some level reached it (a distance field goes on past it).
    bool goal_seen = q_.start == q_.goal;
    std::uint64_t goal_level = 0;
    if (field_run) distances_.init(field_, layout_, slabs_, *q_.distances, q_.distances->levels);
    std::uint64_t level = 0;
    std::uint64_t reached_total = 1, peak_level = 1;
    std::uint64_t list_peak = 0;
    const Checkpointing& cp = q_.checkpointing;
    const std::string identity =
        cp.path.empty() && cp.restart.empty() ? "" : run_identity(field_, q_, slabs_);
    if (!cp.restart.empty()) {
      agree_on_restart(tr_, [&] {
        restore(identity, level, reached_total, peak_level, list_peak);
        return level;
      });
    } else if (slabs_.of_tile(start_tile).rank == slabs_.rank) {
      const Block& b = slabs_.of_tile(start_tile);
      *code_words(b, start_tile) |= Word{1} << layout_.bit_of(q_.start);  // level 0: code 1
      Thread& th = threads_[b.thread];
      mark(th, b, start_tile);
      th.cur.push_back({start_tile, 0});
    }
    const std::uint64_t fixed = codes_.bytes() + windows_.bytes() + marks_bytes();

    DenseProgress progress(q_.progress_label, q_.progress_after_s, free_states_);
    CheckpointSchedule schedule(cp);
    Status status = Status::no_path;
    bool solved = trivial;
    HaloSwap<Entry> halo;
    const std::uint64_t budget = q_.memory_budget;

    int team = T;
    bool failed = false;
    // Whether this rank trades with others: then the master thread runs the halo swap and the
    // ranks' reduction, each between barriers (four a level). On one rank every thread reads
    // what the others published and takes the same decision itself (two barriers a level):
    // fewer points where a thread on a time-shared core can hold up the others.
    const bool alone = tr_.ranks() == 1;
    Decision shared;  // the ranks' decision, from the master thread (not alone)
#pragma omp parallel num_threads(T) if (T > 1)
    {
      const int id = omp_get_thread_num();
      Thread& me = threads_[id];
      if (omp_get_num_threads() != T) {
#pragma omp master
        team = omp_get_num_threads();
      } else if (!trivial)
        for (std::uint64_t lvl = level, reached = reached_total, peak = peak_level;;) {
          const int next_code = static_cast<int>((lvl + 1) % 3) + 1;
          const Word c0 = next_code & 1 ? ~Word{0} : 0, c1 = next_code & 2 ? ~Word{0} : 0;
          try {
            // The frontier's words: reached now, not before the level that reached them.
            for (Entry& e : me.cur) {
              const Block& b = slabs_.of_tile(e.tile);
              const Word* c = code_words(b, e.tile);
              e.bits = (c[0] | c[1]) & ~e.bits;
              unmark(me, b, e.tile);
              // These are the states of level lvl: their distance.
              if (field_run)
                distances_.write(layout_, slabs_.block_index_of_tile(e.tile), e.tile, e.bits,
                                 static_cast<std::int32_t>(lvl));
            }
            std::size_t n = 0;
            for (const Entry& e : me.cur) {
              if ((++n & 1023) == 0 && poll_stop(workers_stop_, me)) break;
              expand(me, e, c0, c1);
            }
            if (budget && list_bytes(me) * T + fixed > budget)
              me.stop = std::max(me.stop, kStopBudget);
            // The query's own condition and the checkpoint schedule, on the master thread only
            // (Stop's contract).
            if (id == 0) {
              poll_stop(q_.stop, me);
              me.save = schedule.due();
            }
          } catch (...) {
            caught(me);
          }
#pragma omp barrier
          if (!alone) {
#pragma omp master
            try {
              halo.run(tr_, slabs_, threads_, inbox_);
            } catch (...) {
              caught(threads_.front());
            }
#pragma omp barrier
          }
          try {
            for (const Thread& t : threads_)
              for (const Entry& e : t.out_local[id])
                apply(me, slabs_.of_tile(e.tile), e.tile, e.bits, c0, c1);
            for (const Entry& e : inbox_[id])
              apply(me, slabs_.of_tile(e.tile), e.tile, e.bits, c0, c1);
          } catch (...) {
            caught(me);
          }
          // This level's summary, in the slot of the level's parity: the other threads read
          // it after the next barrier, and this thread writes that slot again only two levels
          // on, after every thread has passed the next level's first barrier.
          Published& pub = me.published[lvl & 1];
          pub = {me.fresh, me.next.size(), list_bytes(me), me.goal_hit, me.stop, me.save};
#pragma omp barrier
          Decision d;
          if (alone) {
            d = decide(lvl & 1);
          } else {
#pragma omp master
            {
              try {
                shared = decide(lvl & 1);
                // One reduction over the ranks: new states, next frontier entries, goal, stop.
                std::uint64_t sums[2] = {shared.fresh, shared.next};
                std::uint64_t maxes[3] = {shared.goal ? 1u : 0u,
                                          static_cast<std::uint64_t>(shared.stop),
                                          static_cast<std::uint64_t>(shared.save)};
                tr_.sum(sums);
                tr_.max(maxes);
                shared = {sums[0],
                          sums[1],
                          shared.lists,
                          maxes[0] != 0,
                          static_cast<int>(maxes[1]),
                          static_cast<int>(maxes[2])};
              } catch (...) {
                caught(threads_.front());
                shared.stop = kStopFailed;  // the reduction itself failed
              }
            }
#pragma omp barrier
            d = shared;
          }
          ++lvl;
          reached += d.fresh;
          peak = std::max(peak, d.fresh);
          const bool end = d.stop || (d.goal && !field_run) || d.next == 0;
#pragma omp master
          {
            level = lvl;
            reached_total = reached;
            peak_level = peak;
            list_peak = std::max(list_peak, d.lists);
            if (d.goal && !goal_seen) {
              goal_seen = true;
              goal_level = lvl;
            }
            if (d.stop == kStopFailed)
              failed = true;
            else if (d.goal && !field_run)
              solved = true;
            else if (d.stop)
              status = stopped_status(static_cast<std::uint64_t>(d.stop));
            else if (d.next == 0)
              status = Status::no_path;
            try {
              progress.update("level", static_cast<double>(lvl), reached);
            } catch (...) {
              caught(me);  // ends the run at the next level's decision
            }
          }
          if (end) break;
          // Every read of this thread's outboxes (the other threads' apply phase, the master's
          // halo swap) happened before the last barrier.
          me.out_down.clear();
          me.out_up.clear();
          for (auto& box : me.out_local) box.clear();
          me.fresh = 0;
          std::swap(me.cur, me.next);
          me.next.clear();
          if (d.save) {
            // Every thread's frontier is in place: the level's state is whole.
#pragma omp barrier
#pragma omp master
            try {
              save(identity, lvl, reached, peak, list_peak);
            } catch (...) {
              caught(threads_.front());  // ends the run (rethrown after the region)
            }
#pragma omp barrier
            if (d.save == kSaveAndEnd) {
#pragma omp master
              status = Status::interrupted;
              break;
            }
          }
        }
    }
    rethrow_failure(threads_, team, failed);
    Counters& k = res.counters;
    std::uint64_t local[2] = {0, 0};
    for (const Thread& t : threads_) {
      local[0] += t.expanded;
      local[1] += t.generated;
    }
    const double search_ms = clock.milliseconds();
    res.figures.rank_expanded = gather_ranks(tr_, local[0]);
    res.figures.rank_search_ms = gather_ranks(tr_, search_ms);
    tr_.sum(std::span<std::uint64_t>(local, 2));
    k.expanded = local[0];
    k.generated = local[1];
    k.peak_states = reached_total;
    k.peak_open = peak_level;
    res.figures.levels = level;
    res.figures.reached = reached_total;
    res.figures.bytes_needed = fixed;
    std::uint64_t bytes[2] = {fixed + list_peak, fixed + list_peak};
    tr_.max(std::span<std::uint64_t>(bytes, 1));
    tr_.sum(std::span<std::uint64_t>(bytes + 1, 1));
    res.figures.bytes_per_rank = bytes[0];
    res.figures.bytes_total = bytes[1];
    // A distance field that ran to its end (no stop) has solved the query if it reached the goal.
    if (field_run && status == Status::no_path && goal_seen) solved = true;
    if (solved) {
      res.status = Status::solved;
      res.path = walk_back(field_run ? goal_level : level);
      res.hops = res.path.size() - 1;
      res.cost = path_cost(res.path).value();
    } else {
      res.status = status;
    }
    k.time_ms = clock.milliseconds();
    return res;
  }

 private:
  // What a thread tells the others at the end of a level, and what they decide from it.
  struct Published {
    std::uint64_t fresh = 0, next = 0, lists = 0;
    bool goal = false;
    int stop = 0;
    int save = 0;  // the master thread's: kSave, kSaveAndEnd or 0
  };
  struct Decision {
    std::uint64_t fresh = 0, next = 0, lists = 0;  // sums over the threads
    bool goal = false;
    int stop = 0;  // the highest stop code
    int save = 0;  // a checkpoint after this level: kSave, or kSaveAndEnd
  };
  // The threads' summaries of one level (slot = the level's parity), combined.
  Decision decide(int slot) const {
    Decision d;
    for (const Thread& t : threads_) {
      const Published& p = t.published[slot];
      d.fresh += p.fresh;
      d.next += p.next;
      d.lists += p.lists;
      d.goal = d.goal || p.goal;
      d.stop = std::max(d.stop, p.stop);
      d.save = std::max(d.save, p.save);
    }
    return d;
  }

  struct alignas(64) Thread {  // a cache line apart: each thread writes its own counters
    std::exception_ptr error;  // the first exception of this thread's work (caught())
    std::vector<Entry> cur, next;
    std::vector<Entry> out_down, out_up;        // to the ranks below and above
    std::vector<std::vector<Entry>> out_local;  // to this rank's threads
    ZeroedWords marks;
    int id = 0;
    std::uint64_t expanded = 0, generated = 0, fresh = 0;
    bool goal_hit = false;
    int stop = 0;            // kStop* code, the highest wins
    int save = 0;            // the master thread's checkpoint schedule at this level
    Published published[2];  // by level parity
  };

  // The state after `level` levels (dense_checkpoint.hpp), into this rank's checkpoint file.
  void save(const std::string& identity, std::uint64_t level, std::uint64_t reached,
            std::uint64_t peak, std::uint64_t list_peak) const {
    checkpoint::Writer w;
    w.put(level);
    w.put(reached);
    w.put(peak);
    w.put(list_peak);
    w.put_array(std::span<const Word>(codes_.data(), codes_.size()));
    for (const Thread& t : threads_) {
      w.put(t.expanded);
      w.put(t.generated);
      w.put_array(t.cur);  // the next level's frontier, with the bits before this level
    }
    write_checkpoint(q_.checkpointing.path, identity, w.bytes());
  }

  // The state saved by save(), from this rank's --restart file: InputError if it is refused.
  void restore(const std::string& identity, std::uint64_t& level, std::uint64_t& reached,
               std::uint64_t& peak, std::uint64_t& list_peak) {
    const std::string& path = q_.checkpointing.restart;
    const std::string file = read_checkpoint_file(path);
    checkpoint::Reader r(open_checkpoint(file, path, identity), path);
    level = r.get<std::uint64_t>();
    reached = r.get<std::uint64_t>();
    peak = r.get<std::uint64_t>();
    list_peak = r.get<std::uint64_t>();
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
    if (r.left() != 0) r.fail("has bytes after its end (damaged)");
  }

  Word* code_words(const Block& b, std::uint64_t tile) {
    return codes_.data() + 2 * (b.store + (tile - b.lo));
  }
  // The store's words of block b as if indexed by global tile (2 words a tile).
  Word* block_codes(const Block& b) {
    return codes_.data() + 2 * b.store - 2 * b.lo;
  }
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
  // What every thread polls in its work; the master thread alone also evaluates the query's
  // condition (Stop's contract: a condition runs on one polling thread), once per level or
  // bucket.
  const Stop workers_stop_ = q_.stop.without_condition();
  std::uint64_t free_states_ = 0;
  std::array<std::int64_t, kMaxDims> stride_{};
  ZeroedWords codes_;
  std::vector<Thread> threads_;
  std::vector<std::vector<Entry>> inbox_;  // per thread: what the neighbouring ranks sent it
  std::uint64_t goal_tile_ = 0;
  Word goal_bit_ = 0;
  DistanceWriter<std::int32_t> distances_;  // a distance field's part (Query::distances)
};

}  // namespace hpcplan::dense::detail
