#pragma once
// SplitMix64: the finaliser (seed 002, Algorithm 3) used as the state hash and ownership
// function, and the full generator (finaliser over a Weyl sequence) used to derive seeds.
// C++17 and HPCPLAN_HD: the fluid's CUDA kernels draw the same numbers from the same code.
#include <cstdint>

#include "hpcplan/core/portable.hpp"

namespace hpcplan {

// The seed's listing prints the first multiplier with a stray digit; this is the
// published SplitMix64 constant, which the listing clearly intends.
HPCPLAN_HD constexpr std::uint64_t splitmix64_mix(std::uint64_t x) noexcept {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Deterministic stream of 64-bit values; identical on every platform and rank.
class SplitMix64 {
 public:
  HPCPLAN_HD explicit constexpr SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
  HPCPLAN_HD constexpr std::uint64_t next() noexcept {
    state_ += 0x9e3779b97f4a7c15ULL;
    return splitmix64_mix(state_);
  }
  // Uniform double in [0, 1) from the top 53 bits.
  HPCPLAN_HD constexpr double next_unit() noexcept {
    return static_cast<double>(next() >> 11) * 0x1.0p-53;
  }
  // Uniform integer in [0, n); n > 0. Lemire's multiply-shift, bias negligible for n << 2^64.
  std::uint64_t next_below(std::uint64_t n) noexcept {
    return static_cast<std::uint64_t>((static_cast<unsigned __int128>(next()) * n) >> 64);
  }

 private:
  std::uint64_t state_;
};

}  // namespace hpcplan
