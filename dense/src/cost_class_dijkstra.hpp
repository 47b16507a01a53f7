#pragma once
// Exact Dijkstra on the dense lattice by cost classes (dense_search.hpp states why the order is
// exact), as the superstep driver's algorithm (superstep.hpp): one step is one bucket. A class is
// an exact path cost (ones + root2 sqrt2 + root3 sqrt3) with its move count; its states are lists
// of (tile, bits). Each thread keeps the classes of its sub-slab in value order. A bucket [k, k +
// 1) is processed in one pass: each thread takes its classes below k + 1 in order, settles the bits
// not yet settled (the first class to hold a state is its cost), and files the targets into the
// classes one move more expensive, its own or, past its sub-slab, an outbox. Then the driver's
// exchange and decision (the next bucket is the floor of the smallest pending class anywhere; the
// goal settled; nothing left; a stop). A run ends with the bucket that settles the goal, processed
// whole, so its counts do not depend on the number of ranks or threads.
#include <limits>
#include <map>
#include <tuple>

#include "engine_common.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/dense/zeroed_words.hpp"
#include "superstep.hpp"

namespace hpcplan::dense::detail {

// An exact cost and the moves that make it. Classes are ordered by cost, then by fewer moves
// (full connectivity: two unit moves cost what one four-axis move does).
struct ClassKey {
  std::int32_t ones = 0, root2 = 0, root3 = 0, hops = 0;

  double value() const { return LatticeCost{ones, root2, root3}.value(); }
  ClassKey after(int axes) const {
    const LatticeCost c = LatticeCost{ones, root2, root3} + LatticeCost::for_axes(axes);
    return {c.ones, c.root2, c.root3, hops + 1};
  }
  friend bool operator==(const ClassKey&, const ClassKey&) = default;
  friend bool operator<(const ClassKey& a, const ClassKey& b) {
    const double va = a.value(), vb = b.value();
    if (va != vb) return va < vb;
    return a.hops < b.hops;
  }
  // Four 16-bit fields, for the per-state record of a path run.
  std::uint64_t packed() const {
    return static_cast<std::uint64_t>(ones) | static_cast<std::uint64_t>(root2) << 16 |
           static_cast<std::uint64_t>(root3) << 32 | static_cast<std::uint64_t>(hops) << 48;
  }
  bool packable() const {
    return ones >= 0 && ones < 65536 && root2 >= 0 && root2 < 65536 && root3 >= 0 &&
           root3 < 65536 && hops >= 0 && hops < 65535;
  }
};

struct ClassEntry {
  std::uint64_t tile;
  Word bits;
  ClassKey key;
};
// Halo entries merge when they name the same tile and class (Outboxes::to_peer).
inline std::tuple<std::uint64_t, std::int32_t, std::int32_t, std::int32_t, std::int32_t> halo_key(
    const ClassEntry& e) {
  return {e.tile, e.key.ones, e.key.root2, e.key.root3, e.key.hops};
}
inline std::uint64_t halo_hash(const ClassEntry& e) {
  return e.tile ^ (static_cast<std::uint64_t>(e.key.hops) << 40);
}

template <int D, int K, class Kernel>
class CostClassDijkstra final : public SuperstepAlgorithm {
 public:
  CostClassDijkstra(const ObstacleSource& field, const Query& q, SlabTransport& tr,
                    const TileLayout& layout, const FreeWindows& windows, const Kernel& kernel,
                    const SlabMap& slabs, std::uint64_t free_states)
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
    settled_ = ZeroedWords(slabs_.store_tiles);
    if (q_.keep_path) keys_ = ZeroedWords(slabs_.store_tiles * 64);
    threads_.resize(T);
    for (int t = 0; t < T; ++t) {
      threads_[t].size_for(slabs_);
      threads_[t].id = t;
    }
    inbox_.resize(T);
    goal_tile_ = layout_.tile_of(q_.goal);
    goal_bit_ = Word{1} << layout_.bit_of(q_.goal);
    // A distance field settles everything reachable whatever the goal.
    field_run_ = q_.distances != nullptr;
    if (field_run_) distances_.init(field_, layout_, slabs_, *q_.distances, q_.distances->costs);
  }

  // Settled bits, and with a path each state's class (8 bytes a state).
  static std::uint64_t store_bytes(std::uint64_t tiles, bool keep_path) {
    return tiles * 8 + (keep_path ? tiles * 64 * 8 : 0) + 64;
  }

  Totals start() override {
    const std::uint64_t start_tile = layout_.tile_of(q_.start);
    if (slabs_.of_tile(start_tile).rank == slabs_.rank) {
      Thread& th = threads_[slabs_.of_tile(start_tile).thread];
      th.pending[ClassKey{}].push_back({start_tile, Word{1} << layout_.bit_of(q_.start)});
    }
    Totals t;
    t.peak_pending = 1;
    return t;
  }
  std::uint64_t fixed_bytes() const override {
    return settled_.bytes() + keys_.bytes() + windows_.bytes();
  }

  // The classes below the bucket's end, in value order: each settles the bits of its lists not
  // yet settled (the first class to hold a state is its cost) and files their targets.
  void work(int id, const Superstep& step, ThreadControl& ctl) override {
    Thread& me = threads_[id];
    const double bucket = step.key;
    std::size_t n = 0;
    bool stopped = false;
    while (!stopped && !me.pending.empty() && me.pending.begin()->first.value() < bucket + 1) {
      auto node = me.pending.extract(me.pending.begin());
      const ClassKey key = node.key();
      std::vector<Entry>& list = node.mapped();
      ++me.epoch;
      const std::uint64_t settled_before = me.settled;
      // Where this class's targets go, per move length (axes 1..4).
      std::vector<Entry>* into[5] = {};
      for (const Entry& e : list) {
        if ((++n & 1023) == 0 && ctl.poll()) {
          stopped = true;
          break;
        }
        ++me.taken;
        const Block& b = slabs_.of_tile(e.tile);
        Word& s = settled_[b.store + (e.tile - b.lo)];
        const Word fresh = e.bits & ~s;
        if (!fresh) continue;
        s |= fresh;
        me.settled += static_cast<std::uint64_t>(std::popcount(fresh));
        if (q_.keep_path) record(b, e.tile, fresh, key);
        if (field_run_)
          distances_.write(layout_, slabs_.block_index_of_tile(e.tile), e.tile, fresh,
                           static_cast<float>(key.value()));
        if (e.tile == goal_tile_ && (fresh & goal_bit_)) {
          me.goal_hit = true;
          me.goal_key = key;
        }
        expand(me, b, e.tile, fresh, key, into);
      }
      // Classes that settled a state, a set independent of ranks and threads (a class whose
      // states all settled earlier elsewhere is not counted).
      if (me.settled > settled_before) me.processed.push_back(key);
      me.recycle(std::move(list));
    }
  }
  void receive(int id, const Superstep&) override {
    Thread& me = threads_[id];
    for (const Thread& t : threads_)
      for (const ClassEntry& e : t.out_local[id]) file(me, e);
    for (const ClassEntry& e : inbox_[id]) file(me, e);
  }
  StepReport report(int id) const override {
    const Thread& me = threads_[id];
    StepReport r;
    r.fresh = me.settled - me.settled_at_step;
    r.pending = me.pending_entries();
    r.list_bytes = list_bytes(me);
    if (!me.pending.empty()) r.next_key = me.pending.begin()->first.value();
    r.goal = me.goal_hit;
    r.active = me.taken;
    return r;
  }
  std::uint64_t list_bytes(int id) const override { return list_bytes(threads_[id]); }
  void next_step(int id) override {
    Thread& me = threads_[id];
    me.clear();
    me.taken = 0;
    me.settled_at_step = me.settled;
  }
  void send_halo(std::vector<std::vector<std::byte>>& to) override {
    HaloSwap<ClassEntry>::send(threads_, slabs_.peers.size(), to);
  }
  void receive_halo(const std::vector<std::vector<std::byte>>& from) override {
    halo_.receive(slabs_, from, inbox_);
  }
  // The next bucket: the floor of the smallest class pending anywhere.
  double next_key(const Decision& d) const override { return std::floor(d.sum.next_key); }
  const char* progress_unit() const override { return "cost"; }
  double progress_value(const Totals& t) const override { return t.key; }

  std::uint64_t expanded() const override { return sum_over(threads_, &Thread::settled); }
  std::uint64_t generated() const override { return sum_over(threads_, &Thread::generated); }
  void finish(Result& res, const Totals& totals, bool solved) override {
    std::vector<ClassKey> classes;
    for (const Thread& t : threads_)
      classes.insert(classes.end(), t.processed.begin(), t.processed.end());
    res.counters.peak_states = res.counters.expanded;
    res.counters.peak_open = totals.peak_pending;
    res.figures.levels = distinct_classes(classes);
    res.figures.buckets = totals.steps;
    res.figures.reached = res.counters.expanded;
    if (solved) {
      const ClassKey goal = goal_class();
      res.cost = goal.value();
      res.hops = static_cast<std::uint64_t>(goal.hops);
      if (q_.keep_path) {
        res.path = walk_back(goal);
        res.hops = res.path.size() - 1;
      }
    }
  }

  // The state after the last bucket (dense_checkpoint.hpp): the totals in the order of
  // format 1 (bucket, buckets, settled, peak pending, list peak), then the store and lists.
  void save(checkpoint::Writer& w, const Totals& totals) const override {
    w.put(totals.key);
    w.put(totals.steps);
    w.put(totals.reached);
    w.put(totals.peak_pending);
    w.put(totals.list_peak);
    w.put_array(std::span<const Word>(settled_.data(), settled_.size()));
    w.put_array(std::span<const Word>(keys_.data(), keys_.size()));
    for (const Thread& t : threads_) {
      w.put(t.settled);
      w.put(t.generated);
      w.put_array(t.processed);
      w.put<std::uint64_t>(t.pending.size());
      for (const auto& [key, list] : t.pending) {
        w.put(key);
        w.put_array(list);
      }
    }
  }

  // The state saved by save() (InputError if it is refused).
  void restore(checkpoint::Reader& r, Totals& totals) override {
    totals.key = r.get<double>();
    totals.steps = r.get<std::uint64_t>();
    totals.reached = r.get<std::uint64_t>();
    totals.peak_pending = r.get<std::uint64_t>();
    totals.list_peak = r.get<std::uint64_t>();
    r.get_array(std::span<Word>(settled_.data(), settled_.size()));
    r.get_array(std::span<Word>(keys_.data(), keys_.size()));
    for (Thread& t : threads_) {
      t.settled = t.settled_at_step = r.get<std::uint64_t>();
      t.generated = r.get<std::uint64_t>();
      // (The merge windows start empty, so no epoch of theirs needs restoring.)
      r.get_array(t.processed);
      const auto classes = r.get<std::uint64_t>();
      for (std::uint64_t c = 0; c < classes; ++c) {
        const auto key = r.get<ClassKey>();
        // (A path of more moves than the lattice has free states cannot be a shortest one.)
        if (key.ones < 0 || key.root2 < 0 || key.root3 < 0 || key.hops < 0 ||
            static_cast<std::uint64_t>(key.hops) > free_states_ || t.pending.count(key))
          r.fail("lists a class twice or a negative cost (damaged)");
        std::vector<Entry>& list = t.pending[key];
        r.get_array(list);
        for (const Entry& e : list)
          if (e.tile >= layout_.tile_count() || slabs_.of_tile(e.tile).rank != slabs_.rank ||
              slabs_.of_tile(e.tile).thread != t.id)
            r.fail("lists a pending tile this thread does not hold (damaged)");
      }
    }
  }

 private:
  // Merges a class's targets into one entry per tile while one source class is expanded:
  // without it a tile reached from each of its neighbours is listed once per neighbour (6D,
  // extent 11: sorting those lists was 47% of the run). A direct-mapped window of recent
  // tiles per target list; a new source class starts a new epoch.
  struct Dedup {
    static constexpr int kBits = 12;
    // One 16-byte slot per hash: a look-up touches one cache line, not three arrays.
    struct Slot {
      std::uint64_t tile = 0;
      std::uint32_t index = 0, epoch = 0;
    };
    std::vector<Slot> slots = std::vector<Slot>(std::size_t{1} << kBits);
    void add(std::vector<Entry>& list, std::uint64_t u, Word bits, std::uint32_t now) {
      Slot& s = slots[(u * 0x9E3779B97F4A7C15ULL) >> (64 - kBits)];
      if (s.epoch == now && s.tile == u) {
        list[s.index].bits |= bits;
        return;
      }
      s = {u, static_cast<std::uint32_t>(list.size()), now};
      list.push_back({u, bits});
    }
  };

  struct alignas(64) Thread
      : Outboxes<ClassEntry> {  // a cache line apart: each thread writes its own counters
    std::map<ClassKey, std::vector<Entry>> pending;
    Dedup dedup[5];  // per move length
    std::uint32_t epoch = 0;
    int id = 0;
    std::vector<std::vector<Entry>> spare;  // emptied lists, reused for new classes
    std::vector<ClassKey> processed;        // the classes this thread took, in order
    // States settled, and settled before this bucket (its report's fresh states are the
    // difference).
    std::uint64_t settled = 0, generated = 0, settled_at_step = 0;
    bool goal_hit = false;
    ClassKey goal_key;
    std::uint64_t taken = 0;  // class entries taken in this bucket

    std::uint64_t pending_entries() const {
      std::uint64_t n = 0;
      for (const auto& [key, list] : pending) n += list.size();
      return n;
    }
    void recycle(std::vector<Entry>&& list) {
      list.clear();
      if (spare.size() < 64) spare.push_back(std::move(list));
    }
    std::vector<Entry>& class_list(const ClassKey& key) {
      auto [it, inserted] = pending.try_emplace(key);
      if (inserted && !spare.empty()) {
        it->second = std::move(spare.back());
        spare.pop_back();
      }
      return it->second;
    }
  };

  static std::uint64_t list_bytes(const Thread& t) {
    std::uint64_t n = t.capacity_bytes();
    for (const auto& [key, list] : t.pending) n += list.capacity() * sizeof(Entry) + 64;
    for (const auto& list : t.spare) n += list.capacity() * sizeof(Entry);
    return n;
  }
  void record(const Block& b, std::uint64_t tile, Word fresh, const ClassKey& key) {
    if (!key.packable())
      throw RunError(
          "dense Dijkstra: a path cost beyond 65,535 moves of one kind cannot be "
          "recorded for --path; run without --path");
    std::uint64_t* k = keys_.data() + (b.store + (tile - b.lo)) * 64;
    for (Word w = fresh; w; w &= w - 1) k[std::countr_zero(w)] = key.packed() + 1;
  }

  // A target in the source's block, or in another block this thread owns, goes into its
  // class's list unless already settled; any other, to an outbox for its block's owner.
  void expand(Thread& me, const Block& b, std::uint64_t tile, Word fresh, const ClassKey& key,
              std::vector<Entry>** into) {
    int t[kMaxDims];
    layout_.tile_coords(tile, t);
    FreeWindows::At at;
    windows_.locate(t, at);
    me.generated += kernel_.template expand<true>(
        fresh, at, windows_.stride(), stride_.data(),
        [&](std::int64_t delta, Word bits, int axes) __attribute__((always_inline)) {
          const std::uint64_t u = tile + static_cast<std::uint64_t>(delta);
          if (u >= b.lo && u < b.hi) {
            const Word open = bits & ~settled_[b.store + (u - b.lo)];
            if (!open) return;
            if (!into[axes]) into[axes] = &me.class_list(key.after(axes));
            me.dedup[axes].add(*into[axes], u, open, me.epoch);
            return;
          }
          const Block& nb = slabs_.of_tile(u);
          if (nb.rank == slabs_.rank && nb.thread == me.id) {
            // This thread's too: straight into the class.
            const Word open = bits & ~settled_[nb.store + (u - nb.lo)];
            if (!open) return;
            if (!into[axes]) into[axes] = &me.class_list(key.after(axes));
            me.dedup[axes].add(*into[axes], u, open, me.epoch);
            return;
          }
          const ClassEntry e{u, bits, key.after(axes)};
          if (nb.rank == slabs_.rank)
            me.out_local[nb.thread].push_back(e);
          else
            me.to_peer(slabs_.peer_slot[nb.rank], e);
        });
  }

  void file(Thread& me, const ClassEntry& e) {
    const Block& b = slabs_.of_tile(e.tile);
    const Word open = e.bits & ~settled_[b.store + (e.tile - b.lo)];
    if (open) me.class_list(e.key).push_back({e.tile, open});
  }

  // Classes processed anywhere (a class spanning several slabs is processed by each).
  // The classes settled anywhere, counted once: each rank sends its own set (its threads'
  // lists merged first, so the gather grows with ranks, not with ranks x threads).
  std::uint64_t distinct_classes(std::vector<ClassKey> mine) {
    std::sort(mine.begin(), mine.end());
    mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    const auto all =
        tr_.allgather(std::as_bytes(std::span<const ClassKey>(mine.data(), mine.size())));
    std::vector<ClassKey> every(all.size() / sizeof(ClassKey));
    if (!every.empty()) std::memcpy(every.data(), all.data(), every.size() * sizeof(ClassKey));
    std::sort(every.begin(), every.end());
    return static_cast<std::uint64_t>(std::unique(every.begin(), every.end()) - every.begin());
  }

  // The goal's class, from the rank that settled it.
  ClassKey goal_class() {
    struct Found {
      std::int32_t hit;
      ClassKey key;
    } mine{0, {}};
    for (const Thread& t : threads_)
      if (t.goal_hit) mine = {1, t.goal_key};
    const auto all = tr_.allgather(std::as_bytes(std::span<const Found>(&mine, 1)));
    for (std::size_t i = 0; i + sizeof(Found) <= all.size(); i += sizeof(Found)) {
      Found f;
      std::memcpy(&f, all.data() + i, sizeof f);
      if (f.hit) return f.key;
    }
    throw std::logic_error("dense Dijkstra: goal settled but no rank holds its class");
  }

  // From the goal back to the start: the first move, in the fixed order, from a state whose
  // class is this state's class less that move.
  std::vector<std::vector<int>> walk_back(ClassKey at_key) {
    const auto offsets = move_offsets(D, q_.connectivity);
    std::vector<std::vector<int>> path{q_.goal};
    int x[kMaxDims];
    std::copy(q_.goal.begin(), q_.goal.end(), x);
    while (at_key.hops > 0) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < offsets.size() && !slabs_.empty(); ++j) {
        int y[kMaxDims], axes = 0;
        bool inside = true;
        for (int a = 0; a < D; ++a) {
          y[a] = x[a] - offsets[j][a];
          axes += offsets[j][a] != 0;
          inside = inside && y[a] >= 0 && y[a] < layout_.extent();
        }
        if (!inside) continue;
        const std::uint64_t tile = layout_.tile_of(std::span<const int>(y, D));
        if (!slabs_.holds_tile(tile)) continue;
        const Block& b = slabs_.of_tile(tile);
        const std::uint64_t stored =
            keys_[(b.store + (tile - b.lo)) * 64 + layout_.bit_of(std::span<const int>(y, D))];
        if (stored == 0) continue;
        ClassKey before;
        before.ones = static_cast<std::int32_t>((stored - 1) & 0xFFFF);
        before.root2 = static_cast<std::int32_t>(((stored - 1) >> 16) & 0xFFFF);
        before.root3 = static_cast<std::int32_t>(((stored - 1) >> 32) & 0xFFFF);
        before.hops = static_cast<std::int32_t>(((stored - 1) >> 48) & 0xFFFF);
        if (!(before.after(axes) == at_key) || !legal_move(field_, y, offsets[j])) continue;
        best = static_cast<double>(j);
        break;
      }
      tr_.min(std::span<double>(&best, 1));
      if (!std::isfinite(best))
        throw RunError("dense Dijkstra: the walk back found no predecessor");
      const auto& o = offsets[static_cast<std::size_t>(best)];
      int axes = 0;
      for (int a = 0; a < D; ++a) {
        x[a] -= o[a];
        axes += o[a] != 0;
      }
      // The predecessor's class: this one less the move.
      const LatticeCost step = LatticeCost::for_axes(axes);
      at_key = {at_key.ones - step.ones, at_key.root2 - step.root2, at_key.root3 - step.root3,
                at_key.hops - 1};
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
  ZeroedWords settled_, keys_;
  std::vector<Thread> threads_;
  std::vector<std::vector<ClassEntry>> inbox_;  // per thread: what the neighbouring ranks sent it
  HaloSwap<ClassEntry> halo_;
  std::uint64_t goal_tile_ = 0;
  Word goal_bit_ = 0;
  DistanceWriter<float> distances_;  // a distance field's part (Query::distances)
};

}  // namespace hpcplan::dense::detail
