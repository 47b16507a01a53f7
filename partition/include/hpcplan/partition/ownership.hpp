#pragma once
// Which rank owns a lattice state. Two schemes:
//  - hash (seed 002, Algorithm 3): SplitMix64 of its packed key modulo P, or, with a
//    coarsening shift k > 0, of the key with the low k bits of every coordinate cleared, i.e.
//    of the coarse cell (c1 >> k, ..., cd >> k) as in Abstract Zobrist Hashing. Coarse cells of
//    2^k states per axis stay on one rank, so fewer moves leave their rank, at the price of
//    coarser load balance. In 6D a state has 728 neighbours, and most of them differ from it on
//    several axes, so even k = 2 leaves about half of them elsewhere.
//  - slabs of width w along the first axis, dealt round the ranks: the owner is
//    (c1 / w) mod P. Only the moves that cross a slab face leave the rank (6D, extent 11,
//    w = 6, two ranks: 8 bytes sent per expansion against 244 with the hash), and the owner
//    is one table look-up.
//    The balance is the slabs': a search that starts in one corner reaches the far slabs late.
//  - prefix cuts: the states ordered by their first two coordinates, p = c1 * extent + c2,
//    and cut at P - 1 positions, rank r owning cuts[r-1] <= p < cuts[r]. A contiguous cut
//    like two slabs (a plane c1 = k with one step in c2), but placed to 1/extent^2 of the
//    states, so it can split a search's expansions evenly (balanced_prefix_cuts in
//    rank_simulation.hpp finds the positions from a serial run's expansions).
//    Slabs and cuts: a state whose first coordinate and both its neighbours lie in slabs of one
//    owner keeps its whole unit neighbourhood on that rank (holds_neighbourhood), so its successors
//    need no owner look-up at all: most states of a wide slab.
#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "hpcplan/graph/packed_key.hpp"

namespace hpcplan::partition {

template <int W>
class Ownership {
 public:
  // `slab_width` > 0 selects slabs (and ignores `coarsen_shift`); `extent` is the lattice's
  // per-axis extent, which slabs need.
  // Non-empty `prefix_cuts` (P - 1 ascending positions in 1..prefix_count - 1) select prefix
  // cuts instead of both.
  Ownership(const KeyLayout& layout, int ranks, int coarsen_shift, int slab_width = 0,
            int extent = 0, const std::vector<std::uint32_t>& prefix_cuts = {})
      : ranks_(ranks),
        shift_(slab_width > 0 || !prefix_cuts.empty() ? 0 : coarsen_shift),
        slab_width_(prefix_cuts.empty() ? slab_width : 0),
        prefix_cuts_(prefix_cuts),
        axis_word_(layout.word_of(0)),
        axis_shift_(layout.shift_of(0)),
        axis_mask_(layout.mask()),
        second_word_(layout.word_of(layout.dims() > 1 ? 1 : 0)),
        second_shift_(layout.shift_of(layout.dims() > 1 ? 1 : 0)),
        second_mask_(layout.dims() > 1 ? layout.mask() : 0),
        second_extent_(layout.dims() > 1 ? extent : 1) {
    mask_.fill(~0ULL);
    const int cleared = shift_ < layout.bits() ? shift_ : layout.bits();
    const std::uint64_t low = cleared >= 64 ? ~0ULL : ((1ULL << cleared) - 1);
    for (int a = 0; a < layout.dims(); ++a)
      mask_[layout.word_of(a)] &= ~(low << layout.shift_of(a));
    if (slab_width_ > 0 && extent < 1)
      throw std::logic_error("Ownership: slabs need the lattice's extent");
    if (slab_width_ > 0) {
      for (int c = 0; c < extent; ++c) slab_owner_.push_back((c / slab_width_) % ranks_);
      for (int c = 0; c < extent; ++c) {
        const int below = c > 0 ? slab_owner_[c - 1] : slab_owner_[c];
        const int above = c + 1 < extent ? slab_owner_[c + 1] : slab_owner_[c];
        slab_interior_.push_back(below == slab_owner_[c] && above == slab_owner_[c]);
      }
    }
    if (!prefix_cuts_.empty()) build_prefix_tables(extent);
  }

  // How many prefix positions a lattice of this extent has (extent^2; extent in 1D).
  static std::uint32_t prefix_count(const KeyLayout& layout, int extent) {
    return static_cast<std::uint32_t>(extent) *
           static_cast<std::uint32_t>(layout.dims() > 1 ? extent : 1);
  }

  int operator()(const PackedKey<W>& s) const {
    if (ranks_ == 1) return 0;
    if (slab_width_ > 0) return slab_owner_[(s.w[axis_word_] >> axis_shift_) & axis_mask_];
    if (!prefix_owner_.empty()) return prefix_owner_[prefix(s)];
    return static_cast<int>(hash_key(cell(s)) % static_cast<std::uint64_t>(ranks_));
  }
  // Whether every state within one step of s on every axis (s's unit neighbourhood) has s's
  // owner. Conservative: false says nothing.
  bool holds_neighbourhood(const PackedKey<W>& s) const {
    if (ranks_ == 1) return true;
    if (slab_width_ > 0) return slab_interior_[(s.w[axis_word_] >> axis_shift_) & axis_mask_];
    if (!prefix_owner_.empty()) return prefix_interior_[prefix(s)];
    return false;
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
  std::uint32_t prefix(const PackedKey<W>& s) const {
    const auto c1 = static_cast<std::uint32_t>((s.w[axis_word_] >> axis_shift_) & axis_mask_);
    const auto c2 = static_cast<std::uint32_t>((s.w[second_word_] >> second_shift_) & second_mask_);
    return c1 * static_cast<std::uint32_t>(second_extent_) + c2;
  }

  void build_prefix_tables(int extent) {
    if (extent < 1) throw std::logic_error("Ownership: prefix cuts need the lattice's extent");
    if (static_cast<int>(prefix_cuts_.size()) != ranks_ - 1)
      throw std::logic_error("Ownership: prefix cuts need one position fewer than ranks");
    const int e2 = second_extent_;
    const std::uint32_t n = static_cast<std::uint32_t>(extent) * static_cast<std::uint32_t>(e2);
    for (std::size_t j = 0; j < prefix_cuts_.size(); ++j)
      if (prefix_cuts_[j] < 1 || prefix_cuts_[j] >= n ||
          (j > 0 && prefix_cuts_[j] <= prefix_cuts_[j - 1]))
        throw std::logic_error("Ownership: prefix cuts must ascend strictly inside the lattice");
    prefix_owner_.resize(n);
    for (std::uint32_t p = 0; p < n; ++p)
      prefix_owner_[p] = static_cast<int>(
          std::upper_bound(prefix_cuts_.begin(), prefix_cuts_.end(), p) - prefix_cuts_.begin());
    // Interior: the 3 x 3 block of prefixes around (c1, c2), clamped to the lattice, has one
    // owner (moves change each coordinate by at most one).
    prefix_interior_.resize(n);
    for (int a = 0; a < extent; ++a)
      for (int b = 0; b < e2; ++b) {
        const int o = prefix_owner_[a * e2 + b];
        bool same = true;
        for (int da = -1; da <= 1; ++da)
          for (int db = -1; db <= 1; ++db) {
            const int x = std::clamp(a + da, 0, extent - 1), y = std::clamp(b + db, 0, e2 - 1);
            same = same && prefix_owner_[x * e2 + y] == o;
          }
        prefix_interior_[a * e2 + b] = same;
      }
  }

  int ranks_;
  int shift_;
  int slab_width_;
  std::vector<std::uint32_t> prefix_cuts_;
  int axis_word_, axis_shift_;
  std::uint64_t axis_mask_;
  int second_word_, second_shift_;
  std::uint64_t second_mask_;
  int second_extent_;
  std::vector<int> prefix_owner_;      // by prefix position
  std::vector<char> prefix_interior_;  // by prefix position: its 3 x 3 block one owner's
  std::vector<int> slab_owner_;        // by first coordinate
  std::vector<char> slab_interior_;    // by first coordinate: it and both neighbours one owner's
  std::array<std::uint64_t, W> mask_{};
};

}  // namespace hpcplan::partition
