#pragma once
// Which rank owns a lattice state. Two schemes:
//  - hash (seed 002, Algorithm 3): SplitMix64 of its packed key modulo P, or, with a
//    coarsening shift k > 0, of the key with the low k bits of every coordinate cleared, i.e.
//    of the coarse cell (c1 >> k, ..., cd >> k) as in Abstract Zobrist Hashing. Coarse cells of
//    2^k states per axis stay on one rank, so fewer moves leave their rank, at the price of
//    coarser load balance. In 6D a state has 728 neighbours, and most of them differ from it on
//    several axes, so even k = 2 leaves about half of them elsewhere.
//  - slabs of width w along the slab axis (below), dealt round the ranks: the owner is
//    (a / w) mod P for the state's coordinate a on that axis. Only the moves that cross a slab
//    face leave the rank (6D, extent 11, w = 6, two ranks: 8 bytes sent per expansion against
//    244 with the hash), and the owner is one table look-up.
//    The balance is the slabs': a search that starts in one corner reaches the far slabs late.
//  - prefix cuts: the states ordered by their coordinates on the two cut axes (below),
//    p = a * extent + b, and cut at P - 1 positions, rank r owning cuts[r-1] <= p < cuts[r].
//    A contiguous cut like two slabs (a plane a = k with one step in b), but placed to
//    1/extent^2 of the states, so it can split a search's expansions evenly
//    (balanced_prefix_cuts in rank_simulation.hpp finds the positions from a serial run's
//    expansions). The owner only grows with the position, so the states between two positions
//    of one owner are that owner's too.
//  The slab axis is the last one, and the cut axes the last two (last first): the packed key
//  keeps the last axis in its highest bits, so a slab or a cut's side is one contiguous run of
//  keys, and of a dense store's entries. Along the first axis (the lowest bits) every cache line
//  of the store held states of both ranks, each rank using part of every line it fetched: at
//  8D and 10D the ranks reached 78% and 68-72% of the machine's ceiling that way, 90% and 81%
//  along the last axis, in alternated jobs (docs/PERFORMANCE.md, issue 17).
//  Slabs and cuts: a state whose 3 x 3 block of (a, b) neighbours has one owner keeps its
//  whole unit neighbourhood on its rank (holds_neighbourhood), so its successors need no owner
//  look-up: most states of a wide slab or a cut's side. Slabs decide it from a table by a;
//  cuts from the block's first and last positions. Neither keeps anything of size extent^2.
#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "hpcplan/graph/packed_key.hpp"

namespace hpcplan::partition {

// The axis slabs are cut along, and the two axes whose coordinates (a, b) order the states
// for prefix cuts (in 1D the second is the first again, and b counts as 0).
inline int slab_axis(int dims) {
  return dims - 1;
}
inline std::array<int, 2> cut_axes(int dims) {
  return {dims - 1, dims > 1 ? dims - 2 : 0};
}

// How many positions a * extent + b a lattice has (extent^2; extent in 1D, where b = 0).
inline std::uint64_t prefix_positions(int dims, int extent) {
  return static_cast<std::uint64_t>(extent) * static_cast<std::uint64_t>(dims > 1 ? extent : 1);
}

// The index of the first cut that is not strictly above the one before it and inside
// 1..positions - 1, or the number of cuts when all are (so every rank owns some position).
inline std::size_t first_misplaced_cut(const std::vector<std::uint32_t>& cuts,
                                       std::uint64_t positions) {
  for (std::size_t j = 0; j < cuts.size(); ++j)
    if (cuts[j] < 1 || cuts[j] >= positions || (j > 0 && cuts[j] <= cuts[j - 1])) return j;
  return cuts.size();
}

template <int W>
class Ownership {
 public:
  // `slab_width` > 0 selects slabs (and ignores `coarsen_shift`); non-empty `prefix_cuts`
  // (P - 1 positions ascending strictly inside 1..positions - 1) select cuts instead of both.
  // `extent`, the lattice's per-axis extent, is needed by both (and by position()).
  Ownership(const KeyLayout& layout, int ranks, int coarsen_shift, int slab_width = 0,
            int extent = 0, const std::vector<std::uint32_t>& prefix_cuts = {})
      : ranks_(ranks),
        shift_(slab_width > 0 || !prefix_cuts.empty() ? 0 : coarsen_shift),
        slab_width_(prefix_cuts.empty() ? slab_width : 0),
        prefix_cuts_(prefix_cuts),
        first_word_(layout.word_of(cut_axes(layout.dims())[0])),
        first_shift_(layout.shift_of(cut_axes(layout.dims())[0])),
        first_mask_(layout.mask()),
        second_word_(layout.word_of(cut_axes(layout.dims())[1])),
        second_shift_(layout.shift_of(cut_axes(layout.dims())[1])),
        second_mask_(layout.dims() > 1 ? layout.mask() : 0),
        extent_(extent),
        second_extent_(layout.dims() > 1 ? extent : 1) {
    mask_.fill(~0ULL);
    const int cleared = shift_ < layout.bits() ? shift_ : layout.bits();
    const std::uint64_t low = cleared >= 64 ? ~0ULL : ((1ULL << cleared) - 1);
    for (int a = 0; a < layout.dims(); ++a)
      mask_[layout.word_of(a)] &= ~(low << layout.shift_of(a));
    if ((slab_width_ > 0 || !prefix_cuts_.empty()) && extent < 1)
      throw std::logic_error("Ownership: slabs and cuts need the lattice's extent");
    if (slab_width_ > 0) build_slab_tables();
    if (!prefix_cuts_.empty()) check_cuts();
  }

  int operator()(const PackedKey<W>& s) const {
    if (ranks_ == 1) return 0;
    if (slab_width_ > 0) return slab_owner_[first(s)];
    if (!prefix_cuts_.empty()) return owner_at(position(s));
    return static_cast<int>(hash_key(cell(s)) % static_cast<std::uint64_t>(ranks_));
  }
  // Whether every state within one step of s on every axis (s's unit neighbourhood) has s's
  // owner. Conservative: false says nothing.
  bool holds_neighbourhood(const PackedKey<W>& s) const {
    if (ranks_ == 1) return true;
    if (slab_width_ > 0) return slab_interior_[first(s)];
    if (prefix_cuts_.empty()) return false;
    // The block's positions all lie between its first and last one (clamped to the lattice),
    // and the owner only grows with the position.
    const std::uint32_t a = first(s), b = second(s);
    const std::uint32_t e2 = static_cast<std::uint32_t>(second_extent_);
    const std::uint32_t lo = (a > 0 ? a - 1 : 0) * e2 + (b > 0 ? b - 1 : 0);
    const std::uint32_t hi =
        std::min(a + 1, static_cast<std::uint32_t>(extent_) - 1) * e2 + std::min(b + 1, e2 - 1);
    return owner_at(lo) == owner_at(hi);
  }
  // s's position a * extent + b on the cut axes (needs the extent given at construction).
  std::uint32_t position(const PackedKey<W>& s) const {
    return first(s) * static_cast<std::uint32_t>(second_extent_) + second(s);
  }

  // The coarse cell of s (s itself for k = 0): states of one cell share their owner, which
  // lets a caller skip the hash for neighbours that stay in the expanded state's cell.
  PackedKey<W> cell(const PackedKey<W>& s) const {
    PackedKey<W> coarse = s;
    for (int i = 0; i < W; ++i) coarse.w[i] &= mask_[i];
    return coarse;
  }

  int ranks() const { return ranks_; }
  int coarsen_shift() const { return shift_; }
  int slab_width() const { return slab_width_; }
  const std::vector<std::uint32_t>& prefix_cuts() const { return prefix_cuts_; }

 private:
  // The coordinates on the cut axes: a (also the slab axis) and b.
  std::uint32_t first(const PackedKey<W>& s) const {
    return static_cast<std::uint32_t>((s.w[first_word_] >> first_shift_) & first_mask_);
  }
  std::uint32_t second(const PackedKey<W>& s) const {
    return static_cast<std::uint32_t>((s.w[second_word_] >> second_shift_) & second_mask_);
  }
  int owner_at(std::uint32_t position) const {
    return static_cast<int>(std::upper_bound(prefix_cuts_.begin(), prefix_cuts_.end(), position) -
                            prefix_cuts_.begin());
  }

  void build_slab_tables() {
    for (int c = 0; c < extent_; ++c) slab_owner_.push_back((c / slab_width_) % ranks_);
    for (int c = 0; c < extent_; ++c) {
      const int below = slab_owner_[c > 0 ? c - 1 : c];
      const int above = slab_owner_[c + 1 < extent_ ? c + 1 : c];
      slab_interior_.push_back(below == slab_owner_[c] && above == slab_owner_[c]);
    }
  }

  void check_cuts() const {
    if (static_cast<int>(prefix_cuts_.size()) != ranks_ - 1)
      throw std::logic_error("Ownership: prefix cuts need one position fewer than ranks");
    const std::uint64_t n = static_cast<std::uint64_t>(extent_) * second_extent_;
    if (first_misplaced_cut(prefix_cuts_, n) != prefix_cuts_.size())
      throw std::logic_error("Ownership: prefix cuts must ascend strictly inside the lattice");
  }

  int ranks_;
  int shift_;
  int slab_width_;
  std::vector<std::uint32_t> prefix_cuts_;
  int first_word_, first_shift_;
  std::uint64_t first_mask_;
  int second_word_, second_shift_;
  std::uint64_t second_mask_;
  int extent_;
  int second_extent_;                // extent, or 1 in 1D (b = 0)
  std::vector<int> slab_owner_;      // by the coordinate on the slab axis
  std::vector<char> slab_interior_;  // by that coordinate: it and both neighbours one owner's
  std::array<std::uint64_t, W> mask_{};
};

}  // namespace hpcplan::partition
