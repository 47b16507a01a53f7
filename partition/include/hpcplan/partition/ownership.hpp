#pragma once
// Which rank owns a lattice state: SplitMix64 of its packed key modulo P (seed 002,
// Algorithm 3), or, with a coarsening shift k > 0, of the key with the low k bits of every
// coordinate cleared, i.e. of the coarse cell (c1 >> k, ..., cd >> k) as in Abstract Zobrist
// Hashing. Coarse cells of 2^k states per axis stay on one rank, so most moves are local and
// fewer records travel, at the price of coarser load balance.
#include <array>
#include <cstdint>

#include "hpcplan/graph/packed_key.hpp"

namespace hpcplan::partition {

template <int W>
class Ownership {
 public:
  Ownership(const KeyLayout& layout, int ranks, int coarsen_shift)
      : ranks_(ranks), shift_(coarsen_shift) {
    mask_.fill(~0ULL);
    const int cleared = coarsen_shift < layout.bits() ? coarsen_shift : layout.bits();
    const std::uint64_t low = cleared >= 64 ? ~0ULL : ((1ULL << cleared) - 1);
    for (int a = 0; a < layout.dims(); ++a)
      mask_[layout.word_of(a)] &= ~(low << layout.shift_of(a));
  }

  int operator()(const PackedKey<W>& s) const {
    if (ranks_ == 1) return 0;
    return static_cast<int>(hash_key(cell(s)) % static_cast<std::uint64_t>(ranks_));
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

 private:
  int ranks_;
  int shift_;
  std::array<std::uint64_t, W> mask_{};
};

}  // namespace hpcplan::partition
