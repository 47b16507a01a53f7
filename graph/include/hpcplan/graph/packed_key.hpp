#pragma once
// Lattice states packed into W 64-bit words (W = 1, 2 or 4), so that a state is one or two
// machine words for common problems and hashing, equality and neighbour steps are word ops.
// Each axis gets a fixed bit field that never straddles a word; a neighbour step is a plain
// add of a precomputed delta, safe because the graph checks bounds before stepping.
#include <array>
#include <bit>
#include <cstdint>
#include <span>

#include "hpcplan/core/splitmix64.hpp"

namespace hpcplan {

inline constexpr int kMaxDims = 16;
inline constexpr int kMaxExtent = 65535;

template <int W>
struct PackedKey {
  std::array<std::uint64_t, W> w{};
  // Word-wise on purpose: the defaulted comparison of std::array lowers to a libc memcmp
  // call, which took two thirds of search time at the hash map's probes.
  friend constexpr bool operator==(const PackedKey& a, const PackedKey& b) {
    bool equal = true;
    for (int i = 0; i < W; ++i) equal &= a.w[i] == b.w[i];
    return equal;
  }
};

// SplitMix64 of the packed key (seed 002, Algorithm 3); wider keys fold word by word.
template <int W>
constexpr std::uint64_t hash_key(const PackedKey<W>& k) noexcept {
  std::uint64_t h = splitmix64_mix(k.w[0]);
  for (int i = 1; i < W; ++i) h = splitmix64_mix(h ^ k.w[i]);
  return h;
}

// A one-word key's packed bits as an index into a dense table (search/stamped_dense_map.hpp):
// below 2^(bits x dims) for a lattice whose layout fits one word.
constexpr std::uint64_t dense_index(const PackedKey<1>& k) noexcept {
  return k.w[0];
}

template <int W>
struct PackedKeyHash {
  std::size_t operator()(const PackedKey<W>& k) const noexcept { return hash_key(k); }
};

class KeyLayout {
 public:
  KeyLayout(int dims, int extent)
      : dims_(dims),
        bits_(extent <= 2 ? 1 : std::bit_width(static_cast<unsigned>(extent - 1))),
        axes_per_word_(64 / bits_),
        words_((dims + axes_per_word_ - 1) / axes_per_word_) {
    for (int a = 0; a < dims; ++a) {
      word_[a] = a / axes_per_word_;
      shift_[a] = (a % axes_per_word_) * bits_;
    }
  }

  int dims() const { return dims_; }
  int bits() const { return bits_; }
  int words() const { return words_; }
  int word_of(int axis) const { return word_[axis]; }
  int shift_of(int axis) const { return shift_[axis]; }
  std::uint64_t mask() const { return bits_ == 64 ? ~0ULL : ((1ULL << bits_) - 1); }
  // How many dense indices (dense_index) a one-word layout spans: 2^(bits x dims).
  std::uint64_t dense_index_bound() const { return std::uint64_t{1} << (bits_ * dims_); }

  template <int W>
  PackedKey<W> pack(std::span<const int> coords) const {
    PackedKey<W> k;
    for (int a = 0; a < dims_; ++a)
      k.w[word_[a]] |= static_cast<std::uint64_t>(coords[a]) << shift_[a];
    return k;
  }
  template <int W>
  void unpack(const PackedKey<W>& k, int* coords) const {
    const std::uint64_t m = mask();
    for (int a = 0; a < dims_; ++a) coords[a] = static_cast<int>((k.w[word_[a]] >> shift_[a]) & m);
  }
  // The word delta that adds `step` (+1 or -1) to `axis`; adding deltas is modular, so a
  // negative step is the two's complement of the positive one.
  template <int W>
  void add_step(std::array<std::uint64_t, W>& delta, int axis, int step) const {
    const std::uint64_t unit = 1ULL << shift_[axis];
    delta[word_[axis]] += step > 0 ? unit : (~unit + 1);
  }

 private:
  int dims_;
  int bits_;
  int axes_per_word_;
  int words_;
  std::array<int, kMaxDims> word_{};
  std::array<int, kMaxDims> shift_{};
};

}  // namespace hpcplan
