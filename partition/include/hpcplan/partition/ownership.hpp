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
//    A state whose first coordinate and both its neighbours lie in slabs of one owner keeps its
//    whole unit neighbourhood on that rank (holds_neighbourhood), so its successors need no
//    owner look-up at all: most states of a wide slab.
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
  Ownership(const KeyLayout& layout, int ranks, int coarsen_shift, int slab_width = 0,
            int extent = 0)
      : ranks_(ranks),
        shift_(slab_width > 0 ? 0 : coarsen_shift),
        slab_width_(slab_width),
        axis_word_(layout.word_of(0)),
        axis_shift_(layout.shift_of(0)),
        axis_mask_(layout.mask()) {
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
  }

  int operator()(const PackedKey<W>& s) const {
    if (ranks_ == 1) return 0;
    if (slab_width_ > 0) return slab_owner_[(s.w[axis_word_] >> axis_shift_) & axis_mask_];
    return static_cast<int>(hash_key(cell(s)) % static_cast<std::uint64_t>(ranks_));
  }
  // Whether every state within one step of s on every axis (s's unit neighbourhood) has s's
  // owner. Conservative: false says nothing.
  bool holds_neighbourhood(const PackedKey<W>& s) const {
    if (ranks_ == 1) return true;
    if (slab_width_ > 0) return slab_interior_[(s.w[axis_word_] >> axis_shift_) & axis_mask_];
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

 private:
  int ranks_;
  int shift_;
  int slab_width_;
  int axis_word_, axis_shift_;
  std::uint64_t axis_mask_;
  std::vector<int> slab_owner_;      // by first coordinate
  std::vector<char> slab_interior_;  // by first coordinate: it and both neighbours one owner's
  std::array<std::uint64_t, W> mask_{};
};

}  // namespace hpcplan::partition
